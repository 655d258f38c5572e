"""Compiled walk of a ray through the uniform grid (3D-DDA) and the tests it leads to.

See :mod:`core.image_order.grid_of_cuboids` for the grid itself.  The walk (Amanatides and Woo,
1987): find where the ray enters the grid's box and the cell there; for each
axis, the ``t`` where the ray crosses the next cell wall on that axis; then
repeatedly step into the neighbour across the nearest of the three walls.
Each wall crossing is computed from the ray's origin (not accumulated), so
no error builds up along a long walk.

Mailboxing: a primitive listed in several cells is tested once per ray.  Every
query gets a new stamp, and ``mailbox[p]`` remembers the stamp of the last
query that tested primitive ``p``.
"""

from __future__ import annotations

import math

from core.image_order.flat_layout import BOUNDS_TESTS, CELLS, PRIM_TESTS
from core.image_order.kernels.accel_spheres import bounding_roots
from core.image_order.kernels.jit import jit, jit_allocating
from core.image_order.kernels.primitives import no_hit, prim_hit


@jit
def grid_span(o, d, t_min, t_max, lo, hi):
    """``(t_enter, t_exit)`` of the ray in the box ``lo, hi``; ``t_enter > t_exit`` if it misses."""
    for a in range(3):
        inv = 1.0 / d[a]
        t0 = (lo[a] - o[a]) * inv
        t1 = (hi[a] - o[a]) * inv
        if t0 > t1:
            t0, t1 = t1, t0
        if t0 > t_min:
            t_min = t0
        if t1 < t_max:
            t_max = t1
    return t_min, t_max


@jit
def _start_cell(o, d, t, lo, cell_size, res, a):
    x = o[a] + t * d[a]
    c = int(math.floor((x - lo[a]) / cell_size[a]))
    return min(max(c, 0), res[a] - 1)


@jit
def _wall(o, d, cell, lo, cell_size, a):
    """``t`` where the ray leaves cell index ``cell`` along axis ``a`` (``inf`` if parallel)."""
    if d[a] > 0.0:
        return (lo[a] + (cell + 1) * cell_size[a] - o[a]) / d[a]
    if d[a] < 0.0:
        return (lo[a] + cell * cell_size[a] - o[a]) / d[a]
    return math.inf


@jit
def _step(d, a):
    return 1 if d[a] > 0.0 else (-1 if d[a] < 0.0 else 0)


@jit_allocating
def walk_cells(o, d, t_min, t_max, grid, out):
    """Write the cells crossed by the ray for ``t_min <= t <= t_max`` into ``out``; return their count.

    ``out`` is a (K, 3) int64 array with ``K >= nx + ny + nz`` (no ray crosses more cells).
    """
    lo, hi, cell_size, res, _, _ = grid
    if res[0] == 0:
        return 0
    t0, t1 = grid_span(o, d, t_min, t_max, lo, hi)
    if t0 > t1:
        return 0
    c = [_start_cell(o, d, t0, lo, cell_size, res, a) for a in range(3)]
    count = 0
    while count < out.shape[0]:
        out[count, 0], out[count, 1], out[count, 2] = c[0], c[1], c[2]
        count += 1
        w0 = _wall(o, d, c[0], lo, cell_size, 0)
        w1 = _wall(o, d, c[1], lo, cell_size, 1)
        w2 = _wall(o, d, c[2], lo, cell_size, 2)
        a = 0 if (w0 <= w1 and w0 <= w2) else (1 if w1 <= w2 else 2)
        if min(w0, w1, w2) > t1:
            break
        c[a] += _step(d, a)
        if c[a] < 0 or c[a] >= res[a]:
            break
    return count


@jit
def grid_closest(o, d, shear, t_min, t_max, any_hit, use_spheres, geo, grid, scratch, counters):
    """The closest crossing with ``t_min <= t < t_max`` (or any, for shadow rays), walking the grid.

    Parameters
    ----------
    use_spheres : bool
        The lecture's combination: before testing a mesh's triangle, test the
        mesh's bounding sphere (once per ray) and skip the triangle when the
        ray misses the sphere or meets it only beyond the closest hit so far.
    geo : :meth:`core.image_order.flat_scene.Geometry.kernel_tuple`.
    grid : :meth:`core.image_order.grid_of_cuboids.UniformGrid.kernel_tuple`.
    scratch : tuple ``(mailbox, object_stamp, object_span, stamp)``: (P,) int64,
        (O,) int64, (O, 2) float64 and (1,) int64 per-thread arrays.
    counters : (N_COUNTERS,) int64; primitive and sphere tests and cells are added.

    Returns
    -------
    (prim, t, b0, b1, b2) as :func:`core.image_order.kernels.bvh_traverse.bvh_closest`.
    """
    rows, n_spheres, prim_object, _, bounding, _, _ = geo
    lo, hi, cell_size, res, cell_start, cell_prims = grid
    mailbox, object_stamp, object_span, stamp_box = scratch
    best = no_hit()
    if res[0] == 0:
        return best
    t0, t1 = grid_span(o, d, t_min, t_max, lo, hi)
    if t0 > t1:
        return best
    stamp = stamp_box[0] + 1
    stamp_box[0] = stamp
    nx, ny = res[0], res[1]
    cx = _start_cell(o, d, t0, lo, cell_size, res, 0)
    cy = _start_cell(o, d, t0, lo, cell_size, res, 1)
    cz = _start_cell(o, d, t0, lo, cell_size, res, 2)
    best_t = t_max
    tests = 0
    spheres = 0
    cells = 0
    while True:
        cells += 1
        wx = _wall(o, d, cx, lo, cell_size, 0)
        wy = _wall(o, d, cy, lo, cell_size, 1)
        wz = _wall(o, d, cz, lo, cell_size, 2)
        cell = (cz * ny + cy) * nx + cx
        done = False
        for k in range(cell_start[cell], cell_start[cell + 1]):
            p = cell_prims[k]
            if mailbox[p] == stamp:
                continue
            mailbox[p] = stamp
            if use_spheres and p >= n_spheres:
                ob = prim_object[p]
                if object_stamp[ob] != stamp:
                    object_stamp[ob] = stamp
                    spheres += 1
                    object_span[ob, 0], object_span[ob, 1] = bounding_roots(o, d, bounding, ob)
                if object_span[ob, 0] >= best_t or object_span[ob, 1] < t_min:
                    continue
            tests += 1
            t, b0, b1, b2 = prim_hit(rows, p, p < n_spheres, o, d, shear, t_min, best_t)
            if t < best_t:
                best_t = t
                best = (p, t, b0, b1, b2)
                if any_hit:
                    done = True
                    break
        t_exit = min(wx, wy, wz)
        if done or best_t <= t_exit or t_exit > t1:
            break
        if wx <= wy and wx <= wz:
            cx += _step(d, 0)
            if cx < 0 or cx >= res[0]:
                break
        elif wy <= wz:
            cy += _step(d, 1)
            if cy < 0 or cy >= res[1]:
                break
        else:
            cz += _step(d, 2)
            if cz < 0 or cz >= res[2]:
                break
    counters[PRIM_TESTS] += tests
    counters[BOUNDS_TESTS] += spheres
    counters[CELLS] += cells
    return best
