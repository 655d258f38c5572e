"""While a window exists, Python's garbage is collected on the GUI thread, never on a thread beside it.

Python's cycle collector runs in whichever thread's allocations pass its threshold: with a window open,
mostly a render, typesetting or export thread.  What it frees there includes the Qt objects left in
reference cycles, and Qt lets most of them be destroyed on the GUI thread only.  In the window's tests
(tests/app/window and tests/views, two workers), full collections ran on threads of Qt's pool and found
64,000 and 108,000 objects in cycles, among them live QIcons of closed windows (46 and 30; a QIcon holds
pixmaps, which belong to the GUI thread), their QSettings (a QObject of the GUI thread), QImages and
QColors.  Destroying those off their thread is the kind of fault that corrupts the heap, to be found
later elsewhere: a test worker died once of a corrupted heap, found by glibc on the GUI thread while it
measured a text ("malloc_consolidate(): unaligned fastbin chunk detected").

:func:`collect_on_gui_thread` turns Python's automatic collection off while a window exists and collects
on the GUI thread instead, from a timer, by Python's rule: the oldest generation whose count passed its
threshold, if every younger one's did too.  A closed window exists until it is deleted, and so does its
garbage: with the automatic collection back at its closing, threads of Qt's pool collected closed
windows' objects between two tests (in one run of tests/app/window and tests/app/lessons, five windows'
own Python objects, with the Qt objects they held; in tests/app and tests/views, listeners of their
models' signals, which PySide disconnects from the thread that frees them: a script that freed such a
listener on another thread while its signal's object lived crashed within seconds).  So only once the
last window is deleted does the GUI thread collect what is left and turn the automatic collection back
on: a process's later work without a window (the tests of the algorithms, some 1,300) grew from 0.78 to
1.27 GB with none.  The window's stalls stay as they were: ``bench gui``, four runs each way,
interleaved, the longest stall while opening 69-78 ms (74-98 before), on the first tab 40-46 (38-66),
entering and leaving presentation mode 45-69 (40-77), lesson steps 58-77 (67-77).
"""

from __future__ import annotations

import functools
import gc
import itertools

from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QWidget

COLLECT_EVERY_MS = 100
"""How often the GUI thread collects what is due."""

_windows = itertools.count()
_existing: set[int] = set()
"""The windows that asked (numbered), until they are deleted."""


def collect_on_gui_thread(window: QWidget) -> None:
    """From now until ``window`` (and every other window that asked) is deleted, Python collects garbage
    only on this thread, the GUI thread (from a timer of the window's)."""
    number = next(_windows)
    _existing.add(number)
    gc.disable()
    # A plain callable, not a method: PySide ties a method's connection to its object's life, and that
    # object could die on another thread.
    window.destroyed.connect(functools.partial(_deleted, number))
    QTimer(window, interval=COLLECT_EVERY_MS, timeout=collect_due).start()


def _deleted(number: int) -> None:
    """Window ``number`` is deleted: with the last one, what the windows left is collected here, and the
    automatic collection is back."""
    _existing.discard(number)
    if not _existing:
        gc.collect()
        gc.enable()


def collect_due() -> None:
    """Collect the generations Python would have collected by now."""
    counts, thresholds = gc.get_count(), gc.get_threshold()
    due = None
    for generation in range(3):
        if counts[generation] <= thresholds[generation]:
            break
        due = generation
    if due is not None:
        gc.collect(due)
