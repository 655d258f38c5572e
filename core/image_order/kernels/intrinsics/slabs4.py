"""Four slab tests at once: where a ray enters each of the four child boxes of a wide BVH node.

A ray enters an axis-aligned box where it has crossed the near plane of all
three slabs (x, y, z) and leaves it where it crosses the first far plane; it
hits the box when the entry comes before the exit.  The four boxes of a node
(:mod:`core.image_order.bvh`) are stored as six rows of four float32 numbers (``lo x``,
``lo y``, ``lo z``, ``hi x``, ``hi y``, ``hi z``), so one vector load brings
the same side of all four boxes and every step of the test runs on the four
boxes in one instruction (SIMD), the way Embree tests its wide nodes.

:func:`slab_test4` widens the float32 sides to float64 exactly and computes
in float64, as the scalar test would (see :mod:`core.image_order.kernels.intrinsics.simd`).
The comparisons keep pbrt's rule for a ray lying in a slab's plane:
``0 * inf`` is NaN, which fails every comparison and leaves the bound
unchanged.
"""

from __future__ import annotations

import math

from numba import types
from numba.extending import intrinsic

from core.image_order.kernels.intrinsics.simd import FOUR_F32, FOUR_F64, constant, lanes, load, splat


@intrinsic
def slab_test4(typingctx, rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy, oz, ix, iy, iz,
               t_min, t_max):
    """Entry distances of the ray into four boxes, ``inf`` where it misses one.

    Parameters
    ----------
    rows : 1-D float32 array of the wide nodes, flattened.
    near_x ... far_z : int
        Flat indices of the rows holding the four boxes' near and far sides
        per axis (``lo`` is near where the direction is positive, ``hi``
        where it is negative).
    ox, oy, oz : float, the ray origin; ``ix, iy, iz`` : ``1 / d``.
    t_min, t_max : float, the part of the ray that counts.

    Returns
    -------
    (t0, t1, t2, t3) : floats, where the ray enters each box in ``[t_min, t_max]``.
    """
    signature = types.UniTuple(types.float64, 4)(rows, near_x, near_y, near_z, far_x, far_y, far_z, ox, oy,
                                                 oz, ix, iy, iz, t_min, t_max)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data

        def side(index):
            return builder.fpext(load(builder, data, index, FOUR_F32), FOUR_F64)

        origin = [splat(builder, value) for value in args[7:10]]
        inverse = [splat(builder, value) for value in args[10:13]]
        enter, leave = splat(builder, args[13]), splat(builder, args[14])
        for axis in range(3):
            t_near = builder.fmul(builder.fsub(side(args[1 + axis]), origin[axis]), inverse[axis])
            t_far = builder.fmul(builder.fsub(side(args[4 + axis]), origin[axis]), inverse[axis])
            enter = builder.select(builder.fcmp_ordered(">", t_near, enter), t_near, enter)
            leave = builder.select(builder.fcmp_ordered("<", t_far, leave), t_far, leave)
        entry = builder.select(builder.fcmp_ordered("<=", enter, leave), enter, constant(math.inf))
        return lanes(context, builder, sig.return_type, entry)

    return signature, codegen
