"""The few LLVM vector helpers behind the tracer's SIMD intrinsics.

numba has no vector type of its own, so the tests that run on four boxes
or four triangles at once (:mod:`core.image_order.kernels.intrinsics.slabs4`,
:mod:`core.image_order.kernels.intrinsics.triangle4`) are written as numba intrinsics: short
functions that emit LLVM IR on ``<4 x double>`` values.  LLVM turns them into
whatever vector instructions the machine has (SSE2, AVX2, AVX-512).  No
fast-math flags are set, so every lane rounds exactly as the scalar code
does.
"""

from __future__ import annotations

from llvmlite import ir
from numba.core import cgutils

LANES = 4
F64 = ir.DoubleType()
I32 = ir.IntType(32)
F32 = ir.FloatType()
FOUR_F32 = ir.VectorType(F32, LANES)
FOUR_F64 = ir.VectorType(F64, LANES)


def splat(builder, value, width=LANES):
    """A vector of ``width`` lanes with ``value`` (a double) in every lane."""
    vector = ir.Constant(ir.VectorType(F64, width), ir.Undefined)
    for lane in range(width):
        vector = builder.insert_element(vector, value, ir.Constant(I32, lane))
    return vector


def constant(value: float, width=LANES):
    """A constant vector of ``width`` lanes with ``value`` in every lane."""
    return ir.Constant(ir.VectorType(F64, width), [ir.Constant(F64, value)] * width)


def load(builder, data, index, vector_type):
    """The numbers at ``data[index]`` onwards as one vector of ``vector_type`` (aligned as one number)."""
    pointer = builder.bitcast(builder.gep(data, [index]), vector_type.as_pointer())
    return builder.load(pointer, align=4 if vector_type.element == F32 else 8)


def fabs(builder, vector):
    """``|vector|`` lane by lane (a vector of doubles, any width)."""
    signature = ir.FunctionType(vector.type, [vector.type])
    name = f"llvm.fabs.v{vector.type.count}f64"
    return builder.call(cgutils.get_or_insert_function(builder.module, signature, name), [vector])


def lanes(context, builder, return_type, vector, first=0):
    """Lanes ``first`` to ``first + LANES - 1`` of ``vector`` as a numba tuple of floats."""
    values = [builder.extract_element(vector, ir.Constant(I32, first + lane)) for lane in range(LANES)]
    return context.make_tuple(builder, return_type, values)
