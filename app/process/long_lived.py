"""What the program keeps for its whole life is set aside from Python's garbage collector.

Once the window is open, the modules it loaded (Qt, VTK, pyvista, numba and the compiled kernels,
matplotlib) leave about 300,000 objects that live as long as the program.  Python's full collection
walks every one of them whenever enough new objects have survived: about 110 ms each time on a
2-core machine, with the interpreter's lock held, so whichever thread ran it (now the GUI thread,
:mod:`app.process.gui_thread_collection`) the window could not move for as long.  In ``bench gui``
that was some forty times in one run, the floor of most actions' longest stall.
:func:`set_aside_once_loaded` freezes what exists (``gc.freeze``) when everything the first minutes
load is loaded: a full collection then walks only what was made since, about 10 ms.  Only the young
generations are collected first (a few milliseconds): a full collection there held the window
150-250 ms, once, and found nothing to free (0 unreachable objects of 290,000, after opening the
lecture scene).

Only the program's own process does this (``python -m app`` and ``bench gui``): a process that
opens many windows, one after another (the tests), would keep the frozen ones' cycles forever.
"""

from __future__ import annotations

import gc

from PySide6.QtCore import QTimer

LOOK_EVERY_MS = 1000
"""How often it looks whether everything is loaded."""


def set_aside_once_loaded(window) -> QTimer:
    """Collect the young generations and freeze once ``window`` shows its 3D pane, its formulas'
    typesetting is loaded and its kernels are loaded or compiled; returns the timer that looks (it stops
    then)."""
    from views.text import math_view

    def loaded() -> bool:
        typesetting = math_view.loader
        return (window.background_compile.checked.is_set() and window.scene_view.view is not None
                and typesetting is not None and not typesetting.is_alive())

    def look() -> None:
        if loaded():
            timer.stop()
            gc.collect(1)
            gc.freeze()

    timer = QTimer(window, interval=LOOK_EVERY_MS, timeout=look)
    timer.start()
    return timer
