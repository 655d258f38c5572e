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
  pixel, its depth key and whether it passed.  Both cores work at once, each
  on its own bands of rows, with the same result as one core.
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
from numba import prange

from core.compiling.one_signature import njit
from core.object_order.blending import blend_over
from core.object_order.depth_formats import depth_key
from core.object_order.rasterization import (
    MAX_PIXEL,
    centres_within,
    depth_plane,
    edge_function,
    edge_steps,
    fill_rule_offset,
    pixel_centre_fixed,
    plane_depth,
    to_fixed,
)
from core.object_order.zbuffer import FAR_DEPTH, depth_test, distance_from_window_depth


@njit(cache=True, nogil=True)
def _write(color, zbuf, j, i, key, cs, alpha):
    """A fragment that passed: store its depth key and blend its colour over the pixel's."""
    zbuf[j, i] = key
    for c in range(3):
        color[j, i, c] = blend_over(alpha, cs[c], color[j, i, c])


BAND_ROWS = 16
"""Rows of pixels per band: the unit of work one thread takes (:func:`draw_triangles`)."""


@njit(cache=True, nogil=True)
def _corners_fixed(xy, a, b, c):
    """Triangle setup: the corners snapped to fixed point, turned so that inside is E > 0."""
    f0 = (to_fixed(xy[a, 0]), to_fixed(xy[a, 1]))
    f1 = (to_fixed(xy[b, 0]), to_fixed(xy[b, 1]))
    f2 = (to_fixed(xy[c, 0]), to_fixed(xy[c, 1]))
    area = edge_function(f0, f1, f2)
    if area < 0:  # make the corners run so that inside means E > 0 for every edge
        f1, f2 = f2, f1
    return f0, f1, f2, area


SMALL_BOX = 4
"""Boxes of at most so many pixel centres are shrunk to the centres the triangle covers
(:func:`_bounding_boxes`)."""


@njit(cache=True, nogil=True)
def _edges_at(f0, f1, f2, p):
    """The three edge functions of the triangle ``f0, f1, f2`` (fixed point, inside is
    E > 0) at the point ``p``, with the fill rule's offsets: ``p`` is covered when all
    three are ``>= 0``."""
    return (edge_function(f1, f2, p) + fill_rule_offset(f1, f2),
            edge_function(f2, f0, p) + fill_rule_offset(f2, f0),
            edge_function(f0, f1, p) + fill_rule_offset(f0, f1))


@njit(cache=True, nogil=True)
def _covered_box(f0, f1, f2, imin, imax, jmin, jmax):
    """The box of the centres in ``imin .. imax`` x ``jmin .. jmax`` that the triangle
    covers; empty (``jmin > jmax``) when it covers none."""
    ilo, ihi, jlo, jhi = imax + 1, imin - 1, jmax + 1, jmin - 1
    e0, e1, e2 = _edges_at(f0, f1, f2, (pixel_centre_fixed(imin), pixel_centre_fixed(jmin)))
    step_x0, step_y0 = edge_steps(f1, f2)
    step_x1, step_y1 = edge_steps(f2, f0)
    step_x2, step_y2 = edge_steps(f0, f1)
    for j in range(jmin, jmax + 1):
        w0, w1, w2 = e0, e1, e2
        for i in range(imin, imax + 1):
            if (w0 | w1 | w2) >= 0:  # all three >= 0: no sign bit set in any
                ilo, ihi, jlo, jhi = min(ilo, i), max(ihi, i), min(jlo, j), max(jhi, j)
            w0 += step_x0
            w1 += step_x1
            w2 += step_x2
        e0 += step_y0
        e1 += step_y1
        e2 += step_y2
    return ilo, ihi, jlo, jhi


