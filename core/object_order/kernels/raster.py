"""The object-order hot loop: rasterize each triangle and z-test its fragments.

Two kernels share one way of writing a pixel, so that replaying recorded
fragments (:func:`replay`) rebuilds exactly the buffers :func:`draw_triangles`
produced:

- :func:`draw_triangles` sets up each triangle (snap its corners to fixed
  point, fit its depth plane), walks the pixel centres of its bounding box,
  decides coverage with integer edge functions and the top-left rule, takes
  the plane depth at each covered centre (:mod:`core.object_order.rasterization`),
  turns it into the key the z-buffer's number format stores
  (:mod:`core.object_order.depth_formats`) and runs the lecture's z-buffer test
  (:mod:`core.object_order.zbuffer`), or, with the z-test switched off, writes
  every fragment in drawing order.  Optionally it records every fragment: its
  pixel, its depth key and whether it passed.
- :func:`replay` applies the recorded fragments of the first ``stop`` polygons
  to cleared buffers (step scrubbing, :mod:`core.object_order.step_history`).

No formula is written here: each is a ``register_jitable`` function of the
lecture module it belongs to, compiled into these loops, so the readable code
and the compiled code cannot disagree.  (The modules are listed in
:data:`core.object_order.kernels.SOURCES` so that an edit of one recompiles
these kernels.)

Conventions: pixel ``(i, j)`` is column ``i``, row ``j`` (y down); pixels are
numbered ``j * width + i``; depths are window depths in [0, 1] (smaller is
nearer).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from core.object_order.blending import blend_over
from core.object_order.depth_formats import depth_key
from core.object_order.rasterization import (
    MAX_PIXEL,
    SUBPIXEL_BITS,
    depth_plane,
    edge_function,
    edge_steps,
    fill_rule_offset,
    pixel_centre_fixed,
    plane_depth,
    to_fixed,
)
from core.object_order.zbuffer import depth_test


@njit(cache=True, nogil=True)
def _write(color, zbuf, j, i, key, cs, alpha):
    """A fragment that passed: store its depth key and blend its colour over the pixel's."""
    zbuf[j, i] = key
    for c in range(3):
        color[j, i, c] = blend_over(alpha, cs[c], color[j, i, c])


@njit(cache=True, nogil=True)
def _grown(a, n, needed):
    """A copy of ``a[:n]`` with room for at least ``needed`` entries (doubling)."""
    b = np.empty(max(2 * a.shape[0], needed), a.dtype)
    b[:n] = a[:n]
    return b


