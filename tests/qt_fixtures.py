"""Fixtures of every test of the window and the views: GUI tests need a real X server and say so
instead of skipping; settings and text size never leak from one test into the next.

``tests/app/conftest.py`` and ``tests/views/conftest.py`` use them; the core tests do not, so they
run where Qt and pyvista are not installed.

When the suite runs in several worker processes (``pytest -n 2``, as ``.ci/test.sh`` runs it), each
worker starts an X server of its own: two workers' windows never take each other's focus or screen.
"""

import atexit
import os
import subprocess
import sys

import pytest
import pyvista as pv

pv.OFF_SCREEN = True


def _own_x_server() -> None:
    """Start an Xvfb for this worker process and point ``DISPLAY`` at it (the suite's own screen size)."""
    read_end, write_end = os.pipe()
    # -terminate: the server ends when its last client leaves, the worker's Qt at the process's end.
    server = subprocess.Popen(["Xvfb", "-displayfd", str(write_end), "-screen", "0", "1920x1080x24",
                               "-nolisten", "tcp", "-terminate"], pass_fds=(write_end,),
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    os.close(write_end)
    with os.fdopen(read_end) as reply:
        number = reply.readline().strip()
    if not number:
        raise RuntimeError("Xvfb did not start: the tests' X server is in the Debian package xvfb")
    atexit.register(_end_unless_connected, server)
    os.environ["DISPLAY"] = f":{number}"


def _end_unless_connected(server: subprocess.Popen) -> None:
    """End a server no window ever used; one Qt is connected to ends itself when Qt lets go (ending
    it under Qt would have Qt report a broken X connection)."""
    widgets = sys.modules.get("PySide6.QtWidgets")
    if widgets is None or widgets.QApplication.instance() is None:
        server.terminate()


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

    app = QApplication.instance()
    font = None if app is None else QApplication.font()
    yield
    if font is not None and QApplication.instance() is not None:
        QApplication.setFont(font)


def shown_widget(qtbot, widget, width: int, height: int):
    """``widget`` at ``width`` x ``height`` pixels, shown and exposed on screen, and closed after the
    test; returns it."""
    qtbot.addWidget(widget)
    widget.resize(width, height)
    widget.show()
    qtbot.waitExposed(widget)
    return widget
