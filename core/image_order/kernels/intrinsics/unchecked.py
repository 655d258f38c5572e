"""Array reads and writes at a flat index, without numba's check for a negative index.

numba indexes arrays the Python way: an index below zero counts from the
end, so every access with an index it cannot prove non-negative carries a
test and a fix-up.  The BVH traversal's stack pointer and node references
are such indices, and those fix-ups sat on the traversal's critical path
(without them the 100,000-triangle benchmark's primary stage ran about 4 %
faster, in six alternating processes; an isolated traversal loop, 4 to 10 %).  :func:`load_at` and
:func:`store_at` address element ``index`` of a C-contiguous array as if it
were flat, and trust the caller that ``0 <= index < array.size``: as with
numba's own indexing (bounds checks are off), nothing checks the end.
:func:`prefetch_at` asks for an element ahead of its read, at no risk.
"""

from __future__ import annotations

from llvmlite import ir
from numba import types
from numba.core import cgutils, errors
from numba.extending import intrinsic


def _contiguous(array) -> None:
    if not isinstance(array, types.Array) or array.layout != "C":
        raise errors.TypingError(f"expected a C-contiguous array, got {array}")


@intrinsic
def load_at(typingctx, array, index):
    """``array.flat[index]``."""
    _contiguous(array)
    signature = array.dtype(array, index)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        return builder.load(builder.gep(data, [args[1]]))

    return signature, codegen


@intrinsic
def store_at(typingctx, array, index, value):
    """``array.flat[index] = value`` (converted to the array's type)."""
    _contiguous(array)
    signature = types.none(array, index, value)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        converted = context.cast(builder, args[2], sig.args[2], sig.args[0].dtype)
        builder.store(converted, builder.gep(data, [args[1]]))
        return context.get_dummy_value()

    return signature, codegen


@intrinsic
def prefetch_at(typingctx, array, index):
    """Ask the caches for the line that holds ``array.flat[index]``, to be read soon (LLVM's
    ``llvm.prefetch``: a hint, which reads nothing and never faults)."""
    _contiguous(array)
    signature = types.none(array, index)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        pointer = builder.bitcast(builder.gep(data, [args[1]]), ir.IntType(8).as_pointer())
        i32 = ir.IntType(32)
        prefetch = cgutils.get_or_insert_function(
            builder.module, ir.FunctionType(ir.VoidType(), [pointer.type, i32, i32, i32]), "llvm.prefetch.p0")
        # a read (0), to be kept in every level of cache (3), of data (1)
        builder.call(prefetch, [pointer, ir.Constant(i32, 0), ir.Constant(i32, 3), ir.Constant(i32, 1)])
        return context.get_dummy_value()

    return signature, codegen
