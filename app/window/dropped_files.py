"""Files dropped on the window: a scene or a lesson opens, a mesh joins the scene.

A file manager's files dragged onto the window open as File → Open scene…,
File → Open lesson… and Edit → Add → Mesh from file… would open them: a lesson
file by the format its first lines name, any other ``.json`` as a scene (whose
loader names every problem of a file that is not one), an OBJ, STL or PLY file
as a mesh added to the scene.  Anything else is refused in the status bar, naming
the file and what may be dropped.  One file at a time: of several, the first.
"""

from __future__ import annotations

import re
import sys
from pathlib import Path

from PySide6.QtCore import QEvent, QObject

from core.files import safe_files
from core.files.mesh_files import EXTENSIONS as MESH_EXTENSIONS
from core.lessons.lesson_file import FORMAT as LESSON_FORMAT

SCENE, LESSON, MESH = "scene", "lesson", "mesh"
PEEK_BYTES = 65_536
"""How much of a JSON file is read to tell a lesson from a scene (its ``"format"`` comes first)."""


def kind_of(path) -> str | None:
    """What a dropped file is opened as: :data:`SCENE`, :data:`LESSON`, :data:`MESH`, or None.

    >>> kind_of("cube.STL"), kind_of("notes.txt")
    ('mesh', None)
    """
    suffix = Path(path).suffix.lower()
    if suffix in MESH_EXTENSIONS:
        return MESH
    if suffix != ".json":
        return None
    if safe_files.input_file_problem(path, sys.maxsize) is not None:
        return SCENE  # opening it says why it cannot be read (a FIFO would block this read for ever)
    try:
        with open(path, "rb") as f:
            head = f.read(PEEK_BYTES).decode("utf-8", "replace")
    except OSError:
        return SCENE  # opening it says why it cannot be read
    lesson = re.search(r'"format"\s*:\s*"' + re.escape(LESSON_FORMAT) + '"', head)
    return LESSON if lesson else SCENE


def dropped_paths(event) -> list[str]:
    """The local files of a drag or drop event (none for text, web links and the like)."""
    mime = event.mimeData()
    return [url.toLocalFile() for url in mime.urls() if url.isLocalFile()] if mime.hasUrls() else []


class DroppedFiles(QObject):
    """Opens the files dropped on ``window`` (a :class:`app.window.main_window.MainWindow`)."""

    def __init__(self, window):
        super().__init__(window)
        self.window = window
        window.setAcceptDrops(True)
        window.installEventFilter(self)

    def eventFilter(self, watched, event) -> bool:
        if watched is self.window and event.type() in (QEvent.Type.DragEnter, QEvent.Type.DragMove):
            if dropped_paths(event):
                event.acceptProposedAction()
                return True
        elif watched is self.window and event.type() == QEvent.Type.Drop:
            paths = dropped_paths(event)
            if paths:
                event.acceptProposedAction()
                self.open(paths)
                return True
        return False

    def open(self, paths: list[str]) -> None:
        """Open the first of ``paths`` as its kind asks (one file at a time, as the menus do), and
        say what was not opened."""
        w, path = self.window, paths[0]
        kind = kind_of(path)
        if kind == SCENE:
            w.open_scene(path)
        elif kind == LESSON:
            w.lesson_panel.open_lesson_file(path)
        elif kind == MESH:
            w.editor.add_mesh_file(path)
        else:
            w.statusBar().showMessage(f"Cannot open {Path(path).name}: drop a scene or a lesson (.json) or a "
                                      f"mesh ({', '.join(MESH_EXTENSIONS)})", 10000)
        if len(paths) > 1:
            w.statusBar().showMessage(f"{len(paths)} files dropped: only {Path(path).name} was opened, "
                                      "one file at a time", 10000)
