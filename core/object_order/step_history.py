"""Step history: the buffers after any number of polygons, and the story of one pixel.

The lecture's z-buffer figure shows image memory and z-buffer after each
polygon.  Keeping a copy of both buffers per step would cost ``32 W H`` bytes a
step (10,000 polygons at 640 x 480: about 98 GB).  Instead a recording render
keeps what each polygon *did*: its fragments, each a pixel number, a depth
key (the window depth as the z-buffer's format stores it) and the depth-test
result (13 bytes).  The state after the first ``k``
polygons is rebuilt on demand by replaying the passed fragments of those
polygons into cleared buffers (compiled: :func:`core.object_order.kernels.raster.replay`),
with exactly the arithmetic of the render, so a rebuilt step is bit-identical
to rendering only those polygons.

Step ``k`` means "after ``k`` polygons": step 0 is the cleared buffers and
step ``n_steps`` the finished image.  The polygon drawn *at* step ``k`` (going
from step ``k`` to ``k + 1``) is polygon ``k`` of the drawing order.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.object_order import zbuffer
from core.object_order.blending import Blend, blend_over
from core.object_order.fragments import Fragments

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).


@dataclass(frozen=True)
class PixelEvent:
    """One fragment that reached the picked pixel.

    Attributes
    ----------
    polygon : its polygon's position in the drawing order (the buffers after it
        are step ``polygon + 1``).
    object_index : index of its object in ``scene.objects``.
    triangle_index : its face's triangle index within the object's mesh.
    z : its depth key: the window depth in [0, 1] as the z-buffer's format
        stores it (the window depth itself in ``float64``).
    distance : the same depth as distance along the viewing axis (scene units).
    stored_z : the depth key in the z-buffer it was compared with.
    stored_distance : the same as distance along the viewing axis (the far
        plane's distance while nothing has passed there).
    passed : the depth test's result, :func:`core.object_order.zbuffer.depth_test`
        of ``z`` against ``stored_z``; always True with the z-test switched off.
    color_before, color_after : (3,) image memory at the pixel before and after.
    blend : the blend terms, for a passed fragment of a transparent polygon.
    """

    polygon: int
    object_index: int
    triangle_index: int
    z: float
    distance: float
    stored_z: float
    stored_distance: float
    passed: bool
    color_before: np.ndarray
    color_after: np.ndarray
    blend: Blend | None


@dataclass(frozen=True, eq=False)
class StepHistory:
    """Every polygon's fragments, in drawing order, and what is needed to replay them.

    Attributes
    ----------
    width, height : image size in pixels.
    background : (3,) float64, the colour image memory is cleared to.
    near, far : the camera's near and far distances (scene units).
    orthographic : the projection was orthographic.
    offsets : (P + 1,) int64, polygon ``p``'s fragments are
        ``offsets[p] : offsets[p + 1]``.
    fragments : all fragments, in drawing order.
    color : (P, 3) float64, each polygon's flat colour.
    alpha : (P,) float64, each polygon's opacity alpha_s.
    object_index, triangle_index : (P,) int64, where each polygon came from.
    depth_format : the z-buffer's number format
        (:data:`core.object_order.depth_formats.DEPTH_FORMATS`).
    z_test : whether fragments were depth-tested (False: drawn in order).
    """

    width: int
    height: int
    background: np.ndarray
    near: float
    far: float
    orthographic: bool
    offsets: np.ndarray
    fragments: Fragments
    color: np.ndarray
    alpha: np.ndarray
    object_index: np.ndarray
    triangle_index: np.ndarray
    depth_format: str = "float64"
    z_test: bool = True

    @property
    def n_steps(self) -> int:
        """Number of polygons drawn (the last step)."""
        return len(self.alpha)

    @property
    def nbytes(self) -> int:
        """Memory held by the recording, in bytes."""
        per_polygon = (self.offsets, self.color, self.alpha, self.object_index, self.triangle_index)
        return self.fragments.nbytes + sum(a.nbytes for a in per_polygon)

    def buffers(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Image memory (H, W, 3) and z-buffer (H, W, depth keys) after ``k`` polygons."""
        if not 0 <= k <= self.n_steps:
            raise ValueError(f"step must be in [0, {self.n_steps}], got {k}")
        color, zbuf = zbuffer.cleared_buffers(self.width, self.height, self.background,
                                              self.depth_format)
        from core.object_order.kernels import raster as kernels

        f = self.fragments
        kernels.replay(self.offsets, f.pixel, f.z, f.passed, self.color, self.alpha, k, color, zbuf)
        return color, zbuf

    def fragments_per_pixel(self, k: int | None = None) -> np.ndarray:
        """(H, W) int64, how many fragments of the first ``k`` polygons (default all) reached each
        pixel: the overdraw's heat map.

        They add up to every fragment generated, passed or failed.
        """
        k = self.n_steps if k is None else k
        pixels = self.fragments.pixel[:self.offsets[k]]
        counts = np.bincount(pixels, minlength=self.width * self.height)
        return counts.astype(np.int64).reshape(self.height, self.width)

    def polygon_fragments(self, p: int) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
        """The fragments of polygon ``p`` (drawn at step ``p``): columns, rows, depth keys, passed."""
        part = slice(self.offsets[p], self.offsets[p + 1])
        rows, cols = np.divmod(self.fragments.pixel[part], self.width)
        return cols, rows, self.fragments.z[part], self.fragments.passed[part]

    def pixel_history(self, x: int, y: int) -> tuple[PixelEvent, ...]:
        """Every fragment that reached pixel (column ``x``, row ``y``), in order."""
        if not (0 <= x < self.width and 0 <= y < self.height):
            raise ValueError(f"pixel ({x}, {y}) is outside the {self.width} x {self.height} image")
        index = np.flatnonzero(self.fragments.pixel == y * self.width + x)
        polygons = np.searchsorted(self.offsets, index, side="right") - 1
        color, cleared = zbuffer.cleared_buffers(1, 1, self.background, self.depth_format)
        color, stored = color[0, 0], float(cleared[0, 0])
        events = []
        for f, p in zip(index.tolist(), polygons.tolist(), strict=True):
            z, passed = float(self.fragments.z[f]), bool(self.fragments.passed[f])
            after, blend = color, None
            if passed:
                alpha = float(self.alpha[p])
                after = blend_over(alpha, self.color[p], color)
                if alpha < 1.0:
                    blend = Blend(alpha, self.color[p].copy(), color, after)
            distance, stored_distance = (
                float(zbuffer.distance_from_window_depth(v, self.near, self.far, self.orthographic))
                for v in (z, stored))
            events.append(PixelEvent(p, int(self.object_index[p]), int(self.triangle_index[p]), z,
                                     distance, stored, stored_distance, passed, color, after, blend))
            if passed:
                color, stored = after, z
        return tuple(events)
