"""High contrast, pane by pane: what shows turns black and white at once, a hidden tab when shown."""

import pytest
from PySide6.QtCore import QEvent, QObject
from PySide6.QtGui import QPalette
from PySide6.QtWidgets import QDialog, QLabel, QMainWindow, QTabWidget, QVBoxLayout, QWidget

from views.high_contrast import HighContrast


class _Restyles(QObject):
    """Counts the style changes a widget receives."""

    def __init__(self, widget):
        super().__init__(widget)
        self.count = 0
        widget.installEventFilter(self)

    def eventFilter(self, watched, event):  # noqa: N802 (Qt's name)
        if event.type() == QEvent.Type.StyleChange:
            self.count += 1
        return False


def _page(text: str) -> tuple[QWidget, QLabel]:
    page = QWidget()
    label = QLabel(text, page)
    QVBoxLayout(page).addWidget(label)
    return page, label


@pytest.fixture
def tabs(qtbot):
    window = QMainWindow()
    tabs = QTabWidget()
    (first, shown), (second, hidden) = _page("the traced image"), _page("the Cost plot")
    tabs.addTab(first, "Image order")
    tabs.addTab(second, "Cost")
    holder = QWidget()
    QVBoxLayout(holder).setContentsMargins(30, 30, 30, 30)  # the window's background shows around
    holder.layout().addWidget(tabs)
    window.setCentralWidget(holder)
    qtbot.addWidget(window)
    window.resize(640, 400)
    window.show()
    qtbot.waitExposed(window)
    return window, tabs, shown, hidden


def _background(widget) -> str:
    """The colour at the widget's top left corner (above a label's text, which is centred)."""
    return widget.grab().toImage().pixelColor(1, 1).name()


def _text_colour(label) -> str:
    label.ensurePolished()
    return label.palette().color(QPalette.ColorRole.WindowText).name()


def test_the_shown_tab_turns_black_and_white_at_once_and_a_hidden_one_when_it_is_shown(tabs):
    window, tab_widget, shown, hidden = tabs
    restyles = _Restyles(hidden)
    contrast = HighContrast(window)
    contrast.set_on(True)
    assert _background(shown) == "#000000" and _text_colour(shown) == "#ffffff"
    assert restyles.count == 0  # the hidden tab's widgets were not restyled ...
    tab_widget.setCurrentIndex(1)
    assert restyles.count > 0 and _text_colour(hidden) == "#ffffff"  # ... until it was shown
    assert _background(hidden) == "#000000"
    contrast.set_on(False)
    tab_widget.setCurrentIndex(0)
    assert _background(shown) != "#000000" and _text_colour(shown) != "#ffffff"  # normal again


def test_between_the_panes_the_window_is_black_too(tabs):
    window, *_ = tabs
    contrast = HighContrast(window)
    contrast.set_on(True)
    picture = window.grab().toImage()
    assert picture.pixelColor(10, picture.height() // 2).name() == "#000000"  # the margin around the tabs
    contrast.set_on(False)
    picture = window.grab().toImage()
    assert picture.pixelColor(10, picture.height() // 2).name() != "#000000"


def test_a_dialog_opened_later_is_in_high_contrast_too(tabs, qtbot):
    window, *_ = tabs
    HighContrast(window).set_on(True)
    dialog = QDialog(window)
    label = QLabel("Export written", dialog)
    QVBoxLayout(dialog).addWidget(label)
    dialog.show()
    qtbot.waitExposed(dialog)
    assert _text_colour(label) == "#ffffff" and _background(dialog) == "#000000"


def test_a_widget_with_colours_of_its_own_keeps_them(tabs):
    # The scene editor's red error beside a field, a colour's swatch.
    window, tab_widget, shown, _ = tabs
    error = QLabel("refused: the radius must be positive", shown.parentWidget())
    error.setStyleSheet("color: #d00000;")
    error.show()
    HighContrast(window).set_on(True)
    assert _text_colour(error) == "#d00000"
    assert error.styleSheet() == "color: #d00000;"
