"""Where the file dialogs start: the folder the user last opened or saved a file in.

Every open and save dialog of the window (scenes, lessons, meshes, exports, the Cost
sweep's files) starts in one folder, kept in the user's settings
(:mod:`views.user_settings`) so that it outlives the session; before the first
file, or once that folder is gone, it is the user's Documents folder (their home
folder if there is none), never the folder the program was started from.
"""

from __future__ import annotations

import os
from pathlib import Path

from PySide6.QtCore import QStandardPaths
from PySide6.QtWidgets import QFileDialog, QWidget

from views.user_settings import user_settings

FOLDER_SETTING = "files/folder"


def start_folder() -> str:
    """The folder the next file dialog starts in."""
    folder = user_settings().value(FOLDER_SETTING, "", str)
    if folder and os.path.isdir(folder):
        return folder
    documents = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.DocumentsLocation)
    return documents if documents and os.path.isdir(documents) else str(Path.home())


def remember_folder(path: str) -> None:
    """Start the next file dialogs in the folder of the file ``path`` the user chose."""
    user_settings().setValue(FOLDER_SETTING, os.path.dirname(os.path.abspath(path)))


def ask_open(parent: QWidget, title: str, filters: str) -> str | None:
    """The file the user picks to open (``filters`` as Qt writes them), or ``None`` if cancelled."""
    path, _ = QFileDialog.getOpenFileName(parent, title, start_folder(), filters)
    if not path:
        return None
    remember_folder(path)
    return path


def ask_save(parent: QWidget, title: str, name: str, filters: str) -> tuple[str, str] | None:
    """Where the user saves (starting on ``name`` in :func:`start_folder`) and the filter chosen,
    or ``None`` if cancelled."""
    path, chosen = QFileDialog.getSaveFileName(parent, title, os.path.join(start_folder(), name), filters)
    if not path:
        return None
    remember_folder(path)
    return path, chosen
