"""Every window inside its screen: the main window, its dialogs and the presenter window.

A window's *frame* is its client area plus what the window manager adds (the
title bar, the borders); a window whose client area fits the screen can still
hang its bottom edge, with the buttons there, off a small screen.
:func:`keep_on_screen` shrinks a window (down to its minimum size) and moves
it until its frame lies inside the screen's available area (the screen less
its panels).  :class:`KeepWindowsOnScreen` does so for the windows it
watches as each is shown and whenever it grows; the window manager's frame
is known only once the window is on screen, so it checks again when the
window manager first places it.  A full-screen or maximized window is the
window manager's to place.

It watches the windows it is given, the dialogs they open (windows among
their children) and every window that becomes active, each on its own: a
filter on the application would see every event of every widget cross into
Python, and a restyle of the window sends thousands.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, QRect, Qt, QTimer
from PySide6.QtWidgets import QApplication, QWidget

_CHECKED = (QEvent.Type.Show, QEvent.Type.Resize, QEvent.Type.Move)
_CHILDREN = (QEvent.Type.ChildAdded, QEvent.Type.ChildPolished)
"""A watched window's new child, a dialog among them once it is polished (its flags are set then)."""


def frame_fits(window: QWidget, screen: QRect | None = None) -> bool:
    """Whether ``window``'s frame lies inside ``screen`` (default: its screen's available area)."""
    screen = window.screen().availableGeometry() if screen is None else screen
    return screen.contains(window.frameGeometry())


def keep_on_screen(window: QWidget) -> None:
    """Shrink and move ``window`` so that its frame lies inside its screen's available area."""
    if window.isFullScreen() or window.isMaximized() or not window.isVisible():
        return
    available = window.screen().availableGeometry()
    frame, inner = window.frameGeometry(), window.geometry()
    extra_width, extra_height = frame.width() - inner.width(), frame.height() - inner.height()
    least = window.minimumSize()
    width = max(least.width(), min(inner.width(), available.width() - extra_width))
    height = max(least.height(), min(inner.height(), available.height() - extra_height))
    # The client area's place, so that its frame's top left corner lands at (x, y).
    x = max(available.left(), min(frame.left(), available.right() + 1 - width - extra_width))
    y = max(available.top(), min(frame.top(), available.bottom() + 1 - height - extra_height))
    placed = QRect(x + inner.left() - frame.left(), y + inner.top() - frame.top(), width, height)
    if placed != inner:
        window.setGeometry(placed)


class KeepWindowsOnScreen(QObject):
    """Keeps the watched windows (not menus or tool tips) on screen: see :meth:`watch`.

    A window is checked after it is shown, resized or moved by the window
    manager, once the event is handled (so its new frame is known); a window
    the user drags partly off screen on purpose is moved back only when its
    frame no longer fits because it grew.
    """

    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self._pending: set[int] = set()
        self._placed: set[int] = set()
        QApplication.instance().focusWindowChanged.connect(self._activated)

    def watch(self, window: QWidget) -> None:
        """Keep ``window`` on screen, and the windows it opens (dialogs) too."""
        window.installEventFilter(self)  # once: Qt moves a filter installed again to the front
        if window.isVisible():
            self._check_soon(window)

    def stop(self) -> None:
        """Stop watching windows as they become active (those watched keep their filter)."""
        QApplication.instance().focusWindowChanged.disconnect(self._activated)

    def _activated(self, _window) -> None:
        active = QApplication.activeWindow()  # the QWidget of the window given
        if active is not None and not _pop_up(active):
            self.watch(active)

    def eventFilter(self, watched, event) -> bool:
        kind = event.type()
        if kind in _CHILDREN:
            child = event.child()
            if isinstance(child, QWidget) and child.isWindow() and not _pop_up(child):
                child.installEventFilter(self)  # a dialog of this window: shown later, checked then
        elif (kind in _CHECKED and isinstance(watched, QWidget) and watched.isWindow()
              and not _pop_up(watched)):
            key = id(watched)
            if kind == QEvent.Type.Show:
                self._placed.discard(key)  # the window manager places it (again)
            if kind != QEvent.Type.Move or key not in self._placed:
                self._check_soon(watched)
        return False

    def _check_soon(self, window: QWidget) -> None:
        key = id(window)
        if key in self._pending:
            return
        self._pending.add(key)

        def check():
            self._pending.discard(key)
            try:
                keep_on_screen(window)
            except RuntimeError:  # the window was deleted meanwhile
                return
            if window.frameGeometry() != window.geometry():  # the window manager framed it: it is placed
                self._placed.add(key)

        QTimer.singleShot(0, self, check)


def _pop_up(widget: QWidget) -> bool:
    """Menus, tool tips and other pop-ups, which Qt places itself."""
    kind = widget.windowType()
    return kind in (Qt.WindowType.Popup, Qt.WindowType.ToolTip, Qt.WindowType.SplashScreen,
                    Qt.WindowType.Desktop)
