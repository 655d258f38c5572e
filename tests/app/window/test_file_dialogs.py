"""The open and save dialogs start in the user's folders, never in the program's own."""

from pathlib import Path

from checkout import ROOT
from PySide6.QtCore import QStandardPaths
from PySide6.QtWidgets import QFileDialog

from app.window.main_window import MainWindow
from core import presets
from core.files import scene_file


def _window(qtbot) -> MainWindow:
    window = MainWindow(presets.lecture_scene())
    qtbot.addWidget(window)
    return window


def test_open_and_save_start_in_documents_then_in_the_folder_last_used(qtbot, monkeypatch, tmp_path):
    documents = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.DocumentsLocation)
    users = {Path(documents), Path.home()}
    asked = []

    def open_dialog(parent, title, start, filters):
        asked.append(Path(start))
        return answer, filters

    def save_dialog(parent, title, start, filters):
        asked.append(Path(start).parent)
        return str(tmp_path / "other" / "saved.json"), filters

    monkeypatch.setattr(QFileDialog, "getOpenFileName", open_dialog)
    monkeypatch.setattr(QFileDialog, "getSaveFileName", save_dialog)
    monkeypatch.chdir(ROOT)  # started from the program's folder
    scenes = tmp_path / "scenes"
    scenes.mkdir()
    (tmp_path / "other").mkdir()
    answer = str(scenes / "mine.json")
    scene_file.save(presets.zbuffer_three_polygons(), answer)
    window = _window(qtbot)
    with qtbot.waitSignal(window.scene_file_done):  # read off the GUI thread
        window.open_scene_dialog()
    assert asked[-1] in users and asked[-1] != ROOT  # a first run: the user's Documents (or home)
    assert window.scene_path == Path(answer)
    window.save_scene_dialog()
    assert asked[-1] == scenes  # where the last file was opened
    again = _window(qtbot)  # as after a restart
    again.lesson_panel.open_lesson_file()  # another kind of file: the same folder
    assert asked[-1] == tmp_path / "other"  # where the last file was saved
