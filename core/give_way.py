"""Work beside the window gives way to it: it runs at a lower scheduling priority.

The renderers use every core (numba's ``prange``), and the helper processes
(typesetting, FLIP) and the first run's background compile run beside the
window too; on a 2-core machine the GUI thread would wait for a core each time
it wakes, tens of milliseconds in all: the window would stutter while the
observer moves.  So each of them lowers its own priority (Linux ``nice``) to
:data:`NICE`; the threads numba starts for a render inherit it.  They lose no
speed when nothing else runs, and the GUI thread gets a core the moment it has
work.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading

NICE = 5
"""The niceness of work beside the window (0 is the window's): a thread at it gets about a third of
the share of one at 0, so the window wins a core at once and the work still keeps pace beside other
programs."""


def lower_this_thread() -> None:
    """Lower the calling thread's priority to :data:`NICE` (Linux; elsewhere nothing: there
    ``setpriority`` would change the whole process, the window's thread too)."""
    if not sys.platform.startswith("linux"):
        return
    tid = threading.get_native_id()
    with contextlib.suppress(OSError):  # a sandbox may forbid it: the work still runs
        if os.getpriority(os.PRIO_PROCESS, tid) < NICE:
            os.setpriority(os.PRIO_PROCESS, tid, NICE)


def lower_this_process() -> None:
    """Lower the whole calling process's priority by :data:`NICE` (a helper or compile process,
    started by the window: the window's own priority plus :data:`NICE`)."""
    with contextlib.suppress(OSError, AttributeError):  # a sandbox may forbid it; no os.nice: Windows
        os.nice(NICE)
