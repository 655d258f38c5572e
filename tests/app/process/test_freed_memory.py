"""Freed memory kept for the next frame (:mod:`app.process.freed_memory`).

The setting is process-wide, so each case runs in a fresh interpreter: the
same "frames" of array allocations make thousands of page faults each with
the C library's defaults and none once :func:`keep_freed_memory` has run.
"""

from __future__ import annotations

import platform
import subprocess
import sys

FRAMES = """
import resource, sys
import numpy as np
from app.process.freed_memory import keep_freed_memory
tuned = keep_freed_memory() if sys.argv[1] == "tuned" else False
def frame():  # arrays of a few MB, as a frame's results
    arrays = [np.ones(n) for n in (1_000_000, 300_000, 2_000_000, 150_000, 700_000)]
    return sum(float(a[-1]) for a in arrays)
frame()
before = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
for _ in range(10):
    frame()
print(tuned, (resource.getrusage(resource.RUSAGE_SELF).ru_minflt - before) // 10)
"""


def _faults_per_frame(mode: str) -> tuple[str, int]:
    out = subprocess.run([sys.executable, "-c", FRAMES, mode], check=True, capture_output=True, text=True)
    tuned, faults = out.stdout.split()
    return tuned, int(faults)


def test_frames_reuse_freed_memory_once_tuned():
    if platform.libc_ver()[0] != "glibc":  # another C library: left as it is
        assert _faults_per_frame("tuned")[0] == "False"
        return
    tuned, faults = _faults_per_frame("default")
    assert tuned == "False" and faults > 500  # 33 MB of arrays a frame, mostly fresh pages
    assert _faults_per_frame("tuned") == ("True", 0)
