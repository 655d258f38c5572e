"""Rasterization: which pixels a projected triangle covers, and its depth there.

After projection and the viewport mapping every polygon is a flat shape on
the pixel grid.  Rasterization turns it into *fragments*: one per pixel whose
centre it covers, each with a depth for the z-buffer (:mod:`core.object_order.zbuffer`).

Coverage uses *edge functions*: for the edge from ``a`` to ``b``,
``E_ab(p) = (b - a) x (p - a)`` is zero on the edge's line and has one sign
on each side, so a pixel centre is inside a triangle when all three edge
functions agree.  Two rules make neighbouring triangles tile the screen with
no gaps and no pixel drawn twice:

- corners are snapped to a fixed-point grid of ``2**SUBPIXEL_BITS`` steps per
  pixel and the edge functions are evaluated in exact integer arithmetic, so
  a shared edge gives both triangles exactly opposite values;
- the *top-left fill rule* settles pixel centres lying exactly on an edge:
  they belong to the triangle for which that edge is a left edge (the
  triangle lies to its right) or a top edge (horizontal, triangle below).

Depth is not snapped: window depth ``z_win = (z_ndc + 1) / 2`` is an affine
function of the pixel position on a flat triangle for both projections (in
perspective it is affine in ``1 / w``, which is itself affine on the screen),
so the plane through the three unsnapped corners gives the exact depth at
every pixel centre.  Conventions are those of :mod:`core.projection`: pixel
``x`` to the right, ``y`` down, pixel ``(i, j)`` centred at
``(i + 0.5, j + 0.5)``.  The hot loop is :func:`core.object_order.kernels.raster.draw_triangles`;
:func:`snap`, :func:`coverage` and :func:`depth_planes` are its plain reference.
A corner farther than ``MAX_PIXEL`` from the image (possible only with
clipping switched off) would overflow the integer edge functions, so such
triangles are not drawn.
"""

from __future__ import annotations

import numpy as np

from core import projection
from core.object_order.kernels.raster import MAX_PIXEL as MAX_PIXEL
from core.object_order.kernels.raster import SUBPIXEL_BITS

SUBPIXEL = 1 << SUBPIXEL_BITS
"""Fixed-point steps per pixel (corners are snapped to 1/256 pixel, as on GPUs)."""


def window_coordinates(clip: np.ndarray, width: int, height: int) -> tuple[np.ndarray, np.ndarray]:
    """Perspective divide and viewport mapping: clip space to pixels and window depth.

    Parameters
    ----------
    clip : (N, 4) float64, homogeneous clip coordinates.
    width, height : image size in pixels.

    Returns
    -------
    xy : (N, 2) float64, pixel coordinates (x right, y down).
    z_win : (N,) float64, window depth ``(z_ndc + 1) / 2``: 0 on the near plane,
        1 on the far plane.

    Notes
    -----
    A vertex behind the eye (``w < 0``) lands mirrored through the image
    centre; clipping (:mod:`core.object_order.clipping`) removes such vertices first.
    """
    with np.errstate(divide="ignore", invalid="ignore"):
        ndc = clip[:, :3] / clip[:, 3:4]
    return projection.pixel_from_ndc(ndc[:, :2], width, height), (ndc[:, 2] + 1.0) * 0.5


def snap(xy: np.ndarray) -> np.ndarray:
    """Pixel coordinates to fixed point: integer multiples of 1/``SUBPIXEL`` pixel.

    Examples
    --------
    >>> snap(np.array([0.5, 1.25])).tolist()
    [128, 320]
    """
    return np.rint(np.asarray(xy, dtype=float) * SUBPIXEL).astype(np.int64)


def edge_function(a, b, p):
    """``E_ab(p) = (b - a) x (p - a)``: twice the signed area of the triangle ``a, b, p``.

    With y pointing down, ``E > 0`` means ``p`` lies clockwise from the edge as
    seen on the screen.  ``p`` may be a tuple of coordinate arrays.

    Examples
    --------
    >>> edge_function((0, 0), (4, 0), (1, 3)), edge_function((4, 0), (0, 0), (1, 3))
    (12, -12)
    """
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


