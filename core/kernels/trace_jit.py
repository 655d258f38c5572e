"""How the tracer's kernels are compiled: one place for numba's options.

``jit`` compiles a helper (called from other kernels, or from Python for a
single ray); ``jit_parallel`` compiles an entry kernel whose ``prange`` loops
run on all cores.  Both

- cache the machine code on disk (``cache=True``), so only the first run on a
  machine pays the compile time;
- release the GIL (``nogil=True``), so a worker thread renders while the GUI
  thread keeps running;
- follow IEEE 754 for division by zero (``error_model="numpy"``): ``1 / 0``
  is ``inf`` rather than an exception, which the slab test relies on.

``fastmath`` stays off: the watertight triangle test needs ``a*b - c*d`` to be
evaluated exactly as written (no fused multiply-add, no reassociation).

Stale caches
------------
numba checks a cached kernel only against the file that defines it, not
against the files of the functions it calls (and compiles into itself).
After an edit of, say, :mod:`core.optics`, the cached shading kernel would
silently keep the old code.  So on import this module hashes every source
file the tracer's kernels are made of (:data:`SOURCES`) and, when the hash
changed, deletes the tracer's cache files before any kernel is loaded.
"""

from __future__ import annotations

import hashlib
import os
from pathlib import Path

from numba import config, njit

_OPTIONS = {"cache": True, "nogil": True, "error_model": "numpy"}
_KERNELS = Path(__file__).resolve().parent
_CORE = _KERNELS.parent
#: Prefixes of the tracer's kernel modules (the rasteriser's kernels are not ours).
PREFIXES = ("trace_", "accel_", "bvh_")
#: Every file whose code ends up inside the tracer's compiled kernels.
SOURCES = sorted(p for p in _KERNELS.glob("*.py") if p.name.startswith(PREFIXES)) + [
    _CORE / name for name in ("optics.py", "shading.py", "ray_offset.py", "intersect_sphere.py")]


def _cache_dirs() -> list[Path]:
    dirs = [_KERNELS / "__pycache__"]
    if config.CACHE_DIR:
        dirs.append(Path(config.CACHE_DIR) / str(_KERNELS).lstrip(os.sep))
    return dirs


def drop_stale_cache() -> bool:
    """Delete the tracer's cached kernels if any of :data:`SOURCES` changed; True if it did."""
    digest = hashlib.sha1(b"".join(p.read_bytes() for p in SOURCES)).hexdigest()[:16]
    dropped = False
    for folder in _cache_dirs():
        stamp = folder / f"trace_sources.{digest}"
        try:
            folder.mkdir(parents=True, exist_ok=True)
            if stamp.exists():
                continue
            for f in folder.iterdir():
                ours = f.name.startswith(PREFIXES) and f.suffix in (".nbi", ".nbc")
                if ours or f.name.startswith("trace_sources."):
                    f.unlink(missing_ok=True)
                    dropped = True
            stamp.touch()
        except OSError:  # a read-only install: numba caches elsewhere, nothing to do here
            continue
    return dropped


drop_stale_cache()


def jit(func):
    """Compile ``func`` with the tracer's options (serial)."""
    return njit(**_OPTIONS)(func)


def jit_inline(func):
    """Compile ``func`` with the tracer's options, inlined into every caller (for the
    innermost tests, where the cost of a call would exceed the work)."""
    return njit(inline="always", **_OPTIONS)(func)


def jit_parallel(func):
    """Compile ``func`` with the tracer's options, ``prange`` loops in parallel."""
    return njit(parallel=True, **_OPTIONS)(func)
