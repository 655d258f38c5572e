"""Fragments: what every polygon contributes to the pixels it covers, in drawing order.

The lecture calls the colours a polygon gives to the pixels it may affect
*fragments*; the final pixel colour comes from all fragments that reached the
pixel.  :func:`draw` runs rasterization (:mod:`core.object_order.rasterization`)
and the z-buffer test (:mod:`core.object_order.zbuffer`) over all triangles in
drawing order in one compiled loop, bands of rows shared by the cores
(:mod:`core.object_order.kernels.raster`)
and, if asked, keeps every fragment for step and pixel history.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np

from core import stopping
from core.object_order import zbuffer
from core.object_order.depth_formats import format_code

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).


@dataclass(frozen=True)
class Fragments:
    """Every fragment the rasterizer produced, in drawing order.

    Attributes
    ----------
    pixel : (F,) int32, pixel number ``row * width + column``.
    z : (F,) float64, depth key at the pixel centre: the window depth in [0, 1]
        as the z-buffer's format stores it (the window depth itself in float64).
    passed : (F,) bool, the result of the depth test (always True with the
        z-test switched off).
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
    zbuf : (H, W) float64, depth keys; ``FAR_DEPTH`` where nothing passed.
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


class _Scratch(threading.local):
    """The rasterizer's scratch arrays, kept from frame to frame, one set per thread.

    Each triangle's bounding box and range test are overwritten every frame,
    triangle by triangle, so the arrays can be reused; fresh memory of that
    size would cost a page fault per 4 KB when first written.  They grow to
    the largest frame a thread has drawn (33 bytes per triangle) and stay.
    """

    box = np.empty((0, 4), dtype=np.int64)
    out_of_range = np.empty(0, dtype=bool)

    def take(self, n: int) -> tuple[np.ndarray, np.ndarray]:
        """``(n, 4)`` int64 and ``(n,)`` bool arrays of unspecified content."""
        if len(self.box) < n:
            self.box, self.out_of_range = np.empty((n, 4), dtype=np.int64), np.empty(n, dtype=bool)
        return self.box[:n], self.out_of_range[:n]


_scratch = _Scratch()


def draw(xy: np.ndarray, z: np.ndarray, corners: np.ndarray, position: np.ndarray,
         poly_color: np.ndarray, poly_alpha: np.ndarray, width: int, height: int, background,
         record: bool = False, depth_format: str = "float64", z_test: bool = True,
         threads: int | None = None) -> ZBufferPass:
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
    depth_format : the z-buffer's number format
        (:data:`core.object_order.depth_formats.DEPTH_FORMATS`).
    z_test : compare depths; False draws every fragment over what is there, in
        drawing order (the painter without sorting).
    threads : threads sharing the image's bands of rows (default: numba's
        thread count); the result is the same for any number.
    """
    import numba

    from core.object_order.kernels import raster as kernels

    code = format_code(depth_format)
    color, zbuf = zbuffer.cleared_buffers(width, height, background, depth_format)
    generated, passed = np.empty(len(poly_alpha), dtype=np.int64), np.empty(len(poly_alpha), dtype=np.int64)
    stop = np.zeros(1)
    with stopping.watching(stop, 0):  # Ctrl+C or Cancel: StoppedError within a piece of a triangle
        pixel, frag_z, ok, out_of_range = kernels.draw_triangles(
            xy, z, corners, position, np.ascontiguousarray(poly_color, dtype=float),
            np.ascontiguousarray(poly_alpha, dtype=float), color, zbuf, record, code, z_test,
            numba.get_num_threads() if threads is None else max(1, int(threads)),
            *_scratch.take(len(corners)), generated, passed, stop,
        )
    return ZBufferPass(color, zbuf, generated, passed, Fragments(pixel, frag_z, ok) if record else None,
                       out_of_range)
