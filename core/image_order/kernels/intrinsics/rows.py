"""A packet's rows filled from an array of points: three coordinates a point, one row an axis.

A packet of rays (:mod:`core.image_order.kernels.bvh_packet`) keeps each number of its rays in a
row of sixteen, so that its tests read four or eight rays' numbers in one load.  The tracer's
arrays hold the rays the other way, one ray's three coordinates after another (``(N, 3)``,
C order).  :func:`deinterleave3` turns sixteen of them into three rows with one load and a few
shuffles; numba's loop read and wrote them one number at a time (on the lecture scene's shadow
rays, about half of the time spent making a packet).
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.extending import intrinsic

from core.image_order.kernels.intrinsics.simd import F64, I32, load

#: Numbers in a row (the rays of a packet, :data:`core.image_order.kernels.bvh_packet.PACKET_SIZE`).
ROW = 16


@intrinsic
def deinterleave3(typingctx, points, start, rows, x_at, y_at, z_at):
    """Copy points ``start .. start + ROW - 1`` of ``points`` (``(N, 3)`` float64, C order, with at
    least ``start + ROW`` points) into three rows of ``ROW`` numbers of the float64 array ``rows``:
    the x coordinates from flat index ``x_at`` on, y from ``y_at``, z from ``z_at``."""
    signature = types.none(points, start, rows, x_at, y_at, z_at)

    def codegen(context, builder, sig, args):
        source, row_type = ir.VectorType(F64, 3 * ROW), ir.VectorType(F64, ROW)
        points = context.make_array(sig.args[0])(context, builder, args[0]).data
        rows_data = context.make_array(sig.args[2])(context, builder, args[2]).data
        values = load(builder, points, builder.mul(args[1], ir.Constant(args[1].type, 3)), source)
        for axis, at in enumerate(args[3:6]):
            order = ir.Constant(ir.VectorType(I32, ROW), [3 * r + axis for r in range(ROW)])
            row = builder.shuffle_vector(values, ir.Constant(source, ir.Undefined), order)
            builder.store(row, builder.bitcast(builder.gep(rows_data, [at]), row_type.as_pointer()), align=8)
        return context.get_dummy_value()

    return signature, codegen
