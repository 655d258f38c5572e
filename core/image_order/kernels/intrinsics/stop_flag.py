"""Reading the stop flag that another thread raises while a kernel runs (:mod:`core.stopping`).

A plain ``opts[OPT_STOP]`` read in a loop may be hoisted out of it by the
compiler, which assumes no other thread writes the array; the kernel would
then never see the flag.  An atomic load is read anew every time.
"""

from __future__ import annotations

from numba import types
from numba.core import cgutils
from numba.extending import intrinsic


@intrinsic
def flag_raised(typingctx, array, index):
    """Whether ``array[index]`` (a float64 array) is not 0, read atomically."""
    signature = types.boolean(array, index)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        at = context.cast(builder, args[1], sig.args[1], types.intp)
        value = builder.load_atomic(cgutils.gep(builder, data, at), "monotonic", 8)
        return builder.fcmp_unordered("!=", value, context.get_constant(types.float64, 0.0))

    return signature, codegen
