"""Fixtures of every test of the window and the views: GUI tests need a real X server and say so
instead of skipping; settings and text size never leak from one test into the next.

``tests/app/conftest.py`` and ``tests/views/conftest.py`` use them; the core tests do not, so they
run where Qt and pyvista are not installed.

When the suite runs in several worker processes (``pytest -n 2``, as ``.ci/test.sh`` runs it), each
worker starts an X server of its own: two workers' windows never take each other's focus or screen.
"""

import functools
import os
import select
import subprocess

import pytest
import pyvista as pv
from pytestqt.qtbot import QtBot

pv.OFF_SCREEN = True

#: How long qtbot's waits wait when a test names no time (pytest-qt's own default is 5 s): what a
#: test waits for comes in well under a second on a quiet machine, but a busy one (both cores taken,
#: as the test command's two workers take them) has made a 5 s wait run out.
PATIENCE_MS = 30_000


def _patient(wait):
    @functools.wraps(wait)
    def patient(*args, timeout: int = PATIENCE_MS, **kwargs):
        return wait(*args, timeout=timeout, **kwargs)

    return patient


for _wait in ("waitUntil", "waitSignal", "waitSignals", "waitExposed", "waitActive", "waitCallback"):
    setattr(QtBot, _wait, _patient(getattr(QtBot, _wait)))


def _own_x_server() -> None:
    """Start an Xvfb for this worker process and point ``DISPLAY`` at it (the suite's own screen size).

    It lives as long as the worker: not a moment less, or the worker's Qt would lose its connection
    (ended at exit, or by ``-terminate`` once a test's subprocess, its only client yet, left it), and
    not a moment more: ``setpriv --pdeathsig`` (util-linux) has the kernel end it when the worker ends.
    (No Python runs between fork and exec, where another thread's held lock could stop the child.)
    """
    read_end, write_end = os.pipe()
    server = subprocess.Popen(["setpriv", "--pdeathsig", "TERM", "Xvfb", "-displayfd", str(write_end),
                               "-screen", "0", "1920x1080x24", "-nolisten", "tcp"], pass_fds=(write_end,),
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_end)
    with os.fdopen(read_end) as reply:
        ready, _, _ = select.select([reply], [], [], X_SERVER_START_S)
        number = reply.readline().strip() if ready else ""
    if not number:
        server.kill()
        raise RuntimeError(f"Xvfb did not give its display number within {X_SERVER_START_S} s: the tests'"
                           " X server is in the Debian package xvfb, setpriv in util-linux")
    os.environ["DISPLAY"] = f":{number}"


X_SERVER_START_S = 60


if os.environ.get("PYTEST_XDIST_WORKER") and os.environ.get("DISPLAY"):
    _own_x_server()


@pytest.fixture(autouse=True)
def require_display(request):
    needs_gui = "qtbot" in request.fixturenames or request.node.get_closest_marker("gui")
    if needs_gui and not os.environ.get("DISPLAY"):
        pytest.fail(
            "This GUI test needs an X server (VTK gets no OpenGL context offscreen). "
            "Run the suite with `bash .ci/test.sh`, which starts Xvfb, "
            "or wrap pytest in `xvfb-run -a`."
        )


@pytest.fixture(autouse=True)
def private_settings(tmp_path_factory, monkeypatch):
    """QSettings read and write a fresh folder in every test, never the user's configuration;
    so does every ``python -m app`` a test starts (it finds the folder in ``XDG_CONFIG_HOME``)."""
    from PySide6.QtCore import QSettings

    folder = str(tmp_path_factory.mktemp("settings"))
    monkeypatch.setenv("XDG_CONFIG_HOME", folder)
    for settings_format in (QSettings.Format.NativeFormat, QSettings.Format.IniFormat):
        for scope in (QSettings.Scope.UserScope, QSettings.Scope.SystemScope):
            QSettings.setPath(settings_format, scope, folder)


@pytest.fixture(autouse=True)
def application_font_restored():
    """A test that enlarges the application's text (presentation mode, Ctrl++) leaves it as it was."""
    from PySide6.QtWidgets import QApplication

    from views.text.text_scale import NORMAL_TEXT_PT

    app = QApplication.instance()
    font = None if app is None else QApplication.font()
    normal = None if app is None else app.property(NORMAL_TEXT_PT)
    yield
    if font is not None and QApplication.instance() is not None:
        QApplication.setFont(font)
        QApplication.instance().setProperty(NORMAL_TEXT_PT, normal)


@pytest.fixture(autouse=True)
def closed_widgets_deleted():
    """The widgets a test closed (qtbot closes and deletes the ones it was given) are deleted as the test
    ends, not in the next test's first event loop: a window's garbage waits for its deletion to be
    collected on the GUI thread (:mod:`app.process.gui_thread_collection`), as in the program, where
    no other window ever opens."""
    yield
    from PySide6.QtCore import QCoreApplication, QEvent

    if QCoreApplication.instance() is not None:
        QCoreApplication.sendPostedEvents(None, QEvent.Type.DeferredDelete)


def shown_widget(qtbot, widget, width: int, height: int):
    """``widget`` at ``width`` x ``height`` pixels, shown and exposed on screen, and closed after the
    test; returns it."""
    qtbot.addWidget(widget)
    widget.resize(width, height)
    widget.show()
    qtbot.waitExposed(widget)
    return widget


def in_a_window_with_a_shortcut(qtbot, widget, key: str) -> tuple:
    """``widget`` in a main window, shown and active, whose action has the shortcut ``key``; returns
    the window and a list that gets an item each time that action is triggered."""
    from PySide6.QtGui import QAction, QKeySequence
    from PySide6.QtWidgets import QMainWindow

    window = QMainWindow()
    window.setCentralWidget(widget)
    triggered = []
    action = QAction(f"The window's {key}", window)
    action.setShortcut(QKeySequence(key))
    action.triggered.connect(lambda: triggered.append(1))
    window.addAction(action)
    shown_widget(qtbot, window, 400, 300)
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    return window, triggered


def wheel_over(widget, pos, notches: int, modifiers=None) -> bool:
    """Turn the mouse wheel ``notches`` notches (up: positive) over ``pos`` of ``widget``, with
    ``modifiers`` held; whether the widget took the event (one it leaves goes on to its parents when a
    user turns the wheel: Qt does not pass on one sent by a test)."""
    from PySide6.QtCore import QPoint, QPointF, Qt
    from PySide6.QtGui import QWheelEvent
    from PySide6.QtWidgets import QApplication

    pos = QPointF(pos)
    event = QWheelEvent(pos, widget.mapToGlobal(pos), QPoint(0, 0), QPoint(0, 120 * notches),
                        Qt.MouseButton.NoButton, modifiers or Qt.KeyboardModifier.NoModifier,
                        Qt.ScrollPhase.NoScrollPhase, False)
    QApplication.sendEvent(widget, event)
    return event.isAccepted()


def rgb_pixels(image):
    """A QImage (a screenshot, a plotter's picture) as an (H, W, 3) uint8 array, a copy."""
    import numpy as np

    image = image.convertToFormat(image.Format.Format_RGB888)
    rows = np.frombuffer(image.constBits(), np.uint8).reshape(image.height(), image.bytesPerLine())
    return rows[:, :3 * image.width()].reshape(image.height(), image.width(), 3).copy()  # before image goes


def keys_listed(window) -> str:
    """Help → Keys of ``window`` as text: each heading, then a line ``"  keys what they do"`` a row."""
    return "\n".join(f"{heading}\n" + "\n".join(f"  {keys} {what}" for keys, what in rows)
                     for heading, rows in window.keys_sections())
