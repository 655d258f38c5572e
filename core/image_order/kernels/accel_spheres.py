"""Compiled closest-hit search without a spatial structure: every object, or bounding spheres first.

``"none"`` tests the ray against every primitive of the scene: the lecture's
plain ray casting, and the reference the other methods must agree with.

``"spheres"`` is the lecture's first speed-up: an analytic sphere is tested
directly; a mesh's bounding sphere (:mod:`core.image_order.bounding_spheres`) is tested
first, and the mesh's triangles only when the ray meets that sphere before
the closest hit found so far.
"""

from __future__ import annotations

from core.image_order.flat_layout import BOUNDS_TESTS, GEO_N_SPHERES, GEO_ROWS, PRIM_TESTS
from core.image_order.kernels.intersect import sphere_roots
from core.image_order.kernels.jit import jit, jit_inline
from core.image_order.kernels.primitives import no_hit, prim_hit


@jit_inline
def bounding_roots(o, d, bounding, ob):
    """Both crossings ``t_near <= t_far`` of the ray's line with object ``ob``'s bounding sphere
    (row ``(cx, cy, cz, r)`` of ``bounding``), ``(inf, inf)`` when it misses."""
    return sphere_roots(o[0], o[1], o[2], d[0], d[1], d[2], bounding[ob, 0], bounding[ob, 1], bounding[ob, 2],
                        bounding[ob, 3])


@jit
def brute_closest(o, d, shear, t_min, t_max, any_hit, geo, counters):
    """The closest crossing with ``t_min <= t < t_max`` (or any), testing every primitive.

    Returns ``(prim, t, b0, b1, b2)`` as :func:`core.image_order.kernels.bvh_traverse.bvh_closest`.
    """
    rows, n_spheres = geo[GEO_ROWS], geo[GEO_N_SPHERES]
    best = no_hit()
    best_t = t_max
    tests = 0
    for p in range(rows.shape[0]):
        tests += 1
        t, b0, b1, b2 = prim_hit(rows, p, p < n_spheres, o, d, shear, t_min, best_t)
        if t < best_t:
            best_t = t
            best = (p, t, b0, b1, b2)
            if any_hit:
                break
    counters[PRIM_TESTS] += tests
    return best


@jit
def spheres_closest(o, d, shear, t_min, t_max, any_hit, geo, counters):
    """The closest crossing with ``t_min <= t < t_max`` (or any), meshes behind bounding spheres."""
    rows, n_spheres, _, object_prims, bounding, _, _ = geo
    best = no_hit()
    best_t = t_max
    tests = 0
    spheres = 0
    for ob in range(object_prims.shape[0]):
        first, count = object_prims[ob, 0], object_prims[ob, 1]
        if first >= n_spheres:
            spheres += 1
            enter, leave = bounding_roots(o, d, bounding, ob)
            if enter >= best_t or leave < t_min:
                continue
        for p in range(first, first + count):
            tests += 1
            t, b0, b1, b2 = prim_hit(rows, p, p < n_spheres, o, d, shear, t_min, best_t)
            if t < best_t:
                best_t = t
                best = (p, t, b0, b1, b2)
                if any_hit:
                    counters[PRIM_TESTS] += tests
                    counters[BOUNDS_TESTS] += spheres
                    return best
    counters[PRIM_TESTS] += tests
    counters[BOUNDS_TESTS] += spheres
    return best
