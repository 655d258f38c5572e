"""The object-order hot loop: rasterize each triangle and z-test its fragments.

Two kernels share one way of writing a pixel, so that replaying recorded
fragments (:func:`replay`) rebuilds exactly the buffers :func:`draw_triangles`
produced:

- :func:`draw_triangles` sets up each triangle (snap its corners to fixed
  point, fit its depth plane), walks the pixel centres of its bounding box,
  decides coverage with integer edge functions and the top-left rule
  (reference: :mod:`core.object_order.rasterization`), evaluates the depth plane at each covered
  centre and runs the lecture's z-buffer test (:mod:`core.object_order.zbuffer`).
  Optionally it records every fragment: its pixel, its window depth and
  whether it passed.
- :func:`replay` applies the recorded fragments of the first ``stop`` polygons
  to cleared buffers (step scrubbing, :mod:`core.object_order.step_history`).

Conventions: pixel ``(i, j)`` is column ``i``, row ``j`` (y down); its centre
in fixed point is ``(i * S + S / 2, j * S + S / 2)`` with ``S = 2**8``
subpixel steps; pixels are numbered ``j * width + i``; depths are window
depths in [0, 1] (smaller is nearer).
"""

from __future__ import annotations

import numpy as np
from numba import njit

SUBPIXEL_BITS = 8
MAX_PIXEL = float(1 << 20)
"""Largest pixel coordinate the int64 edge functions handle without overflow."""


@njit(cache=True, nogil=True)
def _write(color, zbuf, j, i, z, cs, alpha):
    """Pass: store the depth and the lecture's blend ``c0 = a cs + (1 - a) cd`` (a = 1: opaque)."""
    zbuf[j, i] = z
    for c in range(3):
        color[j, i, c] = alpha * cs[c] + (1.0 - alpha) * color[j, i, c]


@njit(cache=True, nogil=True)
def _grown(a, n, needed):
    """A copy of ``a[:n]`` with room for at least ``needed`` entries (doubling)."""
    b = np.empty(max(2 * a.shape[0], needed), a.dtype)
    b[:n] = a[:n]
    return b


