"""Compiled traversal of the bounding volume hierarchy (see :mod:`core.bvh`).

A ray walks the tree from the root with a small stack.  At an inner node it
tests the boxes of both children, goes on into the nearer child it hits and
pushes the farther one together with the distance where the ray enters it;
a pushed subtree whose entry lies beyond the closest hit found meanwhile is
dropped unvisited.  At a leaf it tests the primitives.  Boxes are only tested
against the part of the ray before the closest hit so far, so far subtrees
fall away quickly.
"""

from __future__ import annotations

import math

from core.kernels.trace_jit import jit
from core.kernels.trace_prims import BOUNDS_TESTS, PRIM_TESTS, no_hit, prim_hit


@jit
def box_entry(nodes, node, ox, oy, oz, ix, iy, iz, near, t_min, t_max):
    """Where the ray enters the box ``(lo, hi)`` of ``nodes[node]`` in ``[t_min, t_max]`` (``inf``: misses).

    ``ix, iy, iz`` are ``1 / d``; ``near`` holds the columns (0-5) of the
    box's near and far sides per axis, ``(nx, ny, nz, fx, fy, fz)`` (``lo`` is
    near where ``d >= 0``, ``hi`` where ``d < 0``).  A NaN from ``0 * inf`` (a
    ray lying in a slab's plane) fails every comparison and leaves the bounds
    unchanged (pbrt's rule); boxes are padded when built, so rounding never
    loses a touching ray.
    """
    nx, ny, nz, fx, fy, fz = near
    tx0 = (nodes[node, nx] - ox) * ix
    tx1 = (nodes[node, fx] - ox) * ix
    ty0 = (nodes[node, ny] - oy) * iy
    ty1 = (nodes[node, fy] - oy) * iy
    tz0 = (nodes[node, nz] - oz) * iz
    tz1 = (nodes[node, fz] - oz) * iz
    if tx0 > t_min:
        t_min = tx0
    if ty0 > t_min:
        t_min = ty0
    if tz0 > t_min:
        t_min = tz0
    if tx1 < t_max:
        t_max = tx1
    if ty1 < t_max:
        t_max = ty1
    if tz1 < t_max:
        t_max = tz1
    return t_min if t_min <= t_max else math.inf


@jit
def bvh_closest(o, d, shear, t_min, t_max, any_hit, bvh, n_spheres, stack, stack_t, counters):
    """The closest crossing with ``t_min <= t < t_max`` (or any, for shadow rays), through the BVH.

    Parameters
    ----------
    o, d : (3,) tuples, the ray; ``shear`` its :func:`~core.kernels.trace_intersect.ray_shear`.
    t_min, t_max : float, the admissible range of ``t``.
    any_hit : bool, stop at the first crossing found (shadow rays).
    bvh : tuple ``(boxes, links, order, rows)`` of :meth:`core.bvh.Bvh.kernel_tuple`.
    n_spheres : int, primitives below this index are spheres.
    stack : (D,) int64 and ``stack_t`` (D,) float64 scratch, ``D >=`` the tree's depth.
    counters : (N_COUNTERS,) int64, box and primitive tests are added.

    Returns
    -------
    (prim, t, b0, b1, b2) : the primitive index (-1 for none) and the crossing.
    """
    nodes, links, order, rows = bvh
    best = no_hit()
    if nodes.shape[0] == 0:
        return best
    ox, oy, oz = o
    ix, iy, iz = 1.0 / d[0], 1.0 / d[1], 1.0 / d[2]
    nx = 3 if ix < 0.0 else 0
    ny = 4 if iy < 0.0 else 1
    nz = 5 if iz < 0.0 else 2
    near = (nx, ny, nz, 3 - nx, 5 - ny, 7 - nz)
    best_t = t_max
    boxes = 1
    tests = 0
    top = 0
    node = 0
    enter = box_entry(nodes, 0, ox, oy, oz, ix, iy, iz, near, t_min, best_t)
    while True:
        if enter < best_t:
            info = links[node, 7]
            if info > 0:
                first = links[node, 6]
                for k in range(first, first + info):
                    tests += 1
                    prim = order[k]
                    t, b0, b1, b2 = prim_hit(rows, k, prim < n_spheres, o, d, shear, t_min, best_t)
                    if t < best_t:
                        best_t = t
                        best = (prim, t, b0, b1, b2)
                        if any_hit:
                            top = 0
                            break
            else:
                a = links[node, 6]
                b = a + 1
                ta = box_entry(nodes, a, ox, oy, oz, ix, iy, iz, near, t_min, best_t)
                tb = box_entry(nodes, b, ox, oy, oz, ix, iy, iz, near, t_min, best_t)
                boxes += 2
                if tb < ta:
                    a, b, ta, tb = b, a, tb, ta
                if tb < math.inf:
                    stack[top] = b
                    stack_t[top] = tb
                    top += 1
                node, enter = a, ta
                continue
        if top == 0:
            counters[BOUNDS_TESTS] += boxes
            counters[PRIM_TESTS] += tests
            return best
        top -= 1
        node, enter = stack[top], stack_t[top]
