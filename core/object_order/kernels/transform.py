"""Transforming vertices compiled: the 4 x 4 matrices of the first stage applied to
every point, and the perspective divide with the viewport mapping, each in one loop.

The pipeline's first stage (world -> view -> clip space) and its projection
stage (:mod:`core.object_order.pipeline`).  Matrices act on column vectors
``[x, y, z, 1]``.  The results are written into arrays the caller allocates with
numpy (see :mod:`core.object_order.kernels`).  One thread: a few nanoseconds per
point are less than what sharing the loop costs on a busy machine.
"""

from __future__ import annotations

from numba import njit


@njit(inline="always")
def _transform(matrix, x, y, z, out, i, rows):
    """``out[i, :rows] = (matrix @ [x, y, z, 1])[:rows]`` (inlined, so that ``rows`` is a constant)."""
    for k in range(rows):
        out[i, k] = matrix[k, 0] * x + matrix[k, 1] * y + matrix[k, 2] * z + matrix[k, 3]


@njit(cache=True, nogil=True)
def view_and_clip(points, view_from_world, clip_from_view, view, clip):
    """Every point to view space, and from there to clip space, in one pass.

    Parameters
    ----------
    points : (N, 3) float64, world space.
    view_from_world : (4, 4) float64, an affine map.
    clip_from_view : (4, 4) float64, the projection.

    view : (N, 3) float64, written: ``(view_from_world @ [p, 1])[:3]``.
    clip : (N, 4) float64, written: ``clip_from_view @ [view, 1]``, homogeneous.
    """
    for i in range(points.shape[0]):
        _transform(view_from_world, points[i, 0], points[i, 1], points[i, 2], view, i, 3)
        _transform(clip_from_view, view[i, 0], view[i, 1], view[i, 2], clip, i, 4)


@njit(cache=True, nogil=True, error_model="numpy")
def window_coordinates(clip, width, height, xy, z_win):
    """Clip space to pixels and window depth, with the arithmetic of
    :func:`core.projection.pixel_from_ndc` (bit for bit).

    Parameters
    ----------
    clip : (N, 4) float64, homogeneous clip coordinates.
    width, height : image size in pixels.

    xy : (N, 2) float64, written: ``x = (x_ndc + 1) / 2 W``, ``y = (1 - y_ndc) / 2 H``.
    z_win : (N,) float64, written: ``(z_ndc + 1) / 2``.  (``w = 0`` gives inf or nan, as
        in numpy.)
    """
    for i in range(clip.shape[0]):
        w = clip[i, 3]
        xy[i, 0] = (clip[i, 0] / w + 1.0) * 0.5 * width
        xy[i, 1] = (1.0 - clip[i, 1] / w) * 0.5 * height
        z_win[i] = (clip[i, 2] / w + 1.0) * 0.5
