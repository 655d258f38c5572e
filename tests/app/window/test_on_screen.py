"""The window and its dialogs stay inside a small screen, frame (title bar, borders) and all."""

import pytest
from PySide6.QtCore import QRect
from PySide6.QtGui import QScreen
from PySide6.QtWidgets import QAbstractScrollArea, QDialogButtonBox, QWidget

from app.window.main_window import MainWindow
from core import presets
from views.presentation import SCALES

TITLE_BAR, BORDER = 20, 1
"""The frame a window manager like openbox adds around a window (pixels)."""


@pytest.fixture
def framed(monkeypatch):
    """Windows get a window manager's frame: a title bar above them and a border around them
    (Xvfb without a window manager adds none, so Qt's frame would equal the client area)."""

    def frame_geometry(widget):
        inner = widget.geometry()
        if not widget.isWindow():
            return inner
        return inner.adjusted(-BORDER, -TITLE_BAR - BORDER, BORDER, BORDER)

    monkeypatch.setattr(QWidget, "frameGeometry", frame_geometry)


def _small_screen(monkeypatch, width, height):
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: QRect(0, 0, width, height))
    return QRect(0, 0, width, height)


def _open(qtbot) -> MainWindow:
    window = MainWindow(presets.lecture_scene())
    qtbot.addWidget(window)
    window.show()
    qtbot.waitExposed(window)
    return window


def test_the_window_frame_and_all_fits_a_1280x720_screen(qtbot, monkeypatch, framed):
    # The window used to take the whole 1280 x 720 for its client area: with the title bar
    # above it, the dock tabs and the status bar (where exports say they were written) hung
    # off the bottom of the screen.
    screen = _small_screen(monkeypatch, 1280, 720)
    window = _open(qtbot)
    qtbot.waitUntil(lambda: screen.contains(window.frameGeometry()), timeout=5000)
    window.statusBar().showMessage("Exported /tmp/slides/traced.png", 8000)  # as an export says
    bar = window.statusBar()
    qtbot.waitUntil(lambda: bar.isVisible() and screen.contains(window.frameGeometry()), timeout=5000)
    assert screen.contains(QRect(bar.mapToGlobal(bar.rect().topLeft()), bar.size()))  # seen whole
    for scale in SCALES:
        window.presentation.set_scale(scale)
        qtbot.waitUntil(lambda: screen.contains(window.frameGeometry()), timeout=5000)


@pytest.mark.parametrize(("screen_size", "scale"), [((1280, 720), 1.0), ((1920, 1080), 2.0)],
                         ids=["1280x720", "1920x1080-x2"])
def test_the_keys_dialog_and_its_ok_button_are_on_screen(qtbot, monkeypatch, framed, screen_size, scale):
    # The keys were listed in a message box taller than a 1280 x 720 screen: its OK button was
    # off screen.  The list now scrolls within the screen.
    screen = _small_screen(monkeypatch, *screen_size)
    window = _open(qtbot)
    window.presentation.set_scale(scale)
    dialog = window.show_keys()
    qtbot.waitExposed(dialog)
    ok = dialog.findChild(QDialogButtonBox).button(QDialogButtonBox.StandardButton.Ok)

    def on_screen():
        assert screen.contains(dialog.frameGeometry()), dialog.frameGeometry()
        assert screen.contains(QRect(ok.mapToGlobal(ok.rect().topLeft()), ok.size()))
        assert ok.isVisible() and ok.height() >= ok.fontMetrics().height()

    qtbot.waitUntil(on_screen, timeout=5000)
    dialog.close()



def test_presenting_at_x2_on_1280x720_the_keys_need_no_sideways_scroll(qtbot, monkeypatch, framed):
    # The keys were plain text in a fixed-pitch font, one unbroken line each: at x2 on a
    # 1280 x 720 screen the dialog showed their first half and a horizontal scroll bar.  The
    # descriptions now wrap to the dialog's width; every key and every description is in it.
    screen = _small_screen(monkeypatch, 1280, 720)
    window = _open(qtbot)
    normal = window.font().pointSizeF()
    window.presentation.set_scale(2.0)
    dialog = window.show_keys()
    qtbot.waitExposed(dialog)
    view = dialog.findChild(QAbstractScrollArea)

    def fits():
        assert screen.contains(dialog.frameGeometry()), dialog.frameGeometry()
        assert view.horizontalScrollBar().maximum() == 0
        assert view.font().pointSizeF() >= 1.9 * normal  # the x2 text

    qtbot.waitUntil(fits, timeout=5000)
    shown = " ".join(view.toPlainText().split())
    for heading, rows in window.keys_sections():
        assert heading in shown
        for keys, what in rows:
            assert keys in shown and " ".join(what.split()) in shown, (keys, what)
    dialog.close()

def test_on_one_screen_the_presenter_window_sits_beside_the_main_window(qtbot, monkeypatch, framed):
    # With one screen the presenter window opened over the main window and hid it.
    screen = _small_screen(monkeypatch, 1920, 1080)
    window = _open(qtbot)
    window.setGeometry(screen.adjusted(BORDER, TITLE_BAR + BORDER, -BORDER, -BORDER))  # the whole screen
    presenter = window.presentation.show_presenter()
    qtbot.addWidget(presenter)
    qtbot.waitExposed(presenter)

    def apart():
        assert screen.contains(presenter.frameGeometry()) and screen.contains(window.frameGeometry())
        assert not presenter.frameGeometry().intersects(window.frameGeometry())

    qtbot.waitUntil(apart, timeout=5000)
    assert window.width() >= 0.6 * screen.width()  # the main window keeps most of the screen