@njit(cache=True, nogil=True, parallel=True)
def _bounding_boxes(xy, corners, width, height, box, out_of_range):
    """The pixels whose centres lie in each triangle's bounding box, clamped to the image,
    and the range test.  Triangle by triangle, shared by the threads (each box is its own).

    Writes
    ------
    box : (T, 4) int64, ``imin, imax, jmin, jmax``; a triangle with no area,
        no pixel centre in its box inside the image, or a corner out of range
        gets an empty box (``jmin > jmax``).  Most triangles of a fine mesh
        are smaller than a pixel: a box of at most ``SMALL_BOX`` centres is
        shrunk to the centres covered, so that the many that cover none get
        an empty box here, with the threads sharing the test, and are never
        binned or drawn.  (Shrinking the box drops only centres that make no
        fragment.)
    out_of_range : (T,) bool, a corner beyond ``MAX_PIXEL`` or not finite.
    """
    for t in prange(corners.shape[0]):
        box[t, 0], box[t, 1], box[t, 2], box[t, 3] = 0, -1, 1, 0
        out_of_range[t] = False
        a, b, c = corners[t, 0], corners[t, 1], corners[t, 2]
        if not (abs(xy[a, 0]) <= MAX_PIXEL and abs(xy[a, 1]) <= MAX_PIXEL and abs(xy[b, 0]) <= MAX_PIXEL
                and abs(xy[b, 1]) <= MAX_PIXEL and abs(xy[c, 0]) <= MAX_PIXEL
                and abs(xy[c, 1]) <= MAX_PIXEL):
            out_of_range[t] = True
            continue
        f0, f1, f2, area = _corners_fixed(xy, a, b, c)
        if area == 0:
            continue
        imin, imax = centres_within(min(f0[0], f1[0], f2[0]), max(f0[0], f1[0], f2[0]))
        jmin, jmax = centres_within(min(f0[1], f1[1], f2[1]), max(f0[1], f1[1], f2[1]))
        imin, imax, jmin, jmax = max(imin, 0), min(imax, width - 1), max(jmin, 0), min(jmax, height - 1)
        if imin <= imax and jmin <= jmax and (imax - imin + 1) * (jmax - jmin + 1) <= SMALL_BOX:
            imin, imax, jmin, jmax = _covered_box(f0, f1, f2, imin, imax, jmin, jmax)
        if imin <= imax and jmin <= jmax:
            box[t, 0], box[t, 1], box[t, 2], box[t, 3] = imin, imax, jmin, jmax


