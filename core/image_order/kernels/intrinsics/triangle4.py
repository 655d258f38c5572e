"""Four watertight ray-triangle tests at once, lane for lane the same arithmetic as the scalar test.

The BVH keeps the triangles of each leaf in groups of four, stored side by
side: for corner ``v`` (A, B, C) and axis ``a`` the four triangles' numbers
sit at ``v * CORNER_STRIDE + a * AXIS_STRIDE + lane``.  One vector load then
brings, say, the z coordinate of all four corners A, and
:func:`triangle_test4` runs the test of
:func:`~core.image_order.kernels.intersect.triangle_hit` (translate, permute,
shear, three edge functions, the sign test, ``t``) on all four triangles in
the same instructions (see :mod:`core.image_order.kernels.intrinsics.simd`).

Exactness is kept by falling back rather than by doing it in vector form:
where a rounded edge function is too small to trust its sign, the scalar
test would redo it with error-free products; the vector test instead marks
the lane ``-inf`` ("too close to call") and the caller runs the scalar test
for that triangle.  Every other lane computes bit for bit what the scalar
test computes, so the hits are identical with or without the vector test.
Besides ``t`` the vector test reports each lane's three edge functions: where
the lane is sure they are the scalar test's own (and none of them is 0), so the
barycentric weights of the triangle finally hit are ``e_i / (e0 + e1 + e2)``,
the scalar test's own division
(:func:`~core.image_order.intersect_triangle.plane_crossing`), and that
triangle is not tested a second time for them.
"""

from __future__ import annotations

import math

from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from core.image_order.intersect_triangle import EDGE_ERROR, UNDERFLOW
from core.image_order.kernels.intrinsics.simd import FOUR_F64, LANES, constant, fabs, lanes, load, splat

AXIS_STRIDE = LANES
CORNER_STRIDE = 3 * AXIS_STRIDE
#: Numbers per group of four triangles.
GROUP_SIZE = 3 * CORNER_STRIDE
#: A lane's result when only the exact scalar test can decide it.
UNSURE = -math.inf


@intrinsic
def triangle_test4(typingctx, groups, start, kx, ky, kz, okx, oky, okz, sx, sy, sz, t_min, t_max):
    """The crossings of a ray with the four triangles of one group.

    Parameters
    ----------
    groups : 1-D float64 array of triangle groups, ``start`` the flat index of this one.
    kx, ky, kz, sx, sy, sz : the ray's :func:`~core.image_order.intersect_triangle.ray_shear`.
    okx, oky, okz : float, the ray origin's coordinates on the axes ``kx, ky, kz``.
    t_min, t_max : float, the admissible range of ``t``.

    Returns
    -------
    (t, e0, e1, e2) : four tuples of four floats, one number per triangle
        ``t`` of the crossing, ``inf`` on a miss, ``UNSURE`` where the scalar
        test must decide; and the edge functions
        (:func:`~core.image_order.intersect_triangle.edge_functions`).  (Four
        tuples of four, not one of sixteen: numba picks a lane of a tuple with a
        branch per element, and the hot loop picks each ``t``.)
    """
    four = types.UniTuple(types.float64, LANES)
    signature = types.Tuple((four, four, four, four))(groups, start, kx, ky, kz, okx, oky, okz, sx, sy, sz,
                                                      t_min, t_max)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        start, kx, ky, kz = args[1:5]
        index_type = start.type

        def coordinate(corner, axis):
            offset = builder.mul(builder.sext(axis, index_type) if axis.type != index_type else axis,
                                 ir.Constant(index_type, AXIS_STRIDE))
            index = builder.add(builder.add(start, ir.Constant(index_type, corner * CORNER_STRIDE)), offset)
            return load(builder, data, index, FOUR_F64)

        okx, oky, okz, sx, sy, sz = [splat(builder, value) for value in args[5:11]]
        x, y, z = [], [], []
        for corner in range(3):
            z.append(builder.fsub(coordinate(corner, kz), okz))
            x.append(builder.fadd(builder.fsub(coordinate(corner, kx), okx), builder.fmul(sx, z[-1])))
            y.append(builder.fadd(builder.fsub(coordinate(corner, ky), oky), builder.fmul(sy, z[-1])))
        edges, sure = [], None
        for i, j in ((1, 2), (2, 0), (0, 1)):
            left, right = builder.fmul(x[i], y[j]), builder.fmul(y[i], x[j])
            value = builder.fsub(left, right)
            bound = builder.fadd(builder.fmul(constant(EDGE_ERROR), builder.fadd(fabs(builder, left),
                                                                                  fabs(builder, right))),
                                 constant(UNDERFLOW))
            trusted = builder.fcmp_ordered(">", fabs(builder, value), bound)
            sure = trusted if sure is None else builder.and_(sure, trusted)
            edges.append(value)
        zero = constant(0.0)
        negative = builder.or_(builder.or_(builder.fcmp_ordered("<", edges[0], zero),
                                           builder.fcmp_ordered("<", edges[1], zero)),
                               builder.fcmp_ordered("<", edges[2], zero))
        positive = builder.or_(builder.or_(builder.fcmp_ordered(">", edges[0], zero),
                                           builder.fcmp_ordered(">", edges[1], zero)),
                               builder.fcmp_ordered(">", edges[2], zero))
        det = builder.fadd(builder.fadd(edges[0], edges[1]), edges[2])
        weighted = [builder.fmul(edges[c], builder.fmul(z[c], sz)) for c in range(3)]
        t = builder.fdiv(builder.fadd(builder.fadd(weighted[0], weighted[1]), weighted[2]), det)
        inside = builder.and_(builder.not_(builder.and_(negative, positive)),
                              builder.fcmp_unordered("!=", det, zero))
        in_range = builder.and_(builder.fcmp_ordered("<=", splat(builder, args[11]), t),
                                builder.fcmp_ordered("<", t, splat(builder, args[12])))
        result = builder.select(builder.and_(inside, in_range), t, constant(math.inf))
        result = builder.select(sure, result, constant(UNSURE))
        return context.make_tuple(builder, sig.return_type,
                                  [lanes(context, builder, sig.return_type[0], v) for v in (result, *edges)])

    return signature, codegen
