"""While a window is open, Python's garbage is freed on the GUI thread: a thread working beside it, which
allocates past the collector's thresholds, no longer frees what is in cycles there (Qt objects among
them, which Qt lets only their own thread destroy)."""

import threading
import weakref

import pytest


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


@pytest.mark.gui
def test_garbage_a_render_thread_leaves_is_freed_on_the_gui_thread(window, qtbot):
    freed_on, made = [], []

    def render():
        garbage_in_a_cycle(freed_on)
        made.append(allocate_past_every_threshold())

    worker = threading.Thread(target=render, name="a render")
    worker.start()
    worker.join()
    qtbot.waitUntil(lambda: bool(freed_on), timeout=5000)  # the window's next collection
    assert freed_on == [threading.main_thread()]
    assert len(made[0]) == 100_000


@pytest.mark.gui
def test_once_the_window_closes_python_collects_as_before(window, qtbot):
    window.close()
    freed_on = []
    garbage_in_a_cycle(freed_on)
    made = allocate_past_every_threshold()  # no event loop runs: Python's own collector frees it, here
    assert freed_on == [threading.main_thread()]
    assert len(made) == 100_000
