"""numba's disk cache, kept honest: cached kernels are dropped when a formula they compile in changes.

numba checks a cached kernel only against the file that defines it, not against
the files whose ``register_jitable`` formulas it compiles into itself.  After an
edit of, say, :mod:`core.object_order.rasterization`, the cached rasterizer
would silently keep the old fill rule.  So each half's kernel package calls
:func:`drop_stale_cache` on import with the list of every file its kernels are
made of; when their hash changed, the package's cached kernels are deleted
before any is loaded, and numba compiles them afresh.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba import config


def _cache_dirs(kernel_dir: Path) -> list[Path]:
    folders = sorted({p.parent for p in kernel_dir.rglob("*.py")})
    dirs = [f / "__pycache__" for f in folders]
    if config.CACHE_DIR:
        dirs += [Path(config.CACHE_DIR) / str(f).lstrip(os.sep) for f in folders]
    return dirs


def drop_stale_cache(kernel_dir: Path, sources: list[Path], tag: str) -> bool:
    """Delete the cached kernels below ``kernel_dir`` if any of ``sources`` changed; True if it did.

    Parameters
    ----------
    kernel_dir : the kernel package's folder (its sub-folders are included).
    sources : every file whose code ends up inside those kernels.
    tag : a short name for the stamp file that records the sources' hash.
    """
    digest = hashlib.sha1(b"".join(p.read_bytes() for p in sources)).hexdigest()[:16]
    dropped = False
    for folder in _cache_dirs(kernel_dir):
        stamp = folder / f"{tag}_sources.{digest}"
        try:
            folder.mkdir(parents=True, exist_ok=True)
            if stamp.exists():
                continue
            for f in folder.iterdir():
                if f.suffix in (".nbi", ".nbc") or f.name.startswith(f"{tag}_sources."):
                    f.unlink(missing_ok=True)
                    dropped = True
            stamp.touch()
        except OSError:  # a read-only install: numba caches elsewhere, nothing to do here
            continue
    return dropped
