"""Four watertight ray-triangle tests at once, lane for lane the same arithmetic as the scalar test.

The BVH keeps the triangles of each leaf in groups of four, stored side by
side: for corner ``v`` (A, B, C) and axis ``a`` the four triangles' numbers
sit at ``v * CORNER_STRIDE + a * AXIS_STRIDE + lane``.  One vector load then
brings, say, the z coordinate of all four corners A, and
:func:`triangle_test4` runs the test of
:func:`~core.image_order.kernels.intersect.triangle_hit` (translate, permute,
shear, three edge functions, the sign test, ``t``) on all four triangles in
the same instructions (see :mod:`core.image_order.kernels.intrinsics.simd`).
:func:`triangle_test4x2` tests one group against two rays at once, in vectors
of eight lanes: a packet's rays that enter the same leaf go through it in
pairs (:mod:`core.image_order.kernels.bvh_packet`).

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
from core.image_order.kernels.intrinsics.simd import F64, FOUR_F64, I32, LANES, constant, fabs, lanes, load

AXIS_STRIDE = LANES
CORNER_STRIDE = 3 * AXIS_STRIDE
#: Numbers per group of four triangles.
GROUP_SIZE = 3 * CORNER_STRIDE
#: A lane's result when only the exact scalar test can decide it.
UNSURE = -math.inf


def _crossings(builder, data, start, rays):
    """The test of one group against ``len(rays)`` rays (one or two), four lanes a ray, as vectors
    of ``4 * len(rays)`` lanes: ``(t, e0, e1, e2, candidates)``, the last the comparison
    ``t < t_max`` (:func:`triangle_test4`).  ``rays`` holds each ray's
    ``(kx, ky, kz, okx, oky, okz, sx, sy, sz, t_min, t_max)``."""
    width = LANES * len(rays)
    index_type = start.type

    def joined(fours):
        """One vector of the rays' four-lane vectors, the first ray's lanes first."""
        if len(fours) == 1:
            return fours[0]
        order = ir.Constant(ir.VectorType(I32, width), list(range(width)))
        return builder.shuffle_vector(fours[0], fours[1], order)

    def coordinate(corner, k):
        """Corner ``corner`` of the four triangles on each ray's shear axis ``k`` (0: kx, 1: ky, 2: kz)."""
        fours = []
        for ray in rays:
            axis = ray[k]
            offset = builder.mul(builder.sext(axis, index_type) if axis.type != index_type else axis,
                                 ir.Constant(index_type, AXIS_STRIDE))
            index = builder.add(builder.add(start, ir.Constant(index_type, corner * CORNER_STRIDE)), offset)
            fours.append(load(builder, data, index, FOUR_F64))
        return joined(fours)

    def spread(k):
        """Number ``k`` of each ray, in that ray's four lanes."""
        vector = ir.Constant(ir.VectorType(F64, width), ir.Undefined)
        for lane in range(width):
            vector = builder.insert_element(vector, rays[lane // LANES][k], ir.Constant(I32, lane))
        return vector

    okx, oky, okz, sx, sy, sz, t_min, t_max = [spread(k) for k in range(3, 11)]
    x, y, z = [], [], []
    for corner in range(3):
        z.append(builder.fsub(coordinate(corner, 2), okz))
        x.append(builder.fadd(builder.fsub(coordinate(corner, 0), okx), builder.fmul(sx, z[-1])))
        y.append(builder.fadd(builder.fsub(coordinate(corner, 1), oky), builder.fmul(sy, z[-1])))
    edges, sure = [], None
    for i, j in ((1, 2), (2, 0), (0, 1)):
        left, right = builder.fmul(x[i], y[j]), builder.fmul(y[i], x[j])
        value = builder.fsub(left, right)
        bound = builder.fadd(builder.fmul(constant(EDGE_ERROR, width),
                                          builder.fadd(fabs(builder, left), fabs(builder, right))),
                             constant(UNDERFLOW, width))
        trusted = builder.fcmp_ordered(">", fabs(builder, value), bound)
        sure = trusted if sure is None else builder.and_(sure, trusted)
        edges.append(value)
    zero = constant(0.0, width)
    negative = builder.or_(builder.or_(builder.fcmp_ordered("<", edges[0], zero),
                                       builder.fcmp_ordered("<", edges[1], zero)),
                           builder.fcmp_ordered("<", edges[2], zero))
    positive = builder.or_(builder.or_(builder.fcmp_ordered(">", edges[0], zero),
                                       builder.fcmp_ordered(">", edges[1], zero)),
                           builder.fcmp_ordered(">", edges[2], zero))
    det = builder.fadd(builder.fadd(edges[0], edges[1]), edges[2])
    inside = builder.and_(builder.not_(builder.and_(negative, positive)),
                          builder.fcmp_unordered("!=", det, zero))
    # t only where some lane's ray passes inside its triangle: the division is the test's
    # slowest instruction, and most tests (a shadow ray's near its own surface) have no lane inside.
    any_inside = builder.icmp_unsigned("!=", builder.bitcast(inside, ir.IntType(width)),
                                       ir.Constant(ir.IntType(width), 0))
    before = builder.basic_block
    with builder.if_then(any_inside, likely=False):
        weighted = [builder.fmul(edges[c], builder.fmul(z[c], sz)) for c in range(3)]
        divided = builder.fdiv(builder.fadd(builder.fadd(weighted[0], weighted[1]), weighted[2]), det)
        computed = builder.basic_block
    t = builder.phi(divided.type)
    t.add_incoming(divided, computed)
    t.add_incoming(constant(math.inf, width), before)
    in_range = builder.and_(builder.fcmp_ordered("<=", t_min, t), builder.fcmp_ordered("<", t, t_max))
    result = builder.select(builder.and_(inside, in_range), t, constant(math.inf, width))
    result = builder.select(sure, result, constant(UNSURE, width))
    return (result, *edges, builder.fcmp_ordered("<", result, t_max))


def _quarters(context, builder, four, vectors, ray):
    """Ray ``ray``'s lanes (``4 ray`` to ``4 ray + 3``) of each of the vectors ``(t, e0, e1, e2)``,
    as numba tuples of four, and of the comparison ``candidates`` as the bits of an int64."""
    *numbers, candidates = vectors
    bits = builder.zext(builder.bitcast(candidates, ir.IntType(candidates.type.count)), ir.IntType(64))
    if ray:
        bits = builder.lshr(bits, ir.Constant(ir.IntType(64), LANES * ray))
    bits = builder.and_(bits, ir.Constant(ir.IntType(64), (1 << LANES) - 1))
    return [lanes(context, builder, four, v, LANES * ray) for v in numbers] + [bits]


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
    (t, e0, e1, e2, candidates) : four tuples of four floats, one number per triangle
        ``t`` of the crossing, ``inf`` on a miss, ``UNSURE`` where the scalar
        test must decide; and the edge functions
        (:func:`~core.image_order.intersect_triangle.edge_functions`).  (Four
        tuples of four, not one of sixteen: numba picks a lane of a tuple with a
        branch per element.)  ``candidates`` has bit ``q`` set where lane ``q``
        is below ``t_max``: a crossing, or ``UNSURE``; only those lanes need
        to be picked.
    """
    four = types.UniTuple(types.float64, LANES)
    signature = types.Tuple((four,) * 4 + (types.int64,))(groups, start, kx, ky, kz, okx, oky, okz, sx, sy,
                                                          sz, t_min, t_max)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        vectors = _crossings(builder, data, args[1], [args[2:]])
        return context.make_tuple(builder, sig.return_type, _quarters(context, builder, four, vectors, 0))

    return signature, codegen


@intrinsic
def triangle_test4x2(typingctx, groups, start, ray_a, ray_b):
    """:func:`triangle_test4` for two rays at once, in vectors of eight lanes (one AVX-512
    instruction where the machine has it, for two of four lanes).  The rays need not share
    their shear axes: each ray's coordinates are loaded on its own axes and the two halves joined.

    ``ray_a`` and ``ray_b`` are each a ray's ``(kx, ky, kz, okx, oky, okz, sx, sy, sz, t_min,
    t_max)``; each lane rounds as it would alone.  Returns ``ray_a``'s five results, then
    ``ray_b``'s.
    """
    four = types.UniTuple(types.float64, LANES)
    signature = types.Tuple(((four,) * 4 + (types.int64,)) * 2)(groups, start, ray_a, ray_b)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        rays = [[builder.extract_value(ray, k) for k in range(11)] for ray in args[2:4]]
        vectors = _crossings(builder, data, args[1], rays)
        return context.make_tuple(builder, sig.return_type, _quarters(context, builder, four, vectors, 0)
                                  + _quarters(context, builder, four, vectors, 1))

    return signature, codegen
