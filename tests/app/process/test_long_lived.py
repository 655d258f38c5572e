"""Once the program has loaded what it needs, Python's full garbage collection walks only what was made
since: each such pass held the interpreter's lock (and so the window) about 110 ms.  Setting them aside
makes no full pass either (that one held the window 150-250 ms)."""

import pytest
from window_helpers import run_as_the_app

OPEN_AND_LOOK = r"""
import gc, sys
from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication
from app import cli
from app.process import long_lived

app = QApplication(sys.argv[:1])
passes = []  # the generations the program asks to collect


class Watched:
    def __getattr__(self, name):
        return getattr(gc, name)

    def collect(self, generation=2):
        passes.append(generation)
        return gc.collect(generation)


long_lived.gc = Watched()

def look():
    if gc.get_freeze_count():
        print(max(passes), gc.get_freeze_count(), len(gc.get_objects()))
        app.quit()

QTimer(app, interval=200, timeout=look).start()
QTimer.singleShot(60_000, lambda: (print(-1, 0, len(gc.get_objects())), app.quit()))  # never set aside
sys.exit(cli.main([]))
"""


@pytest.mark.gui
def test_once_everything_is_loaded_a_full_collection_walks_a_small_share_of_the_objects(tmp_path):
    out = run_as_the_app(OPEN_AND_LOOK, tmp_path)
    oldest, frozen, walked = (int(n) for n in out.split()[-3:])
    assert oldest in (0, 1)  # only the young generations collected first, no full pass
    assert frozen > 100_000  # the objects of what the program loaded, set aside
    assert walked < frozen / 5  # what a full collection still walks
