"""Compiled stages of a full render: primary rays, shading of their hits, secondary rays.

The render runs in three stages so that the statistics can tell where the
time goes (:func:`core.image_order.ray_tracing.render_trace` times each):

1. primary - one ray per pixel, its closest hit and depth;
2. shade - local shading of those hits with their shadow rays, and the
   reflected / refracted rays they spawn;
3. secondary - those rays and all their descendants.

All three run through the one parallel kernel :func:`render_pass`, so numba
compiles the shared shading and intersection code once.

Colour combination: a ray tree's colour, combined bottom-up as in the
lecture (each node: its local colour plus its children's colours times their
coefficients), equals the sum over all nodes of the node's weight in the pixel
times its local colour.  The passes add those terms as the rays are traced,
depth first with a small stack, so no tree is ever stored.

The pixels to trace are given as column and row coordinates ``xs`` and
``ys``.  A pixel's point on the image plane comes from its column alone and its
row alone (:func:`~core.image_order.ray_casting.pixel_on_image_plane`), so each
thread works them out once for every column and row: a primary ray then costs
two divisions fewer, in the primary stage and again where its hit is shaded
(a Whitted frame of the lecture scene, one thread, took 1/1.03 of its time).
The shading makes a row's primary rays again before it shades the row's hits,
eight at a time in vector instructions (:func:`_row_rays`).
Each thread gets one scratch area and takes bands of neighbouring rows until
none are left (:mod:`core.image_order.kernels.intrinsics.bands`).  The parallel
kernel only starts one worker per thread, a plain compiled function: numba
optimises the body of a ``prange`` loop less well than an ordinary function
(about 1.3 times slower here).
"""

from __future__ import annotations

import math

import numpy as np
from numba import prange

from core.image_order import flat_layout
from core.image_order.intersect_triangle import ray_shear
from core.image_order.kernels.bvh_packet import (
    AXIS_FIELDS,
    PACKET_COLS,
    PACKET_ROWS,
    PACKET_SIZE,
    RAY_FIELDS,
    can_share_walk,
    packet_closest,
    packet_depth,
    packet_hit,
    ray_of,
    set_image_point,
    set_primary_rays,
)
from core.image_order.kernels.bvh_traverse import bvh_closest
from core.image_order.kernels.closest_hit import BVH, GRID, GRID_SPHERES, closest_hit
from core.image_order.kernels.intrinsics.bands import BAND_ROWS, take_band
from core.image_order.kernels.intrinsics.stop_flag import flag_raised
from core.image_order.kernels.jit import jit, jit_allocating, jit_inline, jit_parallel
from core.image_order.kernels.shade import shade_hit
from core.image_order.kernels.shared_work import shared_work, work_done
from core.image_order.ray_casting import pixel_on_image_plane, primary_ray_through, view_depth

PRIMARY_STAGE, SHADE_STAGE, SECONDARY_STAGE = range(3)


@jit_allocating
def make_scratch(method, n_prims, n_objects, bvh_depth):
    """Per-thread work arrays for :func:`core.image_order.kernels.closest_hit.closest_hit`.

    ``(mailbox, object_stamp, object_span, stamp, stack, stack_t)``, at the positions
    ``SCRATCH_*`` of :mod:`core.image_order.flat_layout`.
    """
    grid = method in (GRID, GRID_SPHERES)
    stack_size = 3 * bvh_depth + 2 if method == BVH else 1
    return (np.zeros(n_prims if grid else 1, np.int64),
            np.zeros(n_objects if grid else 1, np.int64),
            np.zeros((n_objects if grid else 1, 2)),
            np.zeros(1, np.int64),
            np.zeros(stack_size, np.int64),
            np.zeros(stack_size))


@jit_allocating
def children_array(ny, nx):
    """The uncleared ``children`` array of :func:`render_pass` for ``ny`` x ``nx`` pixels.

    Made here, not by numpy: numpy asks the system for 2 MB pages for every array of 4 MB or
    more, and the first touch of such a page clears all of it.  A pixel's row of ``children`` is
    written only where a ray goes on, so a frame touches a few rows here and there of an array
    that is fresh every frame (at 640 x 480, 39 MB: more than glibc ever keeps for reuse).  In 2 MB
    pages, each frame of the mirror and glass cleared some 13 of them (4-12 ms of sys time over
    the threads, 1-3 ms of the frame); the compiled code's allocator takes plain 4 KB pages, and
    clears only those touched (about 1,500, 6 MB).
    """
    return np.empty((ny, nx, flat_layout.N_SPAWNED, flat_layout.CHILD_SIZE))


