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
``(i + 0.5, j + 0.5)``.

Every formula here is written once, as a small function that numba compiles
into the hot loop (:func:`core.object_order.kernels.raster.draw_triangles`)
and that plain Python calls too: :func:`to_fixed`, :func:`edge_function`,
:func:`is_top_left` with :func:`fill_rule_offset`, :func:`edge_steps`,
:func:`depth_plane` and :func:`plane_depth`.  :func:`coverage` is the loop
written plainly for one triangle.  A corner farther than ``MAX_PIXEL`` from
the image (possible only with clipping switched off) would overflow the
integer edge functions, so such triangles are not drawn.
"""

from __future__ import annotations

import numpy as np

from core.compiling.jitable import jitable

SUBPIXEL_BITS = 8
SUBPIXEL = 1 << SUBPIXEL_BITS
"""Fixed-point steps per pixel (corners are snapped to 1/256 pixel, as on GPUs)."""
MAX_PIXEL = float(1 << 20)
"""Largest pixel coordinate the int64 edge functions handle without overflow."""


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
    Compiled (:func:`core.object_order.kernels.transform.window_coordinates`), with
    the arithmetic of :func:`core.projection.pixel_from_ndc`.
    """
    from core.object_order.kernels import transform as kernels  # the kernel compiles in this module

    xy, z_win = np.empty((len(clip), 2)), np.empty(len(clip))
    kernels.window_coordinates(np.ascontiguousarray(clip, dtype=float), width, height, xy, z_win)
    return xy, z_win


@jitable
def to_fixed(x):
    """One pixel coordinate to fixed point: the nearest multiple of 1/``SUBPIXEL`` pixel.

    Examples
    --------
    >>> int(to_fixed(0.5)), int(to_fixed(1.25))
    (128, 320)
    """
    return np.int64(np.rint(x * SUBPIXEL))


def snap(xy: np.ndarray) -> np.ndarray:
    """:func:`to_fixed` over an array of pixel coordinates (int64, same shape)."""
    return np.vectorize(to_fixed, otypes=[np.int64])(np.asarray(xy, dtype=float))


@jitable
def pixel_centre_fixed(i):
    """The centre of pixel column (or row) ``i`` in fixed point: ``(i + 1/2) SUBPIXEL``."""
    return i * SUBPIXEL + SUBPIXEL // 2


@jitable
def centres_within(lo, hi):
    """The pixel columns (or rows) whose centres lie in the fixed-point range ``lo .. hi``.

    Returns ``(first, last)``, with ``first > last`` when no centre lies in
    it: a triangle whose bounding box holds no pixel centre covers none.

    Examples
    --------
    >>> [int(v) for v in centres_within(128, 128)], [int(v) for v in centres_within(129, 383)]
    ([0, 0], [1, 0])
    """
    return (lo - SUBPIXEL // 2 + SUBPIXEL - 1) >> SUBPIXEL_BITS, (hi - SUBPIXEL // 2) >> SUBPIXEL_BITS


@jitable
def edge_function(a, b, p):
    """``E_ab(p) = (b - a) x (p - a)``: twice the signed area of the triangle ``a, b, p``.

    With y pointing down, ``E > 0`` means ``p`` lies clockwise from the edge as
    seen on the screen.  In fixed point (integers) it is exact.  The
    coordinates of ``p`` may be arrays (a grid of pixel centres).

    Examples
    --------
    >>> edge_function((0, 0), (4, 0), (1, 3)), edge_function((4, 0), (0, 0), (1, 3))
    (12, -12)
    """
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


@jitable
def edge_steps(a, b):
    """How ``E_ab`` changes from one pixel centre to the next: ``(per column, per row)``.

    ``E_ab`` is linear in ``p``, so stepping it by these fixed-point amounts
    gives exactly the value :func:`edge_function` would compute afresh.

    Examples
    --------
    >>> [int(s) for s in edge_steps((0, 0), (4, 0))]
    [0, 1024]
    """
    return (a[1] - b[1]) * SUBPIXEL, (b[0] - a[0]) * SUBPIXEL


@jitable
def is_top_left(a, b):
    """Does the edge ``a -> b`` own the pixel centres lying exactly on it?  The tie rule.

    For a triangle whose corners run so that its inside has ``E > 0`` on every
    edge, the inward normal of ``a -> b`` is ``(-(by - ay), bx - ax)``.  The
    edge is a *left* edge when that normal points right (``by < ay``) and a
    *top* edge when it is horizontal with the normal pointing down (``bx > ax``).
    Two triangles sharing an edge run it in opposite directions, so exactly
    one of them owns its centres.  Equivalently: a centre on the edge belongs
    to the triangle that holds the point an infinitesimal step to its right
    (and, on a horizontal edge, a smaller step down).

    Examples
    --------
    >>> is_top_left((0, 4), (0, 0)), is_top_left((0, 0), (0, 4))   # left, right
    (True, False)
    >>> is_top_left((0, 0), (4, 0)), is_top_left((4, 4), (0, 4))   # top, bottom
    (True, False)
    """
    dx, dy = b[0] - a[0], b[1] - a[1]
    return dy < 0 or (dy == 0 and dx > 0)


@jitable
def fill_rule_offset(a, b):
    """0 for a top-left edge, -1 otherwise: added to the integer ``E_ab``, the test
    ``E + offset >= 0`` keeps centres inside and those on owned edges."""
    return 0 if is_top_left(a, b) else -1


@jitable
def depth_plane(a, b, c, za, zb, zc):
    """The plane of window depth over the screen through a triangle's three corners.

    Parameters
    ----------
    a, b, c : (x, y) float, corners in pixels (unsnapped).
    za, zb, zc : float, their window depths.

    Returns
    -------
    (z_a, dz/dx, dz/dy) : the depth at ``a`` and its change per pixel to the
        right and down (Cramer's rule on the two edge vectors from ``a``).  A
        triangle with no area on screen gets a constant depth ``z_a``.
    """
    det = edge_function(a, b, c)
    if det == 0:
        return za, 0.0, 0.0
    dzb, dzc = zb - za, zc - za
    dzdx = (dzb * (c[1] - a[1]) - dzc * (b[1] - a[1])) / det
    dzdy = (dzc * (b[0] - a[0]) - dzb * (c[0] - a[0])) / det
    return za, dzdx, dzdy


@jitable
def plane_depth(plane, a, px, py):
    """The depth of a fragment: the plane ``(z_a, dz/dx, dz/dy)`` anchored at corner
    ``a`` evaluated at pixel position ``(px, py)`` (a pixel centre).

    Examples
    --------
    >>> plane_depth((0.5, 0.01, -0.02), (10.0, 20.0), 12.5, 20.5)
    0.515
    """
    return plane[0] + (py - a[1]) * plane[2] + (px - a[0]) * plane[1]


def coverage(corners_fixed, width: int, height: int) -> np.ndarray:
    """Pixels whose centres one triangle covers: the kernel's test written plainly.

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
    if area < 0:  # make the corners run so that inside means E > 0 for every edge
        b, c = c, b
    px = pixel_centre_fixed(np.arange(width, dtype=np.int64))[None, :]
    py = pixel_centre_fixed(np.arange(height, dtype=np.int64))[:, None]
    inside = np.full((height, width), area != 0)
    for u, v in ((b, c), (c, a), (a, b)):
        inside &= edge_function(u, v, (px, py)) + fill_rule_offset(u, v) >= 0
    return inside


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
