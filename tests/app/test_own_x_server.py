"""Each worker process of ``pytest -n 2`` (README command 2) draws on an X server of its own, so two
workers' windows never take each other's focus or screen (tests/qt_fixtures.py).  The server lives
exactly as long as its worker: a test's subprocess that used it and left does not end it."""

import os
import subprocess
import sys
import time
from pathlib import Path

from checkout import ROOT

CLIENT = "from PySide6.QtGui import QGuiApplication; QGuiApplication(['client', '-platform', 'xcb'])"
WORKER = f"""
import os, subprocess, sys
before = os.environ["DISPLAY"]
import qt_fixtures  # starts the worker's own X server
subprocess.run([sys.executable, "-c", {CLIENT!r}], check=True)  # a client comes and goes first
from PySide6.QtGui import QGuiApplication
app = QGuiApplication(["worker", "-platform", "xcb"])
size = app.primaryScreen().size()
print(before, os.environ["DISPLAY"], size.width(), size.height())
"""


def test_a_worker_process_has_its_own_x_server_of_the_suites_size_for_its_whole_life():
    env = {**os.environ, "PYTEST_XDIST_WORKER": "gw7", "DISPLAY": os.environ.get("DISPLAY", ":0"),
           "PYTHONPATH": os.pathsep.join([str(ROOT / "tests"), str(ROOT)])}
    done = subprocess.run([sys.executable, "-c", WORKER], cwd=ROOT, env=env, capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    before, after, width, height = done.stdout.split()
    assert after != before and after.startswith(":")
    assert (int(width), int(height)) == (1920, 1080)
    # The worker has ended, and its server with it: the server's socket goes.
    socket = Path(f"/tmp/.X11-unix/X{after[1:]}")
    deadline = time.monotonic() + 30
    while socket.exists() and time.monotonic() < deadline:
        time.sleep(0.05)
    assert not socket.exists()