@njit(cache=True, nogil=True)
def draw_triangles(xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, record):
    """Rasterize triangles in order into ``color`` and ``zbuf`` (modified in place).

    Parameters
    ----------
    xy : (N, 2) float64, vertex positions in pixels (x right, y down).
    z : (N,) float64, vertex window depths.
    corners : (T, 3) int64, vertex indices of each triangle, in drawing order.
    tri_poly : (T,) int64, the polygon (draw position) each triangle belongs to.
    poly_color : (P, 3) float64, flat colour of each polygon.
    poly_alpha : (P,) float64, opacity alpha_s of each polygon (1 = opaque).
    color : (H, W, 3) float64, image memory.
    zbuf : (H, W) float64, z-buffer of window depths.
    record : bool, keep one record per fragment.

    Returns
    -------
    generated, passed : (P,) int64, fragments per polygon.
    frag_pixel : (F,) int32, pixel number ``j * W + i`` of each fragment (empty
        unless ``record``), in drawing order.
    frag_z : (F,) float64, its window depth.
    frag_passed : (F,) bool, whether it passed the depth test.
    out_of_range : int, triangles not drawn because a corner is beyond
        ``MAX_PIXEL`` or not finite.
    """
    height, width = zbuf.shape
    one = 1 << SUBPIXEL_BITS  # one pixel in fixed point
    half = one >> 1
    generated = np.zeros(poly_alpha.shape[0], np.int64)
    passed = np.zeros(poly_alpha.shape[0], np.int64)
    capacity = 4 * width * height if record else 0
    frag_pixel = np.empty(capacity, np.int32)
    frag_z = np.empty(capacity, np.float64)
    frag_passed = np.empty(capacity, np.bool_)
    n = 0
    out_of_range = 0
    for t in range(corners.shape[0]):
        a, b, c = corners[t, 0], corners[t, 1], corners[t, 2]
        ax, ay, bx, by, cx, cy = xy[a, 0], xy[a, 1], xy[b, 0], xy[b, 1], xy[c, 0], xy[c, 1]
        if not (abs(ax) <= MAX_PIXEL and abs(ay) <= MAX_PIXEL and abs(bx) <= MAX_PIXEL
                and abs(by) <= MAX_PIXEL and abs(cx) <= MAX_PIXEL and abs(cy) <= MAX_PIXEL):
            out_of_range += 1
            continue
        # Triangle setup: fixed-point corners and the depth plane of the unsnapped ones.
        x0, y0 = np.int64(np.rint(ax * one)), np.int64(np.rint(ay * one))
        x1, y1 = np.int64(np.rint(bx * one)), np.int64(np.rint(by * one))
        x2, y2 = np.int64(np.rint(cx * one)), np.int64(np.rint(cy * one))
        area = (x1 - x0) * (y2 - y0) - (x2 - x0) * (y1 - y0)
        if area == 0:
            continue
        det = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
        za, dzb, dzc = z[a], z[b] - z[a], z[c] - z[a]
        dzdx = (dzb * (cy - ay) - dzc * (by - ay)) / det if det != 0 else 0.0
        dzdy = (dzc * (bx - ax) - dzb * (cx - ax)) / det if det != 0 else 0.0
        if area < 0:  # make the corners run so that inside means E > 0 for every edge
            x1, y1, x2, y2 = x2, y2, x1, y1
        imin = max(min(x0, x1, x2) >> SUBPIXEL_BITS, 0)
        imax = min(max(x0, x1, x2) >> SUBPIXEL_BITS, width - 1)
        jmin = max(min(y0, y1, y2) >> SUBPIXEL_BITS, 0)
        jmax = min(max(y0, y1, y2) >> SUBPIXEL_BITS, height - 1)
        if imin > imax or jmin > jmax:
            continue
        box = (imax - imin + 1) * (jmax - jmin + 1)
        if record and n + box > frag_pixel.shape[0]:  # room for the whole bounding box
            frag_pixel = _grown(frag_pixel, n, n + box)
            frag_z = _grown(frag_z, n, n + box)
            frag_passed = _grown(frag_passed, n, n + box)
        px = imin * one + half
        py = jmin * one + half
        # Edge functions E_ab(p) = (bx - ax)(py - ay) - (by - ay)(px - ax) at the first
        # pixel centre, minus 1 on edges that are not top-left so that "E >= 0" applies
        # the fill rule; and their exact integer steps per pixel.
        e0 = (x2 - x1) * (py - y1) - (y2 - y1) * (px - x1)
        e1 = (x0 - x2) * (py - y2) - (y0 - y2) * (px - x2)
        e2 = (x1 - x0) * (py - y0) - (y1 - y0) * (px - x0)
        if not (y2 < y1 or (y2 == y1 and x2 > x1)):
            e0 -= 1
        if not (y0 < y2 or (y0 == y2 and x0 > x2)):
            e1 -= 1
        if not (y1 < y0 or (y1 == y0 and x1 > x0)):
            e2 -= 1
        step_x0, step_y0 = (y1 - y2) * one, (x2 - x1) * one
        step_x1, step_y1 = (y2 - y0) * one, (x0 - x2) * one
        step_x2, step_y2 = (y0 - y1) * one, (x1 - x0) * one
        p = tri_poly[t]
        cs = poly_color[p]
        alpha = poly_alpha[p]
        for j in range(jmin, jmax + 1):
            w0, w1, w2 = e0, e1, e2
            z_row = za + (j + 0.5 - ay) * dzdy
            for i in range(imin, imax + 1):
                if w0 >= 0 and w1 >= 0 and w2 >= 0:
                    zf = z_row + (i + 0.5 - ax) * dzdx
                    ok = zf < zbuf[j, i]
                    generated[p] += 1
                    if ok:
                        passed[p] += 1
                        _write(color, zbuf, j, i, zf, cs, alpha)
                    if record:
                        frag_pixel[n] = j * width + i
                        frag_z[n] = zf
                        frag_passed[n] = ok
                        n += 1
                w0 += step_x0
                w1 += step_x1
                w2 += step_x2
            e0 += step_y0
            e1 += step_y1
            e2 += step_y2
    return (generated, passed, frag_pixel[:n].copy(), frag_z[:n].copy(), frag_passed[:n].copy(),
            out_of_range)


@njit(cache=True, nogil=True)
def replay(offsets, frag_pixel, frag_z, frag_passed, poly_color, poly_alpha, stop, color, zbuf):
    """Apply the recorded fragments of polygons ``0 .. stop - 1`` to ``color`` and ``zbuf``.

    Parameters
    ----------
    offsets : (P + 1,) int64, fragments of polygon ``p`` are
        ``offsets[p] : offsets[p + 1]`` of the fragment arrays.
    frag_pixel, frag_z, frag_passed : as returned by :func:`draw_triangles`.
    poly_color, poly_alpha : as given to :func:`draw_triangles`.
    stop : int, number of polygons to apply.
    color, zbuf : (H, W, 3) and (H, W) float64, the buffers, modified in place
        (cleared buffers give the state after ``stop`` polygons).
    """
    width = zbuf.shape[1]
    for p in range(stop):
        cs = poly_color[p]
        alpha = poly_alpha[p]
        for f in range(offsets[p], offsets[p + 1]):
            if frag_passed[f]:
                j = frag_pixel[f] // width
                _write(color, zbuf, j, frag_pixel[f] - j * width, frag_z[f], cs, alpha)
