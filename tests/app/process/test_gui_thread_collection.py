"""While a window exists, Python's garbage is freed on the GUI thread: a thread working beside it, which
allocates past the collector's thresholds, no longer frees what is in cycles there (Qt objects among
them, which Qt lets only their own thread destroy), even once the window is closed, until it is deleted."""

import threading
import weakref

import pytest
from PySide6.QtCore import QCoreApplication, QEvent

from app.window.main_window import MainWindow
from core import presets


class Cycle:
    """An object only the cycle collector frees."""

    def __init__(self):
        self.me = self


def garbage_in_a_cycle(freed_on: list) -> None:
    """A cycle, unreachable at once, that notes the thread that frees it."""
    weakref.finalize(Cycle(), lambda: freed_on.append(threading.current_thread()))


def allocate_past_every_threshold() -> list:
    """Container objects enough for Python's collector to run, in whichever thread makes them (700 more
    made than freed start a young collection, by default); kept while the collection is awaited."""
    return [[] for _ in range(100_000)]


def thread_beside(freed_on: list, made: list) -> None:
    """What a render or typesetting thread does in a test: leaves a cycle and allocates past every
    threshold (on a thread of its own, which has ended when this returns)."""

    def work():
        garbage_in_a_cycle(freed_on)
        made.append(allocate_past_every_threshold())

    worker = threading.Thread(target=work, name="a render")
    worker.start()
    worker.join()


@pytest.mark.gui
def test_garbage_a_render_thread_leaves_is_freed_on_the_gui_thread(window, qtbot):
    freed_on, made = [], []
    thread_beside(freed_on, made)
    qtbot.waitUntil(lambda: bool(freed_on), timeout=5000)  # the window's next collection
    assert freed_on == [threading.main_thread()]
    assert len(made[0]) == 100_000


def delete(window: MainWindow) -> None:
    """Delete ``window`` as an event loop would once ``deleteLater`` was called."""
    window.deleteLater()
    QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)


@pytest.mark.gui
def test_a_closed_windows_garbage_waits_for_the_gui_thread_until_the_window_is_deleted(qtbot):
    # The window exists until it is deleted, and so do its objects in cycles: a thread still at work
    # after it closed (the typesetter's, finishing a formula) collected them there, the window with them.
    window = MainWindow(presets.lecture_scene())
    window.close()
    freed_on, made = [], []
    thread_beside(freed_on, made)
    assert freed_on == [] and len(made[0]) == 100_000
    delete(window)
    assert freed_on == [threading.main_thread()]


@pytest.mark.gui
def test_once_the_last_window_is_deleted_python_collects_as_before(qtbot):
    window = MainWindow(presets.lecture_scene())
    window.close()
    delete(window)
    freed_on = []
    garbage_in_a_cycle(freed_on)
    made = allocate_past_every_threshold()  # no event loop runs: Python's own collector frees it, here
    assert freed_on == [threading.main_thread()]
    assert len(made) == 100_000
