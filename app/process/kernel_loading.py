"""Loading the compiled kernels on the command line, where Ctrl+C must still end cleanly.

A render's first step imports numba and loads its kernels from numba's disk
cache (or compiles them, minutes on a fresh clone).  That is numba's own
Python code, and a ``KeyboardInterrupt`` raised in the middle of it does not
always come out as one: now and then it was swallowed (the render went on and
wrote its file) or left the interpreter to end itself by the signal (exit
-2 instead of 130).  Nothing of the user's has been written at that point,
so :func:`load_kernels` lets Ctrl+C end the process at once, with the same
message and status as an interrupt anywhere else (:func:`app.cli.main`):
numba writes its cache files by renaming finished ones into place, so
nothing half-written is left behind either.
"""

from __future__ import annotations

import os
import signal
import sys
import threading


def load_kernels(mode: str, accel: str) -> float:
    """Import and load (or compile) the kernels a ``mode`` render with ``accel`` runs; returns the seconds.

    A compile (not a load from the kernel cache) is announced on stderr first.  Ctrl+C meanwhile
    ends the process at once with status 130, unless it was started to ignore Ctrl+C (under
    ``nohup``, or with ``&`` from a script).
    """
    on_main_thread = threading.current_thread() is threading.main_thread()
    take_over = on_main_thread and signal.getsignal(signal.SIGINT) is not signal.SIG_IGN
    previous = signal.signal(signal.SIGINT, _exit_at_once) if take_over else None
    try:
        if mode == "raster":
            from core.object_order.pipeline import ensure_compiled as warm_up
        else:
            from core.image_order.ray_tracing import warm_up_for

            warm_up = warm_up_for(accel)
        if not warm_up.ready():
            what = "rasterizer" if mode == "raster" else "tracer"
            print(f"python -m app: compiling the {what}'s kernels first (once per machine and version of "
                  "the code, a minute or two; `python -m app compile` does every renderer at once, on "
                  "every core)", file=sys.stderr, flush=True)
        return warm_up()
    finally:
        if take_over:
            signal.signal(signal.SIGINT, previous)


def _exit_at_once(signum, frame) -> None:
    sys.stderr.write("python -m app: interrupted; no output file was written or changed\n")
    sys.stderr.flush()
    os._exit(130)
