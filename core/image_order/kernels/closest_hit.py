"""The one question every ray asks: what does it hit first?  Answered by the chosen method.

:func:`closest_hit` dispatches on the acceleration code of
:data:`core.image_order.flat_layout.ACCEL_CODES`; all methods call the same
primitive tests, so they return bit-identical hits and differ only in the
work counted in ``counters``.

:func:`closest_hit` itself is inlined where it is called; the traversal of
each method is compiled once and called from there (the render's rays and
the shadow rays of shading inline the BVH traversal instead, see
:mod:`core.image_order.kernels.render` and :mod:`core.image_order.kernels.shade`).
"""

from __future__ import annotations

from core.image_order import flat_layout
from core.image_order.intersect_triangle import ray_shear
from core.image_order.kernels.accel_grid import grid_closest
from core.image_order.kernels.accel_spheres import brute_closest, spheres_closest
from core.image_order.kernels.bvh_traverse import bvh_closest
from core.image_order.kernels.jit import jit, jit_inline

NONE, SPHERES, GRID, GRID_SPHERES, BVH = range(5)


@jit
def _bvh_closest(o, d, shear, t_min, t_max, any_hit, bvh, n_spheres, stack, stack_t, counters):
    return bvh_closest(o, d, shear, t_min, t_max, any_hit, bvh, n_spheres, stack, stack_t, counters)


@jit
def _closest_other(method, o, d, shear, t_min, t_max, any_hit, geo, grid, scratch, counters):
    if method in (GRID, GRID_SPHERES):
        return grid_closest(o, d, shear, t_min, t_max, any_hit, method == GRID_SPHERES, geo, grid,
                            scratch[:flat_layout.SCRATCH_GRID], counters)
    if method == SPHERES:
        return spheres_closest(o, d, shear, t_min, t_max, any_hit, geo, counters)
    return brute_closest(o, d, shear, t_min, t_max, any_hit, geo, counters)


@jit_inline
def closest_hit(method, o, d, t_min, t_max, any_hit, geo, grid, bvh, scratch, counters):
    """The closest crossing of ``o + t d`` with ``t_min <= t < t_max``; with ``any_hit`` any crossing.

    Parameters
    ----------
    method : int, acceleration code (``NONE`` ... ``BVH``).
    o, d : (3,) float tuples, world space; ``d`` need not be unit length.
    t_min, t_max : float.
    any_hit : bool, a shadow ray: any crossing will do.
    geo, grid, bvh : kernel tuples of the geometry and its structures.
    scratch : per-thread tuple ``(mailbox, object_stamp, object_span, stamp, stack, stack_t)``.
    counters : (N_COUNTERS,) int64, the work is added.

    Returns
    -------
    (prim, t, b0, b1, b2)
        Primitive index (-1 for none), ``t`` (``inf`` for none) and a
        triangle's barycentric weights of its corners ``A, B, C``.
    """
    shear = ray_shear(d[0], d[1], d[2])
    if method == BVH:
        return _bvh_closest(o, d, shear, t_min, t_max, any_hit, bvh, geo[flat_layout.GEO_N_SPHERES],
                            scratch[flat_layout.SCRATCH_STACK], scratch[flat_layout.SCRATCH_STACK_T],
                            counters)
    return _closest_other(method, o, d, shear, t_min, t_max, any_hit, geo, grid, scratch, counters)
