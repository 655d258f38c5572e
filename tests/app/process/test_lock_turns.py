"""The window's process hands Python's lock from thread to thread every millisecond, so its GUI thread
waits at most that long each time it asks for the lock while a plot or a sweep runs in Python."""

import os
import subprocess
import sys

import pytest
from checkout import ROOT

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
    env = {**os.environ, "XDG_CONFIG_HOME": str(tmp_path)}  # no last session: the lecture scene
    out = subprocess.run([sys.executable, "-c", OPEN_AND_LOOK], cwd=ROOT, capture_output=True, text=True,
                         env=env, timeout=300)
    assert out.returncode == 0, out.stderr
    before, after = (float(s) for s in out.stdout.split()[-2:])
    assert before == 0.005 and after == 0.001  # Python's default, then the window's
