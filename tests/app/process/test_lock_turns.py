"""The window's process hands Python's lock from thread to thread every millisecond, so its GUI thread
waits at most that long each time it asks for the lock while a plot or a sweep runs in Python."""

import pytest
from window_helpers import run_as_the_app

OPEN_AND_LOOK = r"""
import sys
from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication
from app import cli

app = QApplication(sys.argv[:1])
before = sys.getswitchinterval()
QTimer.singleShot(0, lambda: (print(before, sys.getswitchinterval()), app.quit()))
sys.exit(cli.main([]))
"""


@pytest.mark.gui
def test_the_window_hands_pythons_lock_over_every_millisecond(tmp_path):
    out = run_as_the_app(OPEN_AND_LOOK, tmp_path)
    before, after = (float(s) for s in out.split()[-2:])
    assert before == 0.005 and after == 0.001  # Python's default, then the window's
