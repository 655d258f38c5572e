"""Keeping freed memory for the next frame: the C library's ``malloc`` tuned at start-up.

Every frame of the rasterizer allocates its results afresh: the image and the
z-buffer, vertex and polygon arrays, a few MB each (about 200 MB a frame at a
million triangles).  By default glibc gives a freed block above its mmap
threshold straight back to the system, and trims the free top of its heap, so
the next frame's arrays come as fresh pages that fault on first touch, one
fault per 4 KB: about 15,000 faults a frame at a million triangles and 3,000 at
100,000 in ``python -m app bench raster``, a third of the frame's CPU time.
:func:`keep_freed_memory` raises both thresholds so that freed blocks stay in
the process and the next frame reuses them, with no faults.

The price: the process keeps up to ``TRIM_THRESHOLD`` of freed memory instead
of returning it, so its resident size stays near that of the largest frame.
The setting is process-wide, so it is made once, in the program's entry
(:mod:`app.__main__`); with another C library nothing changes.
"""

from __future__ import annotations

import ctypes
import platform

M_TRIM_THRESHOLD, M_MMAP_THRESHOLD = -1, -3
"""glibc's ``mallopt`` parameter numbers (``malloc.h``)."""
MMAP_THRESHOLD = 32 * 1024 * 1024
"""Blocks above this go to and from the system directly: glibc's largest on 64-bit."""
TRIM_THRESHOLD = 1024 * 1024 * 1024
"""Free memory at the top of the heap kept before any is given back."""


def keep_freed_memory() -> bool:
    """Tune glibc's ``malloc`` to keep freed blocks (see the module); True when it did,
    False with another C library (nothing changes then)."""
    if platform.libc_ver()[0] != "glibc":
        return False
    try:
        mallopt = ctypes.CDLL(None).mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    return bool(mallopt(M_MMAP_THRESHOLD, MMAP_THRESHOLD)) and bool(mallopt(M_TRIM_THRESHOLD, TRIM_THRESHOLD))
