"""The window's thread gets Python's lock back sooner: the interpreter hands it over every millisecond.

Only one thread runs Python at a time.  A thread that waits for the lock asks the one holding it to
let go, and gets it only after the interpreter's switch interval, 5 ms by default.  The GUI thread
gives the lock up at many calls into Qt and VTK and must ask for it again each time, so while a
thread draws a plot with matplotlib or measures a sweep's error in Python (the Cost tab), each of
those waits cost it up to 5 ms: a sweep's longest stall of the window was 188-199 ms with 5 ms and
102-134 ms with 1 ms (``bench gui --seconds 1 --actions picks,cost,lessons,export``, two runs each,
interleaved, quiet 2-core machine).
The threads that lose the lock sooner are background work, which loses a few per cent of its speed.
"""

from __future__ import annotations

import sys

SWITCH_INTERVAL_S = 0.001
"""How long a thread may keep Python's lock once another asks for it."""


def hand_over_often() -> None:
    """Set the interpreter's switch interval to :data:`SWITCH_INTERVAL_S` (the window's process only)."""
    sys.setswitchinterval(SWITCH_INTERVAL_S)
