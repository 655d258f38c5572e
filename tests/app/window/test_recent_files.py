"""File → Open recent lists the scenes and lessons opened or saved last, across sessions, and a file
dropped on the window opens as the menus would open it."""

import json

from PySide6.QtCore import QMimeData, QPoint, Qt, QUrl
from PySide6.QtGui import QDragEnterEvent, QDropEvent
from PySide6.QtWidgets import QApplication, QMenu, QMessageBox
from window_helpers import open_scene_file

from app.window.main_window import MainWindow
from core import presets
from core.files import scene_file
from core.lessons.lesson_file import FILES
from views.recent_files import MOST


def _window(qtbot) -> MainWindow:
    window = MainWindow(presets.lecture_scene())
    qtbot.addWidget(window)
    return window


def _recent_menu(window) -> QMenu:
    file_menu = next(a.menu() for a in window.menuBar().actions() if a.text() == "&File")
    return next(a.menu() for a in file_menu.actions() if a.text() == "Open &recent")


def _entries(window) -> list[str]:
    return [a.text() for a in _recent_menu(window).actions() if not a.isSeparator()]


def test_opened_and_saved_scenes_and_opened_lessons_are_listed_most_recent_first(qtbot, tmp_path):
    window = _window(qtbot)
    assert _entries(window) == ["No recent files", "Clear the list"]
    first, second = tmp_path / "first.json", tmp_path / "second.json"
    scene_file.save(presets.zbuffer_three_polygons(), first)
    scene_file.save(presets.lecture_scene(), second)
    assert open_scene_file(qtbot, window, first) and open_scene_file(qtbot, window, second)
    window.lesson_panel.open_lesson_file(FILES / "05_zbuffer.json")
    saved = tmp_path / "saved.json"
    assert window.editor.save_to(saved)
    assert _entries(window) == ["&1  saved.json", "&2  05_zbuffer.json  (lesson)", "&3  second.json",
                                "&4  first.json", "Clear the list"]
    assert _recent_menu(window).actions()[2].toolTip() == str(second)
    assert open_scene_file(qtbot, window, first)  # again: back to the top, listed once
    assert _entries(window)[:2] == ["&1  first.json", "&2  saved.json"]

    # Another session: the list is still there, and its entries open their files.
    later = _window(qtbot)
    assert _entries(later) == _entries(window)
    with qtbot.waitSignal(later.scene_file_done):
        next(a for a in _recent_menu(later).actions() if a.text() == "&4  second.json").trigger()
    assert later.model.scene == presets.lecture_scene() and later.scene_path == second
    next(a for a in _recent_menu(later).actions() if "(lesson)" in a.text()).trigger()
    assert later.lesson_panel.current_lesson().path == FILES / "05_zbuffer.json"
    next(a for a in _recent_menu(later).actions() if a.text() == "Clear the list").trigger()
    assert _entries(later) == ["No recent files", "Clear the list"]


def test_the_list_keeps_the_last_eight_and_a_file_gone_is_said_and_taken_off(qtbot, tmp_path, monkeypatch):
    window = _window(qtbot)
    for k in range(MOST + 2):
        path = tmp_path / f"scene{k}.json"
        scene_file.save(presets.lecture_scene(), path)
        assert open_scene_file(qtbot, window, path)
    names = _entries(window)[:-1]
    assert len(names) == MOST == 8
    assert names[0] == "&1  scene9.json" and names[-1] == "&8  scene2.json"
    (tmp_path / "scene5.json").unlink()
    said = []
    monkeypatch.setattr(QMessageBox, "warning", lambda parent, title, text: said.append((title, text)))
    before = window.scene_path
    next(a for a in _recent_menu(window).actions() if a.text().endswith("scene5.json")).trigger()
    assert said == [("Cannot open recent file", f"scene5.json is no longer there:\n{tmp_path / 'scene5.json'}"
                     "\n\nIt is taken off the list of recent files.")]
    assert window.scene_path == before
    assert not any("scene5.json" in name for name in _entries(window))


def test_a_list_spoiled_by_hand_reads_as_empty(qtbot):
    from views.user_settings import user_settings

    user_settings().setValue("files/recent", "{not json")
    assert _entries(_window(qtbot)) == ["No recent files", "Clear the list"]
    user_settings().setValue("files/recent", json.dumps([["scene", 3], ["virus", "/x.json"], "odd"]))
    assert _entries(_window(qtbot)) == ["No recent files", "Clear the list"]


def _drop(window, paths) -> None:
    """Drag ``paths`` from a file manager into the window and let go."""
    mime = QMimeData()
    mime.setUrls([QUrl.fromLocalFile(str(p)) for p in paths])
    args = (QPoint(10, 10), Qt.DropAction.CopyAction, mime, Qt.MouseButton.NoButton,
            Qt.KeyboardModifier.NoModifier)
    enter = QDragEnterEvent(*args)
    QApplication.sendEvent(window, enter)
    assert enter.isAccepted()  # the pointer says a drop is welcome
    drop = QDropEvent(*args)
    QApplication.sendEvent(window, drop)
    assert drop.isAccepted()


def test_a_scene_a_lesson_or_a_mesh_dropped_on_the_window_opens(qtbot, tmp_path):
    window = _window(qtbot)
    scene = tmp_path / "dropped.json"
    scene_file.save(presets.zbuffer_three_polygons(), scene)
    with qtbot.waitSignal(window.scene_file_done):
        _drop(window, [scene])
    assert window.scene_path == scene and window.model.scene == presets.zbuffer_three_polygons()
    _drop(window, [FILES / "12_ray_casting.json"])
    assert window.lesson_panel.current_lesson().path == FILES / "12_ray_casting.json"
    mesh = tmp_path / "tetra.obj"
    mesh.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 2 4\nf 1 3 4\nf 2 3 4\n")
    objects = len(window.model.scene.objects)
    _drop(window, [mesh])
    qtbot.waitUntil(lambda: len(window.model.scene.objects) == objects + 1)
    assert window.model.scene.objects[-1].triangles.shape == (4, 3)
    window.editor.stack.setClean()


def test_a_file_that_is_neither_is_refused_in_the_status_bar_and_a_bad_scene_in_a_dialog(
        qtbot, tmp_path, monkeypatch):
    window = _window(qtbot)
    notes = tmp_path / "notes.txt"
    notes.write_text("hello")
    before = window.model.scene
    _drop(window, [notes])
    assert window.statusBar().currentMessage() == ("Cannot open notes.txt: drop a scene or a lesson (.json) "
                                                   "or a mesh (.obj, .stl, .ply)")
    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda *args: shown.append(args[2]))
    bad = tmp_path / "bad.json"
    bad.write_text("{\"objects\": [")
    with qtbot.waitSignal(window.scene_file_done):
        _drop(window, [bad])
    assert window.model.scene == before
    assert shown and shown[0].startswith("bad.json:")


def test_a_link_whose_file_is_gone_is_said_to_be_no_longer_there(qtbot, tmp_path, monkeypatch):
    from views.recent_files import SCENE

    window = _window(qtbot)
    link = tmp_path / "scene.json"
    link.symlink_to(tmp_path / "moved away.json")
    window.recent_files.add(SCENE, link)
    said = []
    monkeypatch.setattr(QMessageBox, "warning", lambda parent, title, text: said.append(text))
    window.recent_files.open(SCENE, str(link))
    assert said and said[0].startswith("scene.json is no longer there")
    assert window.recent_files.entries() == []
