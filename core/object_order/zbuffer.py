"""The z-buffer (depth buffer): which surface is nearest, decided pixel by pixel.

The lecture's algorithm: clear the *image memory* to the background colour
and the *z-buffer* to the greatest depth that can occur, the far (end) plane.
Then, polygon after polygon, every fragment is tested against the z-buffer:
if it lies nearer than the value stored at its pixel it passes, and its colour
goes to image memory and its depth to the z-buffer; otherwise it fails and
nothing changes.  Objects may be drawn in any order and may even pierce each
other: each pixel is decided on its own.

The lecture stores "the z coordinate" with z pointing from the observer into
the scene.  Like GPUs and VTK, this z-buffer stores the *window depth*
``z_win = (z_ndc + 1) / 2``: 0 on the near plane, 1 on the far plane, and
smaller means nearer, so the test and the clear value are the lecture's.
:func:`distance_from_window_depth` turns it back into the distance along the
viewing axis.  Conventions are those of :mod:`core.projection`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.object_order.kernels import raster as kernels

FAR_DEPTH = 1.0
"""Window depth of the far plane: the value the z-buffer is cleared to."""


def cleared_buffers(width: int, height: int, background) -> tuple[np.ndarray, np.ndarray]:
    """Image memory filled with ``background`` and a z-buffer filled with the far plane.

    Returns
    -------
    color : (H, W, 3) float64, RGB in [0, 1].
    zbuf : (H, W) float64, window depth, all ``FAR_DEPTH``.
    """
    color = np.empty((height, width, 3))
    color[:] = np.asarray(background, dtype=float)
    return color, np.full((height, width), FAR_DEPTH)


def depth_test(z, stored):
    """The z-buffer test: a fragment passes when it is nearer than what is stored.

    Strictly nearer: of two surfaces at exactly the same depth, the one drawn
    first stays.

    Examples
    --------
    >>> depth_test(0.4, 1.0), depth_test(0.4, 0.4)
    (True, False)
    """
    return z < stored


def distance_from_window_depth(z_win, near: float, far: float, orthographic: bool):
    """Window depth back to the distance along the viewing axis (scene units, positive).

    Perspective: ``d = 2 n f / ((f + n) - z_ndc (f - n))`` with
    ``z_ndc = 2 z_win - 1`` (the inverse of the perspective matrix's depth
    row); orthographic: depth is linear, ``d = n + z_win (f - n)``.

    Examples
    --------
    >>> float(distance_from_window_depth(0.0, 1.0, 30.0, False))   # near plane
    1.0
    >>> float(distance_from_window_depth(1.0, 1.0, 30.0, False))   # far plane
    30.0
    """
    z_win = np.asarray(z_win, dtype=float)
    if orthographic:
        return near + z_win * (far - near)
    return 2.0 * near * far / ((far + near) - (2.0 * z_win - 1.0) * (far - near))


@dataclass(frozen=True)
class Fragments:
    """Every fragment the rasterizer produced, in drawing order.

    Attributes
    ----------
    pixel : (F,) int32, pixel number ``row * width + column``.
    z : (F,) float64, window depth at the pixel centre.
    passed : (F,) bool, the result of the depth test.
    """

    pixel: np.ndarray
    z: np.ndarray
    passed: np.ndarray

    def __len__(self) -> int:
        return len(self.pixel)

    @property
    def nbytes(self) -> int:
        return self.pixel.nbytes + self.z.nbytes + self.passed.nbytes


@dataclass(frozen=True)
class ZBufferPass:
    """Image memory and z-buffer after all polygons, and what each polygon did.

    Attributes
    ----------
    color : (H, W, 3) float64, image memory.
    zbuf : (H, W) float64, window depth; ``FAR_DEPTH`` where nothing passed.
    generated, passed : (P,) int64, fragments per polygon (in drawing order).
    fragments : every fragment (with ``record``), else ``None``.
    out_of_range : triangles not drawn because a corner lies beyond
        :data:`core.object_order.rasterization.MAX_PIXEL` (only without clipping).
    """

    color: np.ndarray
    zbuf: np.ndarray
    generated: np.ndarray
    passed: np.ndarray
    fragments: Fragments | None
    out_of_range: int = 0

    @property
    def failed(self) -> np.ndarray:
        """(P,) int64, fragments per polygon that failed the depth test."""
        return self.generated - self.passed


def draw(xy: np.ndarray, z: np.ndarray, corners: np.ndarray, position: np.ndarray,
         poly_color: np.ndarray, poly_alpha: np.ndarray, width: int, height: int, background,
         record: bool = False) -> ZBufferPass:
    """Run the z-buffer algorithm over triangles in drawing order.

    Parameters
    ----------
    xy : (N, 2) float64, vertex positions in pixels
        (:func:`core.object_order.rasterization.window_coordinates`).
    z : (N,) float64, vertex window depths.
    corners : (T, 3) int64, vertex indices of each triangle, in drawing order
        (:func:`core.object_order.rasterization.fan_triangles`).
    position : (T,) int64, draw position of each triangle's polygon.
    poly_color : (P, 3) float64, flat colour of each polygon, in drawing order.
    poly_alpha : (P,) float64, opacity alpha_s of each polygon; fragments of a
        polygon with alpha_s < 1 are blended (:mod:`core.object_order.blending`).
    width, height : image size in pixels.
    background : RGB colour image memory is cleared to.
    record : keep every fragment (for step and pixel history).
    """
    color, zbuf = cleared_buffers(width, height, background)
    generated, passed, pixel, frag_z, ok, out_of_range = kernels.draw_triangles(
        xy, z, corners, position, np.ascontiguousarray(poly_color, dtype=float),
        np.ascontiguousarray(poly_alpha, dtype=float), color, zbuf, record,
    )
    return ZBufferPass(color, zbuf, generated, passed, Fragments(pixel, frag_z, ok) if record else None,
                       out_of_range)
