"""Compiled (numba) hot loops of the object-order pipeline.

Stale caches: numba checks a cached kernel only against the file that defines
it, not against the files whose ``register_jitable`` formulas it compiles in.
After an edit of, say, :mod:`core.object_order.rasterization`, the cached
rasterizer would silently keep the old fill rule.  So on import this package
hashes every file its kernels are made of (:data:`SOURCES`) and, when the
hash changed, deletes its cached kernels before any is loaded.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba import config

_KERNELS = Path(__file__).resolve().parent
_OBJECT_ORDER = _KERNELS.parent
#: Every file whose code ends up inside the compiled kernels: this folder and the
#: lecture modules whose formulas they compile in.  ``tests/core/test_raster.py``
#: checks that every ``core`` module a kernel imports is listed here.
SOURCES = sorted(_KERNELS.glob("*.py")) + [
    _OBJECT_ORDER / name for name in ("rasterization.py", "zbuffer.py", "blending.py", "depth_formats.py",
                                  "clipping.py", "culling.py",
                                  "flat_shading.py")]


def _cache_dirs() -> list[Path]:
    dirs = [_KERNELS / "__pycache__"]
    if config.CACHE_DIR:
        dirs.append(Path(config.CACHE_DIR) / str(_KERNELS).lstrip(os.sep))
    return dirs


def drop_stale_cache() -> bool:
    """Delete the cached object-order kernels if any of :data:`SOURCES` changed; True if it did."""
    digest = hashlib.sha1(b"".join(p.read_bytes() for p in SOURCES)).hexdigest()[:16]
    dropped = False
    for folder in _cache_dirs():
        stamp = folder / f"raster_sources.{digest}"
        try:
            folder.mkdir(parents=True, exist_ok=True)
            if stamp.exists():
                continue
            for f in folder.iterdir():
                if f.suffix in (".nbi", ".nbc") or f.name.startswith("raster_sources."):
                    f.unlink(missing_ok=True)
                    dropped = True
            stamp.touch()
        except OSError:  # a read-only install: numba caches elsewhere, nothing to do here
            continue
    return dropped


drop_stale_cache()