def no_heat() -> np.ndarray:
    """The ``heat`` argument of :func:`render_pass` that counts nothing (an empty array of its type)."""
    return np.zeros((0, 0, flat_layout.HEAT_SIZE), np.int64)


@jit_inline
def _bounds_work(count):
    """The box and sphere tests counted so far: bounding spheres, BVH boxes, and the grid's cells
    walked (each a cuboid the ray enters), as the heat map's ``HEAT_BOUNDS_TESTS`` counts them."""
    return count[flat_layout.BOUNDS_TESTS] + count[flat_layout.CELLS]


@jit_inline
def _add_heat(heat, j, i, count, prim_before, bounds_before):
    """Add the tests counted since ``prim_before, bounds_before`` (:func:`_bounds_work`) to pixel
    ``(j, i)``'s heat, if kept."""
    if heat.shape[0] > 0:
        heat[j, i, flat_layout.HEAT_PRIM_TESTS] += count[flat_layout.PRIM_TESTS] - prim_before
        heat[j, i, flat_layout.HEAT_BOUNDS_TESTS] += _bounds_work(count) - bounds_before


@jit
def _primary_rows(first, last, cam, pxs, pys, opts, geo, grid, bvh, scratch, packet, hits, depth, objects,
                  count, heat):
    method = int(opts[flat_layout.OPT_ACCEL])
    if method == BVH and opts[flat_layout.OPT_PACKETS] > 0.0:  # see core.image_order.kernels.bvh_packet
        for j0 in range(first, last, PACKET_ROWS):
            for i0 in range(0, pxs.shape[0], PACKET_COLS):
                if flag_raised(opts, flat_layout.OPT_STOP):
                    return
                _primary_packet(j0, min(j0 + PACKET_ROWS, last), i0, min(i0 + PACKET_COLS, pxs.shape[0]), cam,
                                pxs, pys, geo, bvh, scratch, packet, hits, depth, objects, count, heat)
        return
    n_spheres = geo[flat_layout.GEO_N_SPHERES]
    stack, stack_t = scratch[flat_layout.SCRATCH_STACK], scratch[flat_layout.SCRATCH_STACK_T]
    for j in range(first, last):
        for i in range(pxs.shape[0]):
            if flag_raised(opts, flat_layout.OPT_STOP):
                return
            o, d, t_min, t_max = primary_ray_through(cam, pxs[i], pys[j])
            count[flat_layout.PRIMARY] += 1
            prim_before, bounds_before = count[flat_layout.PRIM_TESTS], _bounds_work(count)
            # BVH rays go straight to the traversal.  Through closest_hit, every array of every
            # structure would be bound anew for each ray, and numba updates the reference count of
            # each array it binds: a quarter of a primary ray's time.
            if method == BVH:
                h = bvh_closest(o, d, ray_shear(d[0], d[1], d[2]), t_min, t_max, False, bvh, n_spheres, stack,
                                stack_t, count)
            else:
                h = closest_hit(method, o, d, t_min, t_max, False, geo, grid, bvh, scratch, count)
            _add_heat(heat, j, i, count, prim_before, bounds_before)
            _write_primary(geo, hits, depth, objects, j, i, h, view_depth(cam, o, d, h[1]))


@jit_inline
def _primary_packet(j0, j1, i0, i1, cam, pxs, pys, geo, bvh, scratch, packet, hits, depth, objects, count,
                    heat):
    """The primary rays of pixels ``[j0, j1) x [i0, i1)`` through the BVH, as one packet when they
    can share the walk, else one by one.  The tests of a shared walk go to the heat map in equal
    parts (:func:`_share_walk`)."""
    rays, axes = packet
    n_spheres = geo[flat_layout.GEO_N_SPHERES]
    stack, stack_t = scratch[flat_layout.SCRATCH_STACK], scratch[flat_layout.SCRATCH_STACK_T]
    n = 0
    for j in range(j0, j1):
        for i in range(i0, i1):
            set_image_point(rays, n, pxs[i], pys[j])
            n += 1
    set_primary_rays(cam, rays, axes, n)
    count[flat_layout.PRIMARY] += n
    shared = bvh[0].shape[0] > 0 and can_share_walk(rays, n, True)
    if shared:
        prim_before, bounds_before = count[flat_layout.PRIM_TESTS], _bounds_work(count)
        packet_closest(n, rays, axes, bvh, n_spheres, stack, stack_t, count)
        if heat.shape[0] > 0:
            _share_walk(heat, j0, j1, i0, i1, n, count[flat_layout.PRIM_TESTS] - prim_before,
                        _bounds_work(count) - bounds_before)
    r = 0
    for j in range(j0, j1):
        for i in range(i0, i1):
            o, d, shear, t_min, t_max = ray_of(rays, axes, r)
            if shared:
                h = packet_hit(rays, axes, r, bvh)
            else:
                prim_before, bounds_before = count[flat_layout.PRIM_TESTS], _bounds_work(count)
                h = bvh_closest(o, d, shear, t_min, t_max, False, bvh, n_spheres, stack, stack_t, count)
                _add_heat(heat, j, i, count, prim_before, bounds_before)
            _write_primary(geo, hits, depth, objects, j, i, h, packet_depth(rays, r, h[1]))
            r += 1


