"""Key filters on the widget with the keyboard focus, not on the whole application.

Qt sends a key press, and first the question whether a shortcut may take it
(a ShortcutOverride event), to the widget that has the keyboard focus, or to
the active window when no widget in it has the focus.  A filter that only
looks at keys needs to see that one widget's events.  Installed on the
application instead, it would see every event of every widget, each one
crossing into Python: a restyle of the window (presentation mode, the text
size) sends thousands, and took a second so.

:func:`follow_focus` keeps a filter on the focus widget (or the active
window) as the focus moves, from window to window too.
"""

from __future__ import annotations

import contextlib

from PySide6.QtCore import QObject
from PySide6.QtWidgets import QApplication, QWidget


class FollowFocus(QObject):
    """Keeps ``key_filter`` installed on the widget the keys go to; see :func:`follow_focus`."""

    def __init__(self, key_filter: QObject):
        super().__init__(key_filter)
        self.key_filter = key_filter
        self._on: QWidget | None = None
        app = QApplication.instance()
        app.focusChanged.connect(self._move)
        app.focusWindowChanged.connect(self._move)
        self._move()

    def watched(self) -> QWidget | None:
        """The widget the filter is on now: the focus widget, else the active window."""
        return self._on

    def _move(self, *_) -> None:
        target = QApplication.focusWidget() or QApplication.activeWindow()
        if target is self._on:
            return
        self._remove()
        self._on = target
        if target is not None:
            target.installEventFilter(self.key_filter)
            target.destroyed.connect(self._gone)  # Qt drops its filters with it: nothing to remove then

    def _gone(self, *_) -> None:
        self._on = None

    def _remove(self) -> None:
        if self._on is not None:
            with contextlib.suppress(RuntimeError):  # its Python side knows it was deleted meanwhile
                self._on.destroyed.disconnect(self._gone)
                self._on.removeEventFilter(self.key_filter)
        self._on = None

    def stop(self) -> None:
        """Take the filter off and stop following the focus."""
        app = QApplication.instance()
        app.focusChanged.disconnect(self._move)
        app.focusWindowChanged.disconnect(self._move)
        self._remove()


def follow_focus(key_filter: QObject) -> FollowFocus:
    """Install ``key_filter`` on the widget with the keyboard focus (or the active window when
    none has it), and move it there whenever the focus moves; ``.stop()`` ends that."""
    return FollowFocus(key_filter)
