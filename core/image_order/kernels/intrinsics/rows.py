"""A packet's rows: filled from an array of points (three coordinates a point, one row an axis),
and a row's least or greatest number.

A packet of rays (:mod:`core.image_order.kernels.bvh_packet`) keeps each number of its rays in a
row of sixteen, so that its tests read four or eight rays' numbers in one load.  The batch of
shadow rays holds them the other way, one ray's three coordinates after another (``(N, 3)``,
C order, float32).  :func:`deinterleave3` turns sixteen of them into three rows with one load,
a widening and a few shuffles; numba's loop read and wrote them one number at a time (on the
lecture scene's shadow rays, about half of the time spent making a packet).
:func:`row_least` and :func:`row_greatest` halve a row in registers with numba's ``min`` and
``max`` comparisons, in the order a loop halving it in memory would make them.
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from core.image_order.kernels.intrinsics.simd import F32, F64, I32, load

#: Numbers in a row (the rays of a packet, :data:`core.image_order.kernels.bvh_packet.PACKET_SIZE`).
ROW = 16


@intrinsic
def deinterleave3(typingctx, points, start, rows, x_at, y_at, z_at):
    """Copy points ``start .. start + ROW - 1`` of ``points`` (``(N, 3)`` float32, C order, with at
    least ``start + ROW`` points) into three rows of ``ROW`` numbers of the float64 array ``rows``,
    each widened (exactly): the x coordinates from flat index ``x_at`` on, y from ``y_at``, z from
    ``z_at``."""
    if points.dtype != types.float32:
        return None
    signature = types.none(points, start, rows, x_at, y_at, z_at)

    def codegen(context, builder, sig, args):
        source, row_type = ir.VectorType(F64, 3 * ROW), ir.VectorType(F64, ROW)
        points = context.make_array(sig.args[0])(context, builder, args[0]).data
        rows_data = context.make_array(sig.args[2])(context, builder, args[2]).data
        at = builder.mul(args[1], ir.Constant(args[1].type, 3))
        values = builder.fpext(load(builder, points, at, ir.VectorType(F32, 3 * ROW)), source)
        for axis, at in enumerate(args[3:6]):
            order = ir.Constant(ir.VectorType(I32, ROW), [3 * r + axis for r in range(ROW)])
            row = builder.shuffle_vector(values, ir.Constant(source, ir.Undefined), order)
            builder.store(row, builder.bitcast(builder.gep(rows_data, [at]), row_type.as_pointer()), align=8)
        return context.get_dummy_value()

    return signature, codegen


def _halved(builder, values, compare):
    """Halve the vector ``values`` until one lane is left: each lane ``r`` of the lower half becomes
    lane ``r + half`` where ``compare`` holds between that and lane ``r``, else keeps its own.  As
    numba's ``min`` (``compare`` ``<``) and ``max`` (``>``) of two floats, lane ``r`` first: ties,
    signed zeros and NaN come out as they do from those."""
    width = values.type.count
    while width > 1:
        half = width // 2
        own = builder.shuffle_vector(values, values, ir.Constant(ir.VectorType(I32, half), list(range(half))))
        other = builder.shuffle_vector(values, values,
                                       ir.Constant(ir.VectorType(I32, half), list(range(half, width))))
        values = builder.select(builder.fcmp_ordered(compare, other, own), other, own)
        width = half
    return builder.extract_element(values, ir.Constant(I32, 0))


def _row_extreme(rows, at, compare):
    signature = types.float64(rows, at)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        return _halved(builder, load(builder, data, args[1], ir.VectorType(F64, ROW)), compare)

    return signature, codegen


@intrinsic
def row_least(typingctx, rows, at):
    """The least of the ``ROW`` numbers of the float64 array ``rows`` from flat index ``at`` on: the
    number, bit for bit, that halving the row in memory with numba's ``min`` (``rows[r] =
    min(rows[r], rows[r + half])`` for ``half`` 8, 4, 2, 1) leaves in ``rows[at]``."""
    return _row_extreme(rows, at, "<")


@intrinsic
def row_greatest(typingctx, rows, at):
    """The greatest of the ``ROW`` numbers from ``rows[at]`` on, as :func:`row_least` with ``max``."""
    return _row_extreme(rows, at, ">")