@jit
def _share_walk(heat, j0, j1, i0, i1, n, prims, bounds):
    """A packet's shared walk, ``prims`` and ``bounds`` tests, into the heat of its ``n`` pixels
    ``[j0, j1) x [i0, i1)``: equal parts, the remainders one each to the first pixels."""
    r = 0
    for j in range(j0, j1):
        for i in range(i0, i1):
            heat[j, i, flat_layout.HEAT_PRIM_TESTS] += prims // n + (r < prims % n)
            heat[j, i, flat_layout.HEAT_BOUNDS_TESTS] += bounds // n + (r < bounds % n)
            r += 1


@jit_inline
def _write_primary(geo, hits, depth, objects, j, i, h, hit_depth):
    """Pixel ``(j, i)``'s closest hit ``h`` into the hits, its depth ``hit_depth`` (read where
    there is a hit) and the object it shows."""
    prim, t, b0, b1, b2 = h
    hits[j, i, flat_layout.HIT_PRIM], hits[j, i, flat_layout.HIT_T] = prim, t
    hits[j, i, flat_layout.HIT_B0], hits[j, i, flat_layout.HIT_B1] = b0, b1
    hits[j, i, flat_layout.HIT_B2] = b2
    if prim >= 0:
        depth[j, i] = hit_depth
        objects[j, i] = geo[flat_layout.GEO_PRIM_OBJECT][prim]
    else:
        depth[j, i] = math.inf
        objects[j, i] = -1


@jit_inline
def _clip(color, j, i):
    """Clamp pixel ``(j, i)``'s finished colour to [0, 1], as ``np.clip`` does (NaN stays NaN)."""
    for a in range(3):
        if color[j, i, a] < 0.0:
            color[j, i, a] = 0.0
        elif color[j, i, a] > 1.0:
            color[j, i, a] = 1.0


@jit
def _as_hit(row):
    """A row of the hits array as the closest-hit tuple ``(prim, t, b0, b1, b2)``."""
    return (int(row[flat_layout.HIT_PRIM]), row[flat_layout.HIT_T], row[flat_layout.HIT_B0],
            row[flat_layout.HIT_B1], row[flat_layout.HIT_B2])


@jit_inline
def _row_rays(cam, pxs, py, rays):
    """The primary rays of a row of pixels (image plane points ``pxs``, ``py``) into ``rays``
    (6, nx): origins, then directions (:func:`~core.image_order.ray_casting.primary_ray_through`).

    One loop with no branch, which the compiler turns into vector instructions: eight pixels'
    square roots and divisions at a time (AVX-512), each lane rounding as one pixel's.  Worked out
    pixel by pixel within the shading, each ray's square root and divisions were waited on: a
    Whitted frame's shading took 1/0.90 of its time (lecture and mirror and glass, one thread).
    """
    for i in range(pxs.shape[0]):
        o, d, _, _ = primary_ray_through(cam, pxs[i], py)
        rays[0, i], rays[1, i], rays[2, i] = o
        rays[3, i], rays[4, i], rays[5, i] = d


