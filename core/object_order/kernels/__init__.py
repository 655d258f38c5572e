"""Compiled (numba) hot loops of the object-order pipeline.

Cache: on import this package caches its kernels in the user's cache folder, in a
folder named after the contents of every file its kernels are made of
(:data:`SOURCES`; :mod:`core.compiling.kernel_cache`): every checkout and install of the same
code shares them, and a changed formula is never served from an old kernel.

Memory: the kernels write their large results into arrays the caller allocates
with numpy, which asks the system for huge pages for large arrays.  Memory a
kernel allocates itself comes in 4 KB pages, and at a million triangles the
page faults on a frame's fresh results cost more than the work done in them.
"""

from __future__ import annotations

from pathlib import Path

from core.compiling.jitable import register_all
from core.compiling.kernel_cache import share_cache

_KERNELS = Path(__file__).resolve().parent
_OBJECT_ORDER = _KERNELS.parent
#: Every file whose code ends up inside the compiled kernels: this folder and the
#: lecture modules whose formulas they compile in.  ``tests/core/object_order/test_raster.py``
#: checks that every ``core`` module a kernel imports is listed here.
SOURCES = sorted(_KERNELS.glob("*.py")) + [
    _OBJECT_ORDER / name for name in ("rasterization.py", "zbuffer.py", "blending.py", "depth_formats.py",
                                      "clipping.py", "culling.py", "flat_shading.py")] + [
    _OBJECT_ORDER.parent / "compiling" / name for name in ("jitable.py", "one_signature.py")]


share_cache(_KERNELS, SOURCES, "raster")
register_all()  # the lecture modules' formulas, before any kernel is compiled or loaded
