"""matplotlib is used by one thread at a time: an exported picture, or a formula typeset in this process,
waits while a plot is drawn on another thread (shared FreeType faces failed with "invalid outline" when
a lesson's formula and the Cost plot were drawn at once).  Formulas are typeset in a process of their
own, which waits for no plot."""

import threading

import numpy as np

from app.export.picture_sheet import Panel, compose
from views.matplotlib_lock import MATPLOTLIB
from views.text import math_view, typesetting_process


def _waits_for_matplotlib(work) -> bool:
    """Whether ``work``, run on another thread, waits while this thread holds matplotlib, and
    finishes once it lets go."""
    done = threading.Event()
    worker = threading.Thread(target=lambda: (work(), done.set()), daemon=True)
    with MATPLOTLIB:
        worker.start()
        waited = not done.wait(0.5)  # half a second: typesetting this takes a few milliseconds
    return waited and done.wait(60)


def test_a_formula_typeset_in_this_process_waits_while_another_thread_draws_with_matplotlib():
    assert _waits_for_matplotlib(lambda: typesetting_process.ink(r"$\alpha + \beta_{lock}$", 13.7, "#000000",
                                                                 96.0))


def test_the_typesetting_process_goes_on_while_a_plot_is_drawn():
    done = threading.Event()
    # keep=False: typeset now, not read from the formula cache; a size no other test uses.
    worker = threading.Thread(target=lambda: (math_view._typeset(r"$\gamma_{lock}$", 13.9, "#000000", 96.0,
                                                                  False), done.set()), daemon=True)
    with MATPLOTLIB:
        worker.start()
        assert done.wait(60)


def test_an_exported_sheet_waits_too_and_the_same_thread_may_hold_it_again():
    panel = Panel("a panel", np.full((8, 8, 3), 0.5))
    assert _waits_for_matplotlib(lambda: compose([panel], 1, ["a caption"]))
    with MATPLOTLIB:  # a drawing that saves its figure takes the lock again on its own thread
        sheet = compose([panel], 1, ["a caption"])
    assert sheet.ndim == 3 and sheet.shape[2] == 3