@jit
def _shade_rows(first, last, cam, pxs, pys, hits, color, children, spawned, materials, lights, opts, geo,
                grid, bvh, scratch, rec, rays, count, heat):
    for j in range(first, last):
        _row_rays(cam, pxs, pys[j], rays)
        for i in range(pxs.shape[0]):
            if flag_raised(opts, flat_layout.OPT_STOP):
                return
            if hits[j, i, flat_layout.HIT_PRIM] < 0:
                spawned[j, i] = 0
                for a in range(3):
                    color[j, i, a] = opts[flat_layout.OPT_BACKGROUND + a]
                _clip(color, j, i)
                continue
            o, d = (rays[0, i], rays[1, i], rays[2, i]), (rays[3, i], rays[4, i], rays[5, i])
            prim_before, bounds_before = count[flat_layout.PRIM_TESTS], _bounds_work(count)
            shade_hit(o, d, _as_hit(hits[j, i]), 1.0, 0, materials, lights, opts, geo, grid, bvh, scratch,
                      count, rec, False)
            _add_heat(heat, j, i, count, prim_before, bounds_before)
            for a in range(3):
                color[j, i, a] = rec[flat_layout.REC_LOCAL + a]
            # Only the rays that go on are written: most pixels spawn none, and their rows of
            # ``children`` are then never touched (nor paged in).
            reflected = rec[flat_layout.REC_REFLECT + flat_layout.CHILD_STATUS] == flat_layout.CHILD_TRACED
            refracted = rec[flat_layout.REC_REFRACT + flat_layout.CHILD_STATUS] == flat_layout.CHILD_TRACED
            spawned[j, i] = (reflected * (1 << flat_layout.SPAWN_REFLECT)
                             + refracted * (1 << flat_layout.SPAWN_REFRACT))
            if spawned[j, i] == 0:  # the colour is final; the secondary stage finishes the others
                _clip(color, j, i)
            if reflected:
                for a in range(flat_layout.CHILD_SIZE):
                    children[j, i, flat_layout.SPAWN_REFLECT, a] = rec[flat_layout.REC_REFLECT + a]
            if refracted:
                for a in range(flat_layout.CHILD_SIZE):
                    children[j, i, flat_layout.SPAWN_REFRACT, a] = rec[flat_layout.REC_REFRACT + a]


@jit
def _secondary_rows(first, last, color, children, spawned, materials, lights, opts, geo, grid, bvh, scratch,
                    rec, stack, count, heat):
    method = int(opts[flat_layout.OPT_ACCEL])
    n_spheres = geo[flat_layout.GEO_N_SPHERES]
    t_start = 0.0 if opts[flat_layout.OPT_SCALED_OFFSET] > 0.0 else opts[flat_layout.OPT_EPSILON]
    o_at, d_at = flat_layout.CHILD_ORIGIN, flat_layout.CHILD_DIRECTION
    for j in range(first, last):
        for i in range(color.shape[1]):
            if spawned[j, i] == 0:
                continue
            prim_before, bounds_before = count[flat_layout.PRIM_TESTS], _bounds_work(count)
            top = 0
            for kind in range(flat_layout.N_SPAWNED):
                if spawned[j, i] & (1 << kind):
                    for a in range(flat_layout.CHILD_SIZE):
                        stack[top, a] = children[j, i, kind, a]
                    stack[top, flat_layout.STACK_GENERATION] = 1.0
                    stack[top, flat_layout.STACK_KIND] = kind
                    top += 1
            while top > 0:
                if flag_raised(opts, flat_layout.OPT_STOP):
                    return
                top -= 1
                o = (stack[top, o_at], stack[top, o_at + 1], stack[top, o_at + 2])
                d = (stack[top, d_at], stack[top, d_at + 1], stack[top, d_at + 2])
                weight = stack[top, flat_layout.CHILD_WEIGHT]
                depth = int(stack[top, flat_layout.STACK_GENERATION])
                kind = stack[top, flat_layout.STACK_KIND]
                count[flat_layout.REFLECTION if kind == flat_layout.SPAWN_REFLECT
                      else flat_layout.REFRACTION] += 1
                if method == BVH:  # inlined, as for the primary rays
                    h = bvh_closest(o, d, ray_shear(d[0], d[1], d[2]), t_start, math.inf, False, bvh,
                                    n_spheres, scratch[flat_layout.SCRATCH_STACK],
                                    scratch[flat_layout.SCRATCH_STACK_T], count)
                else:
                    h = closest_hit(method, o, d, t_start, math.inf, False, geo, grid, bvh, scratch, count)
                if h[flat_layout.HIT_PRIM] < 0:
                    for a in range(3):
                        color[j, i, a] += weight * opts[flat_layout.OPT_BACKGROUND + a]
                    continue
                shade_hit(o, d, h, weight, depth, materials, lights, opts, geo, grid, bvh, scratch, count,
                          rec, False)
                for a in range(3):
                    color[j, i, a] += weight * rec[flat_layout.REC_LOCAL + a]
                for kind2 in range(flat_layout.N_SPAWNED):
                    at = (flat_layout.REC_REFLECT if kind2 == flat_layout.SPAWN_REFLECT
                          else flat_layout.REC_REFRACT)
                    if rec[at + flat_layout.CHILD_STATUS] == flat_layout.CHILD_TRACED:
                        for a in range(flat_layout.CHILD_SIZE):
                            stack[top, a] = rec[at + a]
                        stack[top, flat_layout.STACK_GENERATION] = depth + 1
                        stack[top, flat_layout.STACK_KIND] = kind2
                        top += 1
            _add_heat(heat, j, i, count, prim_before, bounds_before)
            _clip(color, j, i)


