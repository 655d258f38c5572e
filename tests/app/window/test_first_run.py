"""The window on a machine whose kernels are not compiled yet: a first look at once, and the compile said."""

import pytest
from checkout import ROOT
from window_helpers import RENDER_TIMEOUT_MS

from app import renders
from app.window import background_compile, main_window, tabs
from app.window.main_window import MainWindow
from core import presets
from core.image_order import ray_tracing


def _open(qtbot, on_image=lambda: None):
    """The lecture scene's window, shown until its traced image is whole; what the progress bar and the
    image said on the way.  ``on_image`` is called at each image shown."""
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    image = win.tab("image order").widget.image
    seen = []  # (progress-bar text, the image's note) at every change of either
    win.renders.status_changed.connect(lambda tab: seen.append((win.progress.format(), image.note)))
    set_image = image.set_image
    image.set_image = lambda shown: (set_image(shown), seen.append((win.progress.format(), image.note)),
                                     on_image())
    win.show()
    qtbot.waitUntil(lambda: win.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    return win, seen


@pytest.mark.gui
def test_a_compile_still_to_come_is_said_and_a_first_look_shown_meanwhile(qtbot, monkeypatch):
    # As on a fresh machine: the tracer's kernels count as not compiled until an image is shown (here
    # they then load from the cache in a second, so the render goes on as it would after the compile).
    # Counted as never compiled, any render started later at start would say "compiling" again, as a
    # machine compiled by then would not: the test saw that once in five fresh-clone runs.
    compiled = []
    monkeypatch.setattr(ray_tracing, "compiled_for", lambda accel: bool(compiled))
    win, seen = _open(qtbot, on_image=lambda: compiled.append(True))
    said = [k for k, (text, _) in enumerate(seen) if "compiling the tracer's kernels" in text]
    assert said, seen
    first_look = [k for k, (_, note) in enumerate(seen) if note == tabs.FIRST_LOOK]
    assert first_look and first_look[0] >= said[0]  # shown while the compile is said
    assert seen[-1] == ("Image order: done", "")  # then the traced image, and the bar says so
    assert all("compiling" not in text for text, _ in seen[first_look[-1] + 1:]), seen


@pytest.mark.gui
def test_an_image_that_ends_a_wait_is_never_shown_beside_it(qtbot, monkeypatch):
    # Partial results reach the window a few times a second: one a render sends sooner after its
    # last is dropped.  A render whose kernels load quickly may end before any after its "compiling"
    # reaches the window (the test above failed so in one of two fresh-clone runs); its image must not
    # appear while the bar still says the kernels compile.  Here every partial result but a job's
    # first is dropped, so each render ends that way.
    monkeypatch.setattr(ray_tracing, "compiled_for", lambda accel: False)
    monkeypatch.setattr(renders, "PROGRESS_PER_SECOND", 1e-6)
    win, seen = _open(qtbot)
    first_look = [k for k, (_, note) in enumerate(seen) if note == tabs.FIRST_LOOK]
    assert first_look and "compiling the tracer's kernels" in seen[first_look[0]][0]
    assert seen[-1] == ("Image order: done", "")
    assert all("compiling" not in text for text, _ in seen[first_look[-1] + 1:]), seen


@pytest.mark.gui
def test_the_bar_counts_the_seconds_of_a_compile_and_stops_when_it_ends(qtbot, monkeypatch):
    # A compile takes most of a minute on a fresh machine: a bar standing at "0%" all that time
    # would look like a window that hangs. Here the "compile" lasts until the bar has counted to 2 s.
    import re
    import threading

    compiled = threading.Event()
    monkeypatch.setattr(ray_tracing, "compiled_for", lambda accel: compiled.is_set())
    render = tabs.render_trace
    monkeypatch.setattr(tabs, "render_trace", lambda *args, **kw: (compiled.wait(60), render(*args, **kw))[1])
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    counted = []  # the seconds the bar said, in order
    win.renders.status_changed.connect(lambda tab: counted.extend(
        int(n) for n in re.findall(r"compiling the tracer's kernels, (\d+) s so far", win.progress.format())))
    win.show()
    qtbot.waitUntil(lambda: max(counted, default=0) >= 2, timeout=RENDER_TIMEOUT_MS)
    assert "%" not in win.progress.text()  # no percent while nothing can be counted
    assert "once per machine" in win.progress.format()  # and why the wait
    # From 0 up, never back (a tick the busy GUI thread serves late may skip a second, never count back)
    assert counted[0] == 0 and counted == sorted(counted)
    compiled.set()
    qtbot.waitUntil(lambda: win.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    assert win.progress.format() == "Image order: done"
    assert not win.renders._wait_clock.isActive()  # nothing is counted any more


@pytest.mark.gui
def test_nothing_is_said_to_compile_when_everything_is_compiled(qtbot):
    win, seen = _open(qtbot)
    assert seen and all("compiling" not in text for text, _ in seen)
    assert all(note != tabs.FIRST_LOOK for _, note in seen)


class _NotCompiled:
    def ready(self):
        return False


@pytest.mark.gui
def test_the_background_compile_is_said_and_ends_with_the_window(qtbot, monkeypatch):
    # As on a fresh machine: no kernel group compiled. The compile itself is stood in for by a process
    # that would run for ten minutes: it must be said while it runs and ended when the window closes.
    monkeypatch.setattr(background_compile, "warm_up_of", lambda group: _NotCompiled())
    monkeypatch.setattr(background_compile.BackgroundCompile, "COMMAND",
                        ("-c", "import time; time.sleep(600)"))
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    win.show()
    qtbot.waitUntil(lambda: win.background_compile.running, timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: win.statusBar().currentMessage() == main_window.BACKGROUND_COMPILE, timeout=5000)
    process = win.background_compile._process
    win.close()
    qtbot.waitUntil(lambda: process.poll() is not None, timeout=5000)


CLOSE_WHILE_COMPILING = """
import sys, time
from app import cli
from app.window import tabs
from core.compiling import warm_up
from core.image_order import ray_tracing
from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication

ray_tracing.compiled_for = lambda accel: False
warm_up.WarmUp.__call__ = lambda self: time.sleep(600)  # a compile of ten minutes, which nothing interrupts
shown = tabs.ImageOrderTab.show_progress

def show_progress(self, partial):  # the first look is on screen: the user closes the window
    shown(self, partial)
    QTimer.singleShot(0, QApplication.instance().closeAllWindows)

tabs.ImageOrderTab.show_progress = show_progress
app = QApplication(sys.argv[:1])
sys.exit(cli.main([]))
"""


@pytest.mark.gui
def test_closing_the_window_during_a_compile_ends_the_program(tmp_path):
    import os
    import subprocess
    import sys
    import time

    env = {**os.environ, "XDG_CONFIG_HOME": str(tmp_path)}
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", CLOSE_WHILE_COMPILING], cwd=ROOT, env=env,
                          capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    assert time.monotonic() - start < 120  # not the ten minutes of the compile still running
