"""Render threads give way to the window: they run at a lower scheduling priority.

The renderers use every core (numba's ``prange``), so during a render the GUI
thread would wait for a core each time it wakes, tens of milliseconds in all
on a 2-core machine: the window stutters while the observer moves.  A job's
thread lowers its own priority (Linux ``nice``, per thread) before it renders;
the threads numba starts for it inherit it.  The renders lose no speed when
nothing else runs, and the GUI thread gets a core the moment it has work.
"""

from __future__ import annotations

import contextlib
import os
import sys
import threading

RENDER_NICE = 5
"""The render threads' niceness (0 is the window's): each gets about a third of the share of a thread at
0, so the window wins a core at once and renders still keep pace beside other programs."""


def give_way_to_the_window() -> None:
    """Lower the calling thread's priority to :data:`RENDER_NICE` (Linux; elsewhere nothing).

    On other systems ``setpriority`` would change the whole process, the window's thread too.
    """
    if not sys.platform.startswith("linux"):
        return
    tid = threading.get_native_id()
    with contextlib.suppress(OSError):  # a sandbox may forbid it: the renders still run
        if os.getpriority(os.PRIO_PROCESS, tid) < RENDER_NICE:
            os.setpriority(os.PRIO_PROCESS, tid, RENDER_NICE)
