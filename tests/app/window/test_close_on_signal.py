"""Ctrl+C, SIGTERM, or the terminal closing (SIGHUP) closes the window as its close button does."""

import os
import select
import signal
import subprocess
import sys
from pathlib import Path

import pytest
from checkout import ROOT
from interrupts import ctrl_c_reaches
from process_ends import ended

from core import presets

# The window as `python -m app` opens it, its background compile stood in for by a process that would
# run for ten minutes; once that has started, the window is open and the process says its number.
OPEN_WINDOW = """
import sys
from app import cli
from app.window import background_compile
from PySide6.QtWidgets import QApplication


class NotCompiled:
    def ready(self):
        return False


background_compile.warm_up_of = lambda group: NotCompiled()
background_compile.BackgroundCompile.COMMAND = ("-c", "import time; time.sleep(600)")
start = background_compile.BackgroundCompile._start


def started(self):
    start(self)
    print(self._process.pid, flush=True)


background_compile.BackgroundCompile._start = started
app = QApplication(sys.argv[:1])
sys.exit(cli.main([]))
"""


def _open_and_signal(config: Path, signum: int) -> tuple[int, str, int]:
    """Open the window (settings in ``config``), send it ``signum`` once it is open; its status, its
    stderr and its stand-in compile's process number."""
    env = {**os.environ, "XDG_CONFIG_HOME": str(config)}
    window = subprocess.Popen([sys.executable, "-c", OPEN_WINDOW], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True,
                              preexec_fn=ctrl_c_reaches)  # a terminal's Ctrl+C, however the tests started
    try:
        ready, _, _ = select.select([window.stdout], [], [], 300)
        line = window.stdout.readline() if ready else ""
        assert line.strip().isdigit(), (line, window.poll())
        window.send_signal(signum)
        _, err = window.communicate(timeout=120)
    finally:
        window.kill()
    return window.returncode, err, int(line)


@pytest.mark.gui
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP],
                         ids=["ctrl-c", "sigterm", "terminal-closed"])
def test_a_signal_closes_the_window_and_its_compile_and_the_session_is_remembered(tmp_path, signum):
    status, err, compile_pid = _open_and_signal(tmp_path, signum)
    assert status == 128 + signum  # as a program stopped by that signal
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err[-2000:]
    assert ended(compile_pid, 10)  # the compile did not run on without the window
    settings = (tmp_path / "Render Explorer" / "Render Explorer.conf").read_text()
    assert "observer=" in settings  # the window closed as it does, remembering the session


@pytest.mark.gui
def test_a_damaged_last_session_opens_the_window_on_the_lecture_scene_and_is_replaced(tmp_path):
    # Garbage where the last session is kept (half a JSON scene, bytes that are not text): the window
    # still opens on the lecture scene (it lives until it is told to close), and closing it writes that
    # scene's session over the garbage.
    kept = tmp_path / "Render Explorer" / "Render Explorer.conf"
    kept.parent.mkdir()
    kept.write_bytes(b'[session]\nscene="{\\"objects\\": [1,2,3\nobserver=\xff\xfe\x00garbage\n')
    status, err, _ = _open_and_signal(tmp_path, signal.SIGTERM)
    assert status == 128 + signal.SIGTERM and "Traceback" not in err, err[-2000:]
    observer = next(line for line in kept.read_text().splitlines() if line.startswith("observer="))
    eye = [float(v) for v in presets.lecture_scene().camera.eye]
    assert f'\\"eye\\": {eye}' in observer  # the lecture scene's observer, as JSON, over the garbage
