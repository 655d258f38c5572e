"""Shadow rays in a batch: is anything between each point and its light?  Any hit, on all cores.

A shadow ray only asks whether something blocks the way to the light, so the
walk of the BVH stops at the first triangle it finds
(:func:`~core.image_order.kernels.bvh_traverse.bvh_closest` with ``any_hit``),
as shading traces them one by one (:mod:`core.image_order.kernels.shade`).
This kernel traces a whole batch of given rays, so that ``python -m app bench
trace`` can time the shadow rays alone, next to Embree's ``rtcOccluded16`` on
the same rays.  Sixteen consecutive rays go as one packet
(:func:`~core.image_order.kernels.bvh_packet.packet_occluded`) where they
can share a walk (one sign of ``d`` per axis; the bench's rays start at the
lit hits of neighbouring pixels, row by row, and go to one light), else one by
one; either way each ray gets the blocker and ``t`` it gets alone, bit for bit.

The rays are dealt out in chunks of neighbouring rays, taken by the threads
one at a time from a shared counter
(:func:`~core.image_order.kernels.intrinsics.bands.take_band`), as the
render's bands of rows are.

The rays come as float32 numbers, as the bench makes them and as Embree takes
them, so that both tracers read the same arrays; each number is widened to
float64 (exactly) as a packet is made, and everything after is float64.  Read
as float64 arrays, the rays were twice the bytes, and on the lecture scene's
rays (few tests each) the memory's time shows: a loop doing nothing but read
its 172,145 rays and write an answer each took 0.80 ms as float64 and 0.53 as
float32 (two threads, warm caches), where the whole kernel takes 1.3-2.1.

Only a blocked ray's answer is written (its blocker and ``t``); the caller fills both arrays
first (-1 and ``inf``, none), as Embree's ``rtcOccluded16`` sets ``tfar`` only where a ray is
blocked.  On the lecture scene's rays, 2% of them blocked, writing every ray's two numbers (16
bytes a ray, 2.75 MB) took a ninth of the kernel's time: 1.42 ms against 1.24 (two threads,
warm, the two ways alternating in one process 201 times).
"""

from __future__ import annotations

import numpy as np
from numba import prange

from core.image_order import flat_layout
from core.image_order.kernels.bvh_packet import (
    AXIS_FIELDS,
    PACKET_SIZE,
    RAY_FIELDS,
    can_share_walk,
    packet_blocker,
    packet_occluded,
    ray_of,
    set_rays,
    shear_rays,
)
from core.image_order.kernels.bvh_traverse import bvh_closest
from core.image_order.kernels.intrinsics.bands import take_band
from core.image_order.kernels.jit import jit_allocating, jit_parallel
from core.image_order.kernels.shared_work import shared_work, work_done

#: Rays per chunk a thread takes: neighbouring rays share the nodes they visit in the core's cache.
CHUNK_RAYS = 16 * PACKET_SIZE


@jit_allocating
def _worker(queue, origins, directions, t_min, t_max, bvh, n_spheres, bvh_depth, blockers, blocker_t, count):
    stack = np.zeros(3 * bvh_depth + 2, np.int64)
    stack_t = np.zeros(3 * bvh_depth + 2)
    stack_rays = np.zeros(3 * bvh_depth + 2, np.int64)
    rays, axes = np.empty(PACKET_SIZE * RAY_FIELDS), np.empty(PACKET_SIZE * AXIS_FIELDS, np.int64)
    n = origins.shape[0]
    while True:
        first = take_band(queue) * CHUNK_RAYS
        if first >= n:
            break
        for start in range(first, min(first + CHUNK_RAYS, n), PACKET_SIZE):
            size = min(PACKET_SIZE, n - start)
            set_rays(rays, axes, origins, directions, t_min, t_max, start, size)
            count[flat_layout.SHADOW] += size
            shared = bvh[0].shape[0] > 0 and can_share_walk(rays, size, False)
            if shared:
                packet_occluded(size, rays, axes, bvh, n_spheres, stack, stack_rays, count)
            else:  # one by one: each ray's lone walk takes its shear from the packet's rows
                shear_rays(rays, axes, size)
            for r in range(size):
                if shared:
                    blocker, t = packet_blocker(rays, axes, r, bvh)
                else:
                    o, d, shear, ray_t_min, ray_t_max = ray_of(rays, axes, r)
                    h = bvh_closest(o, d, shear, ray_t_min, ray_t_max, True, bvh, n_spheres, stack, stack_t,
                                    count)
                    blocker, t = h[flat_layout.HIT_PRIM], h[flat_layout.HIT_T]
                if blocker >= 0:  # an unblocked ray's answer stays the caller's: none
                    blockers[start + r], blocker_t[start + r] = blocker, t


@jit_parallel
def trace_shadow_rays(origins, directions, t_min, t_max, bvh, n_spheres, bvh_depth, n_workers, blockers,
                      blocker_t):
    """Whether each ray ``o + t d``, ``t_min <= t < t_max``, crosses anything; return the counters.

    Parameters
    ----------
    origins, directions : (N, 3) float32, world space; a direction need not be unit length.
    t_min, t_max : (N,) float32, each ray's admissible range of ``t`` (``t_max``: the light).
    bvh : tuple of :meth:`core.image_order.bvh.Bvh.kernel_tuple`; ``bvh_depth`` its depth.
    n_spheres : int, primitives below this index are spheres.
    n_workers : int, threads (``numba.get_num_threads()``, asked by the caller).
    blockers : (N,) int64, filled with -1 by the caller: a primitive that blocks each blocked ray
        is written in (any blocker, not necessarily the nearest), and into ``blocker_t`` (N,)
        float64, filled with ``inf``, where the ray crosses it; an unblocked ray's two numbers
        are left as they are.

    Returns
    -------
    (N_COUNTERS,) int64, shadow rays traced and the box and primitive tests.
    """
    queue, counters = shared_work(n_workers)
    for w in prange(n_workers):
        _worker(queue, origins, directions, t_min, t_max, bvh, n_spheres, bvh_depth, blockers, blocker_t,
                counters[w])
    return work_done(counters)
