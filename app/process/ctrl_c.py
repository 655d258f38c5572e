"""Ctrl+C on the command line stops a compiled kernel too, within a pixel or a ray.

Python runs its SIGINT handler (``KeyboardInterrupt``) only when the main
thread is between two of its own statements.  While the main thread waits in
a compiled kernel for hours, that never happens.  But the C-level handler
still runs at once, and with :func:`signal.set_wakeup_fd` it writes the
signal's number to a pipe: a small thread waiting on that pipe sets
:data:`core.stopping.EVERY_JOB`, the kernels see their stop flag and return,
and the main thread meets its ``KeyboardInterrupt`` as soon as it is back in
Python (``python -m app`` then exits with status 130, writing nothing).
"""

from __future__ import annotations

import os
import signal
import threading

from core import stopping


def _relay(read_end: int) -> None:
    while True:
        try:
            received = os.read(read_end, 64)
        except InterruptedError:
            continue
        if not received:
            return
        if signal.SIGINT in received:
            stopping.EVERY_JOB.set()


def stop_kernels_on_ctrl_c() -> None:
    """Call once, from the main thread, before a command's work: Ctrl+C then stops kernels too.

    Does nothing when SIGINT is ignored (a command started in the background
    or under ``nohup``): Ctrl+C is then meant not to stop it.
    """
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        return
    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)  # the C handler must never wait on a full pipe
    signal.set_wakeup_fd(write_end, warn_on_full_buffer=False)
    threading.Thread(target=_relay, args=(read_end,), name="ctrl-c relay", daemon=True).start()
