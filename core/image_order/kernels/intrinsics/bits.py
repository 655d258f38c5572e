"""Bits of a mask: the lowest set bit, for loops that visit only the lanes a vector test selected, and
how many are set."""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.core import cgutils
from numba.extending import intrinsic

_I64 = ir.IntType(64)


@intrinsic
def lowest_bit(typingctx, bits):
    """The index of the lowest set bit of the int64 ``bits``, which must not be 0 (one instruction:
    ``llvm.cttz``)."""
    signature = types.int64(types.int64)

    def codegen(context, builder, sig, args):
        count = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_I64, [_I64, ir.IntType(1)]),
                                               "llvm.cttz.i64")
        return builder.call(count, [args[0], ir.Constant(ir.IntType(1), 1)])

    return signature, codegen


@intrinsic
def bit_count(typingctx, bits):
    """How many bits of the int64 ``bits`` are set (one instruction: ``llvm.ctpop``)."""
    signature = types.int64(types.int64)

    def codegen(context, builder, sig, args):
        count = cgutils.get_or_insert_function(builder.module, ir.FunctionType(_I64, [_I64]),
                                               "llvm.ctpop.i64")
        return builder.call(count, [args[0]])

    return signature, codegen
