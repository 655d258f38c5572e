"""Compiled (numba) hot loops of the object-order pipeline.

Stale caches: numba checks a cached kernel only against the file that defines
it, not against the files whose ``register_jitable`` formulas it compiles in.
After an edit of, say, :mod:`core.object_order.rasterization`, the cached
rasterizer would silently keep the old fill rule.  So on import this package
hashes every file its kernels are made of (:data:`SOURCES`) and, when the
hash changed, deletes its cached kernels before any is loaded.

Memory: the kernels write their large results into arrays the caller allocates
with numpy, which asks the system for huge pages for large arrays.  Memory a
kernel allocates itself comes in 4 KB pages, and at a million triangles the
page faults on a frame's fresh results cost more than the work done in them.
"""

from __future__ import annotations

from pathlib import Path

from core.jitable import register_all
from core.kernel_cache import drop_stale_cache

_KERNELS = Path(__file__).resolve().parent
_OBJECT_ORDER = _KERNELS.parent
#: Every file whose code ends up inside the compiled kernels: this folder and the
#: lecture modules whose formulas they compile in.  ``tests/core/test_raster.py``
#: checks that every ``core`` module a kernel imports is listed here.
SOURCES = sorted(_KERNELS.glob("*.py")) + [
    _OBJECT_ORDER / name for name in ("rasterization.py", "zbuffer.py", "blending.py", "depth_formats.py",
                                      "clipping.py", "culling.py", "flat_shading.py")] + [
    _OBJECT_ORDER.parent / "jitable.py"]


drop_stale_cache(_KERNELS, SOURCES, "raster")
register_all()  # the lecture modules' formulas, before any kernel is compiled or loaded