@njit(cache=True, nogil=True)
def _bin(box, n_bands):
    """Binning: cut every triangle into pieces, one per band of rows its box reaches.

    Returns
    -------
    piece_tri : (E,) int64, the triangle of each piece; pieces are numbered
        triangle by triangle, and within a triangle band by band (top down),
        so piece order is drawing order.
    band_start : (B + 1,) int64, band ``b``'s pieces are
        ``band_pieces[band_start[b] : band_start[b + 1]]``.
    band_pieces : (E,) int64, piece numbers band by band, each band's in
        drawing order.
    """
    n_tri = box.shape[0]
    count = np.zeros(n_bands + 1, np.int64)
    for t in range(n_tri):
        if box[t, 2] <= box[t, 3]:
            for b in range(box[t, 2] // BAND_ROWS, box[t, 3] // BAND_ROWS + 1):
                count[b + 1] += 1
    band_start = np.cumsum(count)
    n = band_start[n_bands]
    fill = band_start[:-1].copy()
    piece_tri = np.empty(n, np.int64)
    band_pieces = np.empty(n, np.int64)
    k = 0
    for t in range(n_tri):
        if box[t, 2] <= box[t, 3]:
            for b in range(box[t, 2] // BAND_ROWS, box[t, 3] // BAND_ROWS + 1):
                piece_tri[k] = t
                band_pieces[fill[b]] = k
                fill[b] += 1
                k += 1
    return piece_tri, band_start, band_pieces


@njit(cache=True, nogil=True)
def _draw_rows(xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, depth_code, z_test,
               t, imin, imax, jlo, jhi, record, slot, frag_pixel, frag_key, frag_passed):
    """Rasterize rows ``jlo .. jhi`` of triangle ``t``'s box, columns ``imin .. imax``, and
    z-test its fragments; with ``record`` they are kept from position ``slot`` on.

    Returns the numbers of fragments generated and passed.
    """
    width = zbuf.shape[1]
    a, b, c = corners[t, 0], corners[t, 1], corners[t, 2]
    f0, f1, f2, _ = _corners_fixed(xy, a, b, c)
    pa, pb, pc = (xy[a, 0], xy[a, 1]), (xy[b, 0], xy[b, 1]), (xy[c, 0], xy[c, 1])
    plane = (0.0, 0.0, 0.0)  # the depth plane, fitted at the first covered centre: most
    # sub-pixel triangles whose box holds a centre still cover none
    first = (pixel_centre_fixed(imin), pixel_centre_fixed(jlo))
    # The three edge functions at the first pixel centre, with the fill rule's offset
    # so that "E >= 0" means covered, and their exact integer steps per pixel.
    e0, e1, e2 = _edges_at(f0, f1, f2, first)
    step_x0, step_y0 = edge_steps(f1, f2)
    step_x1, step_y1 = edge_steps(f2, f0)
    step_x2, step_y2 = edge_steps(f0, f1)
    p = tri_poly[t]
    cs = poly_color[p]
    alpha = poly_alpha[p]
    generated = 0
    passed = 0
    for j in range(jlo, jhi + 1):
        w0, w1, w2 = e0, e1, e2
        for i in range(imin, imax + 1):
            if (w0 | w1 | w2) >= 0:  # all three >= 0: no sign bit set in any
                if generated == 0:
                    plane = depth_plane(pa, pb, pc, z[a], z[b], z[c])  # of the unsnapped corners
                key = depth_key(plane_depth(plane, pa, i + 0.5, j + 0.5), depth_code)
                ok = not z_test or depth_test(key, zbuf[j, i])
                if ok:
                    passed += 1
                    _write(color, zbuf, j, i, key, cs, alpha)
                if record:
                    frag_pixel[slot + generated] = j * width + i
                    frag_key[slot + generated] = key
                    frag_passed[slot + generated] = ok
                generated += 1
            w0 += step_x0
            w1 += step_x1
            w2 += step_x2
        e0 += step_y0
        e1 += step_y1
        e2 += step_y2
    return generated, passed


@njit(cache=True, nogil=True)
def _draw_bands(w, workers, xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, depth_code,
                z_test, box, piece_tri, band_start, band_pieces, record, slot, scratch_pixel,
                scratch_key, scratch_passed, piece_generated, piece_passed, stop):
    """One worker's share: bands ``w, w + workers, ...``, each band's pieces in drawing order.

    ``stop[0]`` raised by another thread (:mod:`core.stopping`) ends it before the next piece
    (at most ``BAND_ROWS`` rows of one triangle): the stores into the images keep the compiler
    from reading it once for the whole loop.
    """
    for b in range(w, band_start.shape[0] - 1, workers):
        for q in range(band_start[b], band_start[b + 1]):
            if stop[0] != 0.0:
                return
            k = band_pieces[q]
            t = piece_tri[k]
            jlo = max(box[t, 2], b * BAND_ROWS)
            jhi = min(box[t, 3], b * BAND_ROWS + BAND_ROWS - 1)
            piece_generated[k], piece_passed[k] = _draw_rows(
                xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, depth_code, z_test,
                t, box[t, 0], box[t, 1], jlo, jhi, record, slot[k] if record else 0, scratch_pixel,
                scratch_key, scratch_passed)


@njit(cache=True, nogil=True, parallel=True)
def _draw_bands_in_parallel(workers, xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf,
                            depth_code, z_test, box, piece_tri, band_start, band_pieces, record, slot,
                            scratch_pixel, scratch_key, scratch_passed, piece_generated, piece_passed, stop):
    """All workers at once, one thread each."""
    for w in prange(workers):  # prange counts in uint64: as int64, w shares the serial call's copy
        _draw_bands(np.int64(w), workers, xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf,
                    depth_code, z_test, box, piece_tri, band_start, band_pieces, record, slot,
                    scratch_pixel, scratch_key, scratch_passed, piece_generated, piece_passed, stop)


@njit(cache=True, nogil=True)
def draw_triangles(xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, record,
                   depth_code, z_test, n_workers, box, out_of_range, generated, passed, stop):
    """Rasterize triangles in order into ``color`` and ``zbuf`` (modified in place).

    The image is cut into bands of ``BAND_ROWS`` rows.  Binning lists for
    every band the triangles whose bounding box reaches it, in drawing order;
    ``n_workers`` threads then share the bands (worker ``w`` takes bands
    ``w, w + n_workers, ...``) and each draws a band's triangles in that
    order, its rows only.  A pixel lies in one band, so it meets exactly the
    fragments, in exactly the order, of a single-threaded render: the output
    does not depend on ``n_workers``.  Recorded fragments are gathered
    triangle by triangle and within one band by band, which is row by row as
    the triangle was drawn.

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
    n_workers : int >= 1, threads sharing the bands.
    box : (T, 4) int64 and out_of_range : (T,) bool, scratch space.
    generated, passed : (P,) int64, written: fragments per polygon.
    stop : (1,) float64, the stop flag (:mod:`core.stopping`): raised while the kernel runs, it
        returns within a piece of a triangle, its results incomplete.

    Returns
    -------
    frag_pixel : (F,) int32, pixel number ``j * W + i`` of each fragment (empty
        unless ``record``), in drawing order.
    frag_key : (F,) float64, its depth key.
    frag_passed : (F,) bool, whether it passed the depth test.
    out_of_range : int, triangles not drawn because a corner is beyond
        ``MAX_PIXEL`` or not finite.
    """
    height, width = zbuf.shape
    _bounding_boxes(xy, corners, width, height, box, out_of_range)
    n_bands = (height + BAND_ROWS - 1) // BAND_ROWS
    piece_tri, band_start, band_pieces = _bin(box, n_bands)
    n_pieces = piece_tri.shape[0]
    # Room for every fragment a piece may make (``record`` only): the pixels of its box within
    # its band.  A triangle's pieces follow each other, band after band from its box's top.
    slot = np.zeros(n_pieces + 1 if record else 1, np.int64)
    if record:
        b = 0
        for k in range(n_pieces):
            t = piece_tri[k]
            b = b + 1 if k > 0 and piece_tri[k - 1] == t else box[t, 2] // BAND_ROWS
            rows = min(box[t, 3], b * BAND_ROWS + BAND_ROWS - 1) - max(box[t, 2], b * BAND_ROWS) + 1
            slot[k + 1] = slot[k] + rows * (box[t, 1] - box[t, 0] + 1)
    scratch_pixel = np.empty(slot[-1], np.int32)
    scratch_key = np.empty(slot[-1], np.float64)
    scratch_passed = np.empty(slot[-1], np.bool_)
    piece_generated = np.empty(n_pieces, np.int64)  # every piece is drawn, by one worker
    piece_passed = np.empty(n_pieces, np.int64)
    workers = max(1, min(n_workers, n_bands))
    if workers == 1:
        _draw_bands(0, 1, xy, z, corners, tri_poly, poly_color, poly_alpha, color, zbuf, depth_code,
                    z_test, box, piece_tri, band_start, band_pieces, record, slot, scratch_pixel,
                    scratch_key, scratch_passed, piece_generated, piece_passed, stop)
    else:
        _draw_bands_in_parallel(workers, xy, z, corners, tri_poly, poly_color, poly_alpha, color,
                                zbuf, depth_code, z_test, box, piece_tri, band_start, band_pieces,
                                record, slot, scratch_pixel, scratch_key, scratch_passed,
                                piece_generated, piece_passed, stop)
    generated[:] = 0
    passed[:] = 0
    if stop[0] != 0.0:  # stopped: the pieces not drawn have no counts; gather nothing from them
        return np.empty(0, np.int32), np.empty(0, np.float64), np.empty(0, np.bool_), 0
    for k in range(n_pieces):
        p = tri_poly[piece_tri[k]]
        generated[p] += piece_generated[k]
        passed[p] += piece_passed[k]
    # Gather the recorded fragments piece by piece, which is drawing order.
    start = np.zeros(n_pieces + 1 if record else 1, np.int64)
    if record:
        start[1:] = np.cumsum(piece_generated)
    frag_pixel = np.empty(start[-1], np.int32)
    frag_key = np.empty(start[-1], np.float64)
    frag_passed = np.empty(start[-1], np.bool_)
    if record:
        for k in range(n_pieces):
            for f in range(piece_generated[k]):
                frag_pixel[start[k] + f] = scratch_pixel[slot[k] + f]
                frag_key[start[k] + f] = scratch_key[slot[k] + f]
                frag_passed[start[k] + f] = scratch_passed[slot[k] + f]
    return frag_pixel, frag_key, frag_passed, int(out_of_range.sum())


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


@njit(cache=True, nogil=True)
def depth_image(zbuf, near, far, orthographic):
    """(H, W) float64, the distance along the viewing axis of each pixel's depth key
    (:func:`core.object_order.zbuffer.distance_from_window_depth`), +inf where the
    z-buffer still holds the far plane (nothing drawn)."""
    out = np.empty(zbuf.shape)
    for j in range(zbuf.shape[0]):
        for i in range(zbuf.shape[1]):
            z = zbuf[j, i]
            out[j, i] = distance_from_window_depth(z, near, far, orthographic) if z < FAR_DEPTH else np.inf
    return out
