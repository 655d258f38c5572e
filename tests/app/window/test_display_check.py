"""Without a screen, `python -m app` says so, status 2; Qt aborted it (status 134, a core dump)."""

import os
import subprocess
import sys

import pytest
from checkout import ROOT
from unserved_display import unserved_display


def _open_window(**env) -> subprocess.CompletedProcess:
    """`python -m app` (the window on the lecture scene) with ``env`` for the display's variables."""
    base = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    return subprocess.run([sys.executable, "-m", "app"], cwd=ROOT, env={**base, **env}, capture_output=True,
                          text=True, timeout=120)


def test_without_a_display_the_window_says_there_is_no_screen_and_what_to_do():
    done = _open_window()
    assert done.returncode == 2
    assert done.stderr.startswith("python -m app: error: no screen to open the window on: DISPLAY is not set")
    assert "xvfb-run" in done.stderr and "python -m app --help" in done.stderr
    assert "Traceback" not in done.stderr and "xcb-cursor" not in done.stderr


def test_a_display_no_x_server_answers_on_is_named():
    unserved = unserved_display()
    done = _open_window(DISPLAY=unserved)
    assert done.returncode == 2
    assert f"no X server answers on display '{unserved}'" in done.stderr
    assert "Traceback" not in done.stderr and "xcb-cursor" not in done.stderr


@pytest.mark.gui
def test_the_display_the_tests_draw_on_is_one_the_window_opens_on():
    from app.window.display_check import why_no_display

    assert why_no_display() is None