@jit_allocating
def _worker(stage, queue, cam, xs, ys, hits, depth, objects, color, children, spawned, materials, lights,
            opts, geo, grid, bvh, bvh_depth, count, heat):
    scratch = make_scratch(int(opts[flat_layout.OPT_ACCEL]), geo[flat_layout.GEO_ROWS].shape[0],
                           materials.shape[0], bvh_depth)
    rec = np.empty(flat_layout.record_size(lights.shape[0]))
    rays = np.empty((6, xs.shape[0]))  # a row's primary rays, as the shading reads them
    # of the secondary rays
    stack = np.empty((2 * int(opts[flat_layout.OPT_MAX_DEPTH]) + 4, flat_layout.STACK_SIZE))
    packet = (np.empty(PACKET_SIZE * RAY_FIELDS), np.empty(PACKET_SIZE * AXIS_FIELDS, np.int64))
    pxs, pys = np.empty(xs.shape[0]), np.empty(ys.shape[0])  # the pixels' points on the image plane
    for i in range(xs.shape[0]):
        pxs[i] = pixel_on_image_plane(cam, xs[i], 0.0)[0]
    for j in range(ys.shape[0]):
        pys[j] = pixel_on_image_plane(cam, 0.0, ys[j])[1]
    while True:
        first = take_band(queue) * BAND_ROWS
        if first >= ys.shape[0] or flag_raised(opts, flat_layout.OPT_STOP):
            break
        last = min(first + BAND_ROWS, ys.shape[0])
        if stage == PRIMARY_STAGE:
            _primary_rows(first, last, cam, pxs, pys, opts, geo, grid, bvh, scratch, packet, hits, depth,
                          objects, count, heat)
        elif stage == SHADE_STAGE:
            _shade_rows(first, last, cam, pxs, pys, hits, color, children, spawned, materials, lights, opts,
                        geo, grid, bvh, scratch, rec, rays, count, heat)
        else:
            _secondary_rows(first, last, color, children, spawned, materials, lights, opts, geo, grid, bvh,
                            scratch, rec, stack, count, heat)


@jit_parallel
def render_pass(stage, cam, xs, ys, hits, depth, objects, color, children, spawned, materials, lights, opts,
                geo, grid, bvh, bvh_depth, n_workers, heat):
    """Run one stage of the render over the pixels ``xs`` x ``ys``, in parallel; return its counters.

    Parameters
    ----------
    stage : int
        ``PRIMARY_STAGE``: closest hit of every pixel's primary ray into
        ``hits`` (ny, nx, HIT_SIZE) ``(prim, t, b0, b1, b2)`` (prim -1: nothing hit) and
        its camera-space depth into ``depth`` (ny, nx) (``inf`` on a miss), the object hit into
        ``objects`` (ny, nx) int64 (-1 on a miss).
        ``SHADE_STAGE``: local colour of each hit into ``color`` (ny, nx, 3)
        (the background on a miss), clamped to [0, 1] where no ray goes on, and the
        reflected and refracted rays it
        spawns: ``spawned`` (ny, nx) uint8 gets bit ``1 << kind`` set for every ray of kind
        ``SPAWN_*`` that will be traced, and only those rays are written into
        ``children`` (ny, nx, N_SPAWNED, CHILD_SIZE).
        ``SECONDARY_STAGE``: trace those rays and all their descendants, adding
        ``weight * colour`` of every hit (or of the background) to ``color``, then clamp
        each of those pixels to [0, 1].  After the three stages ``color`` is the image.
    cam, opts, materials, lights : arrays laid out as in :mod:`core.image_order.flat_layout`.
    xs, ys : (nx,) and (ny,) float64, pixel columns and rows.
    geo, grid, bvh : kernel tuples of the geometry and its structures.
    bvh_depth : int, depth of the BVH (size of the traversal stack).
    n_workers : int, threads to share the bands (``numba.get_num_threads()``; asked
        by the caller, as a compiled call to it would keep this kernel out of the cache).
    heat : (ny, nx, HEAT_SIZE) int64, each pixel's primitive tests and its box and sphere
        tests (:func:`_bounds_work`; all its rays, this stage's) are added to it;
        :func:`no_heat` to keep none.

    Returns
    -------
    (N_COUNTERS,) int64, rays by kind and work done.
    """
    queue, counters = shared_work(n_workers)
    for w in prange(n_workers):
        _worker(stage, queue, cam, xs, ys, hits, depth, objects, color, children, spawned, materials, lights,
                opts, geo, grid, bvh, bvh_depth, counters[w], heat)
    return work_done(counters)
