"""High contrast for a lecture hall: black and white with a yellow accent, pane by pane.

A style sheet set on a window restyles every widget under it, the hidden ones
too: after the lessons the window holds about a thousand widgets, three in
four of them on the tabs not shown, and one sheet on the window held it for
some 70 ms.  So :class:`HighContrast` sets the sheet on each pane that
shows (a dock, the menu bar, the status bar, the shown page of every tab
widget or stack) and on a hidden page when it is next shown; a widget or
dialog made later beside the panes takes it when Qt first polishes it.  The
window's own background, seen between the panes, is turned black by its
palette.

Colours only: the font's size stays the application's, so the text scale
(:mod:`views.presentation`) reaches every widget whatever its sheet.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject
from PySide6.QtGui import QColor, QPalette
from PySide6.QtWidgets import QStackedWidget, QWidget

#: Black and white with a yellow accent.
HIGH_CONTRAST = """
QWidget { background-color: #000000; color: #ffffff; }
QWidget:disabled { color: #9a9a9a; }
QAbstractItemView { alternate-background-color: #262626; }
QAbstractButton, QComboBox, QSpinBox, QDoubleSpinBox, QLineEdit {
    border: 2px solid #ffffff; padding: 3px; }
QAbstractButton:checked, QAbstractButton:pressed { background-color: #ffd400; color: #000000; }
QToolButton { background-color: #ffffff; color: #000000; }
QCheckBox, QRadioButton { border: none; }
QCheckBox:checked, QRadioButton:checked { background-color: #000000; color: #ffffff; }
QCheckBox::indicator, QRadioButton::indicator {
    width: 0.8em; height: 0.8em; border: 2px solid #ffffff; background-color: #000000; }
QCheckBox::indicator:checked, QRadioButton::indicator:checked { background-color: #ffd400; }
QRadioButton::indicator { border-radius: 0.4em; }
QListView::item:selected, QTreeView::item:selected, QTableView::item:selected {
    background-color: #ffd400; color: #000000; }
QTabBar::tab:selected { background-color: #ffd400; color: #000000; }
QToolTip { background-color: #ffffff; color: #000000; }
QSlider::groove:horizontal { height: 0.3em; background: #9a9a9a; border-radius: 0.15em; }
QSlider::sub-page:horizontal { background: #ffd400; border-radius: 0.15em; }
QSlider::handle:horizontal {
    width: 1.2em; margin: -0.45em 0; background: #ffffff; border: 2px solid #ffd400; border-radius: 0.6em; }
"""

_WATCHED = "_high_contrast_watched"
"""A stack's property: its page changes already restyle the page shown."""


def _dark_palette() -> QPalette:
    """The sheet's colours as a palette: for the window's background between its panes, and the
    frames its containers draw (a tab widget's around its pages)."""
    role = QPalette.ColorRole
    palette = QPalette(QColor("#000000"))  # every role derived from black ...
    for name, colour in ((role.WindowText, "#ffffff"), (role.Text, "#ffffff"), (role.ButtonText, "#ffffff"),
                         (role.Base, "#000000"), (role.AlternateBase, "#262626")):
        palette.setColor(name, QColor(colour))  # ... but the text white
    for name in (role.WindowText, role.Text):
        palette.setColor(QPalette.ColorGroup.Disabled, name, QColor("#9a9a9a"))
    return palette


def _hides_pages(widget: QWidget) -> bool:
    """Whether ``widget`` or a widget under it is a stack with a page not shown."""
    stacks = widget.findChildren(QStackedWidget)
    if isinstance(widget, QStackedWidget):
        stacks.append(widget)
    return any(stack.count() > 1 for stack in stacks)


def _own_sheet(widget: QWidget) -> bool:
    """Whether ``widget`` has a style sheet of its own (a swatch's colour, an error's red), which
    outranks its parents' and so is not replaced: its children are styled instead."""
    return widget.styleSheet() not in ("", HIGH_CONTRAST)


class HighContrast(QObject):
    """The high-contrast theme of ``window``, on or off (off at first)."""

    def __init__(self, window: QWidget):
        super().__init__(window)
        self.window = window
        self._on = False

    def on(self) -> bool:
        return self._on

    def sheet(self) -> str:
        """The style sheet the window's panes take now."""
        return HIGH_CONTRAST if self._on else ""

    def set_on(self, on: bool) -> None:
        if bool(on) == self._on:
            return
        self._on = bool(on)
        self.window.setPalette(_dark_palette() if self._on else QPalette())
        self._style(self.window, top=True)

    def _style(self, widget: QWidget, top: bool = False) -> None:
        """Give the panes under ``widget`` that show the sheet now, and have its stacks give it to
        a page when they show it."""
        if isinstance(widget, QStackedWidget) and widget.count() > 1:
            widget.installEventFilter(self)  # once, however often installed
            if not widget.property(_WATCHED):
                widget.setProperty(_WATCHED, True)
                widget.currentChanged.connect(lambda _index, stack=widget: self._page_shown(stack))
            if widget.currentWidget() is not None:
                self._style(widget.currentWidget())
            return
        if not top and not _own_sheet(widget) and not _hides_pages(widget):
            if widget.styleSheet() != self.sheet():
                widget.setStyleSheet(self.sheet())
            return
        widget.installEventFilter(self)
        for child in widget.children():
            if isinstance(child, QWidget):
                self._style(child)

    def _page_shown(self, stack: QStackedWidget) -> None:
        if stack.currentWidget() is not None:
            self._style(stack.currentWidget())

    def eventFilter(self, watched, event) -> bool:  # noqa: N802 (Qt's name)
        # A widget made later beside the panes (a dialog, a pane or a page added): styled as Qt
        # first polishes it, before it is drawn.  (Inside a pane it takes the pane's sheet.)  With
        # the theme off there is nothing to give: a new widget has no sheet.
        if self._on and event.type() == QEvent.Type.ChildPolished:
            child = event.child()
            if isinstance(child, QWidget):
                self._style(child)
        return False
