"""Image order: every pixel in turn.

A ray is cast from the eye through each pixel (ray casting,
:mod:`.ray_casting`) and, for mirrors and glass, traced further (ray
tracing).  The intersection tests, optics, shading, the effects plan and the
acceleration structures (bounding spheres, the grid of cuboids, the BVH) each
have a module; :mod:`.ray_tracing` renders an image and :mod:`.ray_tree`
records one pixel's rays.  Compiled hot loops are in :mod:`.kernels`.
"""
