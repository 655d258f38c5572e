"""Object order: every polygon in turn.

Culling, clipping to the viewing pyramid (frustum), projection, rasterization
and the z-buffer, with transparency blended last; :mod:`.pipeline` runs them
in the lecture's order.  Compiled hot loops are in :mod:`.kernels`.
"""
