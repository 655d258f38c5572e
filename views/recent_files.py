"""File → Open recent: the scenes and lessons opened or saved last, kept across sessions.

:class:`RecentFiles` fills a menu with the files the window last opened or
saved (most recent first, at most :data:`MOST`, each file once), numbered for
the keyboard (Alt+F, R, then 1 to 8), each with its folder in its tooltip and the
status bar.  The list is kept in the user's settings (:mod:`views.user_settings`),
so it outlives the session.  A file that is no longer where it was is not opened: a
dialog says so, naming its path, and it leaves the list.  One that is there but cannot be
read (a folder, a named pipe, a file it may not read) goes to the window's loader, whose
dialog says why, and stays on the list.
"""

from __future__ import annotations

import json
import os

from PySide6.QtCore import QObject, Signal
from PySide6.QtWidgets import QMenu, QMessageBox, QWidget

from views.user_settings import user_settings

RECENT_SETTING = "files/recent"
MOST = 8
"""How many files the list keeps."""
SCENE, LESSON = "scene", "lesson"
"""The kinds of file the list keeps."""


class RecentFiles(QObject):
    """The recent files in ``menu`` (a submenu of File), for ``parent``'s dialogs.

    Signals
    -------
    chosen(str kind, str path) : the user picked a file that is still there; the window opens it.
    """

    chosen = Signal(str, str)

    def __init__(self, menu: QMenu, parent: QWidget):
        super().__init__(parent)
        self.menu = menu
        self._parent = parent
        self._fill()

    def entries(self) -> list[tuple[str, str]]:
        """``(kind, absolute path)`` of each file, the most recent first."""
        try:
            kept = json.loads(user_settings().value(RECENT_SETTING, "[]", str))
        except ValueError:  # written by hand, or by another program
            return []
        if not isinstance(kept, list):
            return []
        return [(kind, path) for kind, path in (e for e in kept if isinstance(e, list) and len(e) == 2)
                if kind in (SCENE, LESSON) and isinstance(path, str)]

    def add(self, kind: str, path) -> None:
        """The window opened or saved the file ``path`` of ``kind``: first in the list."""
        path = os.path.abspath(path)
        self._keep([(kind, path)] + [(k, p) for k, p in self.entries() if p != path])

    def forget(self, path: str) -> None:
        self._keep([(k, p) for k, p in self.entries() if p != path])

    def clear(self) -> None:
        self._keep([])

    def open(self, kind: str, path: str) -> None:
        """Open a file of the list: ``chosen``, or, if it is gone, a dialog and off the list."""
        if not os.path.exists(path):
            self.forget(path)
            QMessageBox.warning(self._parent, "Cannot open recent file",
                                f"{os.path.basename(path)} is no longer there:\n{path}\n\n"
                                "It is taken off the list of recent files.")
            return
        self.chosen.emit(kind, path)

    def _keep(self, entries: list[tuple[str, str]]) -> None:
        settings = user_settings()
        settings.setValue(RECENT_SETTING, json.dumps([list(e) for e in entries[:MOST]]))
        settings.sync()
        self._fill()

    def _fill(self) -> None:
        self.menu.clear()
        entries = self.entries()
        for k, (kind, path) in enumerate(entries):
            name = os.path.basename(path).replace("&", "&&")
            action = self.menu.addAction(f"&{k + 1}  {name}" + ("  (lesson)" if kind == LESSON else ""))
            action.setToolTip(path)
            action.setStatusTip(f"Open {path}")
            action.triggered.connect(lambda _=False, kind=kind, path=path: self.open(kind, path))
        if not entries:
            self.menu.addAction("No recent files").setEnabled(False)
        self.menu.addSeparator()
        clear = self.menu.addAction("Clear the list", self.clear)
        clear.setEnabled(bool(entries))
        self.menu.setToolTipsVisible(True)