@njit(cache=True, nogil=True)
def draw_triangles(xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, record,
                   depth_code, z_test):
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
    zbuf : (H, W) float64, z-buffer of depth keys (cleared to the far plane's key).
    record : bool, keep one record per fragment.
    depth_code : int, the z-buffer's number format
        (:func:`core.object_order.depth_formats.format_code`).
    z_test : bool, compare depths; False writes every fragment in drawing order.

    Returns
    -------
    generated, passed : (P,) int64, fragments per polygon.
    frag_pixel : (F,) int32, pixel number ``j * W + i`` of each fragment (empty
        unless ``record``), in drawing order.
    frag_key : (F,) float64, its depth key.
    frag_passed : (F,) bool, whether it passed the depth test.
    out_of_range : int, triangles not drawn because a corner is beyond
        ``MAX_PIXEL`` or not finite.
    """
    height, width = zbuf.shape
    generated = np.zeros(poly_alpha.shape[0], np.int64)
    passed = np.zeros(poly_alpha.shape[0], np.int64)
    capacity = 4 * width * height if record else 0
    frag_pixel = np.empty(capacity, np.int32)
    frag_key = np.empty(capacity, np.float64)
    frag_passed = np.empty(capacity, np.bool_)
    n = 0
    out_of_range = 0
    for t in range(corners.shape[0]):
        a, b, c = corners[t, 0], corners[t, 1], corners[t, 2]
        pa, pb, pc = (xy[a, 0], xy[a, 1]), (xy[b, 0], xy[b, 1]), (xy[c, 0], xy[c, 1])
        if not (abs(pa[0]) <= MAX_PIXEL and abs(pa[1]) <= MAX_PIXEL and abs(pb[0]) <= MAX_PIXEL
                and abs(pb[1]) <= MAX_PIXEL and abs(pc[0]) <= MAX_PIXEL and abs(pc[1]) <= MAX_PIXEL):
            out_of_range += 1
            continue
        # Triangle setup: fixed-point corners and the depth plane of the unsnapped ones.
        f0 = (to_fixed(pa[0]), to_fixed(pa[1]))
        f1 = (to_fixed(pb[0]), to_fixed(pb[1]))
        f2 = (to_fixed(pc[0]), to_fixed(pc[1]))
        area = edge_function(f0, f1, f2)
        if area == 0:
            continue
        plane = depth_plane(pa, pb, pc, z[a], z[b], z[c])
        if area < 0:  # make the corners run so that inside means E > 0 for every edge
            f1, f2 = f2, f1
        imin = max(min(f0[0], f1[0], f2[0]) >> SUBPIXEL_BITS, 0)
        imax = min(max(f0[0], f1[0], f2[0]) >> SUBPIXEL_BITS, width - 1)
        jmin = max(min(f0[1], f1[1], f2[1]) >> SUBPIXEL_BITS, 0)
        jmax = min(max(f0[1], f1[1], f2[1]) >> SUBPIXEL_BITS, height - 1)
        if imin > imax or jmin > jmax:
            continue
        box = (imax - imin + 1) * (jmax - jmin + 1)
        if record and n + box > frag_pixel.shape[0]:  # room for the whole bounding box
            frag_pixel = _grown(frag_pixel, n, n + box)
            frag_key = _grown(frag_key, n, n + box)
            frag_passed = _grown(frag_passed, n, n + box)
        first = (pixel_centre_fixed(imin), pixel_centre_fixed(jmin))
        # The three edge functions at the first pixel centre, with the fill rule's offset
        # so that "E >= 0" means covered, and their exact integer steps per pixel.
        e0 = edge_function(f1, f2, first) + fill_rule_offset(f1, f2)
        e1 = edge_function(f2, f0, first) + fill_rule_offset(f2, f0)
        e2 = edge_function(f0, f1, first) + fill_rule_offset(f0, f1)
        step_x0, step_y0 = edge_steps(f1, f2)
        step_x1, step_y1 = edge_steps(f2, f0)
        step_x2, step_y2 = edge_steps(f0, f1)
        p = tri_poly[t]
        cs = poly_color[p]
        alpha = poly_alpha[p]
        for j in range(jmin, jmax + 1):
            w0, w1, w2 = e0, e1, e2
            for i in range(imin, imax + 1):
                if w0 >= 0 and w1 >= 0 and w2 >= 0:
                    key = depth_key(plane_depth(plane, pa, i + 0.5, j + 0.5), depth_code)
                    ok = not z_test or depth_test(key, zbuf[j, i])
                    generated[p] += 1
                    if ok:
                        passed[p] += 1
                        _write(color, zbuf, j, i, key, cs, alpha)
                    if record:
                        frag_pixel[n] = j * width + i
                        frag_key[n] = key
                        frag_passed[n] = ok
                        n += 1
                w0 += step_x0
                w1 += step_x1
                w2 += step_x2
            e0 += step_y0
            e1 += step_y1
            e2 += step_y2
    return (generated, passed, frag_pixel[:n].copy(), frag_key[:n].copy(), frag_passed[:n].copy(),
            out_of_range)


@njit(cache=True, nogil=True)
def replay(offsets, frag_pixel, frag_key, frag_passed, poly_color, poly_alpha, stop, color, zbuf):
    """Apply the recorded fragments of polygons ``0 .. stop - 1`` to ``color`` and ``zbuf``.

    Parameters
    ----------
    offsets : (P + 1,) int64, fragments of polygon ``p`` are
        ``offsets[p] : offsets[p + 1]`` of the fragment arrays.
    frag_pixel, frag_key, frag_passed : as returned by :func:`draw_triangles`.
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
                _write(color, zbuf, j, frag_pixel[f] - j * width, frag_key[f], cs, alpha)