def is_top_left(a, b) -> bool:
    """Does the edge ``a -> b`` own the pixel centres lying exactly on it?

    For a triangle whose corners run so that its inside has ``E > 0`` on every
    edge, the inward normal of ``a -> b`` is ``(-(by - ay), bx - ax)``.  The
    edge is a *left* edge when that normal points right (``by < ay``) and a
    *top* edge when it is horizontal with the normal pointing down (``bx > ax``).

    Examples
    --------
    >>> is_top_left((0, 4), (0, 0)), is_top_left((0, 0), (0, 4))   # left, right
    (True, False)
    >>> is_top_left((0, 0), (4, 0)), is_top_left((4, 4), (0, 4))   # top, bottom
    (True, False)
    """
    dx, dy = b[0] - a[0], b[1] - a[1]
    return bool(dy < 0 or (dy == 0 and dx > 0))


def coverage(corners_fixed, width: int, height: int) -> np.ndarray:
    """Pixels whose centres one triangle covers: the reference for the compiled kernel.

    Parameters
    ----------
    corners_fixed : (3, 2) int64, corners in fixed point (:func:`snap`).
    width, height : image size in pixels.

    Returns
    -------
    (H, W) bool
    """
    a, b, c = (tuple(int(v) for v in corner) for corner in corners_fixed)
    area = edge_function(a, b, c)
    if area < 0:
        b, c = c, b
    px = np.arange(width, dtype=np.int64)[None, :] * SUBPIXEL + SUBPIXEL // 2
    py = np.arange(height, dtype=np.int64)[:, None] * SUBPIXEL + SUBPIXEL // 2
    inside = np.full((height, width), area != 0)
    for u, v in ((b, c), (c, a), (a, b)):
        e = edge_function(u, v, (px, py))
        inside &= (e > 0) | ((e == 0) & is_top_left(u, v))
    return inside


def depth_planes(xy: np.ndarray, z: np.ndarray) -> np.ndarray:
    """The plane of window depth over the screen through each triangle's corners.

    Parameters
    ----------
    xy : (T, 3, 2) float64, corners in pixels (unsnapped).
    z : (T, 3) float64, window depth of the corners.

    Returns
    -------
    (T, 3) float64, ``(z_a, dz/dx, dz/dy)`` so that at pixel position ``p``
    ``z = z_a + (p_x - a_x) dz/dx + (p_y - a_y) dz/dy`` with ``a`` the first
    corner.  A triangle with no area on screen gets a constant depth ``z_a``.
    """
    ab, ac = xy[:, 1] - xy[:, 0], xy[:, 2] - xy[:, 0]
    dzb, dzc = z[:, 1] - z[:, 0], z[:, 2] - z[:, 0]
    det = ab[:, 0] * ac[:, 1] - ac[:, 0] * ab[:, 1]
    safe = np.where(det != 0, det, 1.0)
    dzdx = np.where(det != 0, (dzb * ac[:, 1] - dzc * ab[:, 1]) / safe, 0.0)
    dzdy = np.where(det != 0, (dzc * ab[:, 0] - dzb * ac[:, 0]) / safe, 0.0)
    return np.stack([z[:, 0], dzdx, dzdy], axis=1)


def fan_triangles(offsets: np.ndarray, order: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Split convex polygons into triangle fans, polygon by polygon in ``order``.

    Parameters
    ----------
    offsets : (P + 1,) int64, polygon ``p`` has vertices ``offsets[p] : offsets[p + 1]``.
    order : (P,) int64, the order to draw the polygons in.

    Returns
    -------
    corners : (T, 3) int64, vertex indices ``(v0, v_k, v_k+1)`` of every triangle.
    position : (T,) int64, the position in ``order`` of the polygon it comes from
        (non-decreasing).

    Examples
    --------
    >>> corners, position = fan_triangles(np.array([0, 3, 8]), np.array([1, 0]))
    >>> corners.tolist(), position.tolist()
    ([[3, 4, 5], [3, 5, 6], [3, 6, 7], [0, 1, 2]], [0, 0, 0, 1])
    """
    count = np.maximum(np.diff(offsets) - 2, 0)[order]
    position = np.repeat(np.arange(len(order)), count)
    within = np.arange(len(position)) - np.repeat(np.cumsum(count) - count, count)
    first = np.repeat(offsets[:-1][order], count)
    return np.stack([first, first + within + 1, first + within + 2], axis=1), position
