"""Ctrl+C, SIGTERM, or the terminal closing (SIGHUP) closes the window as its close button does."""

import os
import select
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from checkout import ROOT

# The window as `python -m app` opens it, its background compile stood in for by a process that would
# run for ten minutes; once that has started, the window is open and the process says its number.
OPEN_WINDOW = """
import signal
import sys

signal.signal(signal.SIGINT, signal.default_int_handler)  # a terminal's Ctrl+C, whatever started the test
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


def _ended(pid: int) -> bool:
    """Whether process ``pid`` has ended (gone, or a zombie nobody has reaped yet)."""
    stat = Path(f"/proc/{pid}/stat")
    try:
        return stat.read_text().rsplit(")", 1)[1].split()[0] == "Z"
    except (FileNotFoundError, ProcessLookupError):
        return True


def _ends_soon(pid: int, seconds: float = 10) -> bool:
    """Whether process ``pid`` ends within ``seconds`` (a signal sent to it takes a moment)."""
    deadline = time.monotonic() + seconds
    while not _ended(pid) and time.monotonic() < deadline:
        time.sleep(0.05)
    return _ended(pid)


@pytest.mark.gui
@pytest.mark.parametrize("signum", [signal.SIGINT, signal.SIGTERM, signal.SIGHUP],
                         ids=["ctrl-c", "sigterm", "terminal-closed"])
def test_a_signal_closes_the_window_and_its_compile_and_the_session_is_remembered(tmp_path, signum):
    env = {**os.environ, "XDG_CONFIG_HOME": str(tmp_path)}
    window = subprocess.Popen([sys.executable, "-c", OPEN_WINDOW], cwd=ROOT, env=env, stdout=subprocess.PIPE,
                              stderr=subprocess.PIPE, text=True)
    try:
        ready, _, _ = select.select([window.stdout], [], [], 300)
        line = window.stdout.readline() if ready else ""
        assert line.strip().isdigit(), (line, window.poll())
        compile_pid = int(line)
        window.send_signal(signum)
        _, err = window.communicate(timeout=120)
    finally:
        window.kill()
    assert window.returncode == 128 + signum  # as a program stopped by that signal
    assert "Traceback" not in err and "KeyboardInterrupt" not in err, err[-2000:]
    assert _ends_soon(compile_pid)  # the compile did not run on without the window
    settings = (tmp_path / "Render Explorer" / "Render Explorer.conf").read_text()
    assert "observer=" in settings  # the window closed as it does, remembering the session
