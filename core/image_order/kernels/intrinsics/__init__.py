"""Speed only: SIMD and thread-scheduling intrinsics for the tracer's kernels.

Nothing here is a lecture concept.  These modules write LLVM IR (four boxes or
four triangles at once, one box for a packet's sixteen rays, the lowest bit of
a mask, an atomic counter that hands out bands of rows) so the compiled tracer
keeps pace with Embree.  Each computes exactly what the scalar code in
:mod:`core.image_order.kernels` computes; a student reading the tracer can
skip this folder.
"""
