"""File → Open in the window with files that used to crash or hang VTK's readers.

Each case runs the real window in a subprocess, so a crash or a hang fails the test
instead of ending the test run: the window must show one dialog naming the file, keep
its current scene, and stay usable (it renders the old scene again afterwards).
"""

import json
import os
import struct
import subprocess
import sys
from pathlib import Path

import pytest
from checkout import ROOT

WINDOW = """
import json, sys
from PySide6.QtCore import QEventLoop, QMimeData, QPoint, Qt, QUrl
from PySide6.QtGui import QDragEnterEvent, QDropEvent
from PySide6.QtWidgets import QApplication, QMessageBox

from app.window.main_window import MainWindow
from core import presets

app = QApplication([])
messages = []
QMessageBox.critical = staticmethod(lambda parent, title, text, *rest: messages.append(text))
window = MainWindow(presets.lecture_scene())
window.show()
before = window.model.scene
"""
"""The start of each driver: the real window, its dialogs' messages kept in ``messages``."""

DRIVER = WINDOW + """

def open_scene_file(path):  # File, Open scene: whether it opened, once read (off the GUI thread)
    done, loop = [], QEventLoop()
    window.scene_file_done.connect(lambda _path, opened: (done.append(opened), loop.quit()))
    window.open_scene(path)
    loop.exec()
    window.scene_file_done.disconnect()
    return done[0]


for k, path in enumerate(sys.argv[1:]):
    messages.clear()
    opened = open_scene_file(path)
    fov = 41.0 + k
    window.model.set_camera(window.model.camera.replace(fov_y_deg=fov))  # still usable
    print(json.dumps({"opened": opened, "kept": window.model.scene.objects == before.objects,
                      "fov_set": window.model.camera.fov_y_deg == fov, "messages": list(messages)}))
window.close()
"""


def _binary_ply_shorter_than_its_header(path: Path) -> None:
    header = (b"ply\nformat binary_little_endian 1.0\nelement vertex 1000\n"
              b"property float x\nproperty float y\nproperty float z\n"
              b"element face 1\nproperty list uchar int vertex_indices\nend_header\n")
    path.write_bytes(header + struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0))


def _obj_with_missing_texture_coordinates_and_a_face_past_the_vertices(path: Path) -> None:
    path.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1/7 2/8 3/9\nf 1 2 98\n")


def _ascii_ply_declaring_two_billion_vertices(path: Path) -> None:
    path.write_text("ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\n"
                    "property float y\nproperty float z\nend_header\n0 0 0\n")


def _fifo(path: Path) -> None:
    os.mkfifo(path)


CASES = {
    "short.ply": _binary_ply_shorter_than_its_header,
    "bad.obj": _obj_with_missing_texture_coordinates_and_a_face_past_the_vertices,
    "huge.ply": _ascii_ply_declaring_two_billion_vertices,
    "pipe.obj": _fifo,
}


@pytest.mark.gui
def test_opening_scenes_with_damaged_meshes_shows_a_dialog_and_keeps_the_scene(tmp_path):
    scenes = []
    for name, make in sorted(CASES.items()):
        make(tmp_path / name)
        scene = tmp_path / f"scene-{name}.json"
        scene.write_text(json.dumps({"objects": [{"type": "mesh_file", "path": name}]}))
        scenes.append(str(scene))
    out = subprocess.run([sys.executable, "-c", DRIVER, *scenes], cwd=ROOT, capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    results = [json.loads(line) for line in out.stdout.strip().splitlines()[-len(CASES):]]
    for name, result in zip(sorted(CASES), results, strict=True):
        assert result["opened"] is False and result["kept"] is True, name
        assert result["fov_set"] is True, name
        assert len(result["messages"]) == 1 and name in result["messages"][0], (name, result)
    assert "Traceback" not in out.stderr


DROP_DRIVER = WINDOW + """
mime = QMimeData()
mime.setUrls([QUrl.fromLocalFile(sys.argv[1])])
args = (QPoint(10, 10), Qt.DropAction.CopyAction, mime, Qt.MouseButton.NoButton,
        Qt.KeyboardModifier.NoModifier)
done, loop = [], QEventLoop()
window.scene_file_done.connect(lambda _path, opened: (done.append(opened), loop.quit()))
QApplication.sendEvent(window, QDragEnterEvent(*args))
QApplication.sendEvent(window, QDropEvent(*args))  # a FIFO read here would never return
loop.exec()
print(json.dumps({"opened": done[0], "kept": window.model.scene.objects == before.objects,
                  "messages": messages}))
window.close()
"""


@pytest.mark.gui
def test_a_named_pipe_dropped_on_the_window_is_refused_in_a_dialog_and_nothing_hangs(tmp_path):
    """Dropping a file reads its first lines to tell a lesson from a scene: a FIFO named
    ``scene.json`` would block that read, on the GUI thread, until something wrote to it."""
    pipe = tmp_path / "scene.json"
    os.mkfifo(pipe)
    out = subprocess.run([sys.executable, "-c", DROP_DRIVER, str(pipe)], cwd=ROOT, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result["opened"] is False and result["kept"] is True
    assert len(result["messages"]) == 1 and "scene.json" in result["messages"][0]
    assert "not a regular file" in result["messages"][0]


RECENT_DRIVER = WINDOW + """
from views.recent_files import LESSON, SCENE

scene, lesson = sys.argv[1:]
done, loop = [], QEventLoop()
window.scene_file_done.connect(lambda _path, opened: (done.append(opened), loop.quit()))
window.recent_files.add(SCENE, scene)
window.recent_files.add(LESSON, lesson)
window.recent_files.open(SCENE, scene)
loop.exec()
window.recent_files.open(LESSON, lesson)
box = window.findChild(QMessageBox, "lesson_error")
print(json.dumps({"opened": done[0], "kept": window.model.scene.objects == before.objects,
                  "messages": messages, "lesson": box.text() + " " + box.informativeText(),
                  "listed": [path for _kind, path in window.recent_files.entries()]}))
box.close()
window.close()
"""


@pytest.mark.gui
def test_a_named_pipe_on_the_recent_files_list_is_said_to_be_one_and_stays_listed(tmp_path):
    """A scene and a lesson on File → Open recent that became named pipes: they are there, so not
    "no longer there" (it said so, and took them off the list); the loaders' dialogs say what they
    are, without reading them."""
    scene, lesson = tmp_path / "scene.json", tmp_path / "lesson.json"
    os.mkfifo(scene)
    os.mkfifo(lesson)
    out = subprocess.run([sys.executable, "-c", RECENT_DRIVER, str(scene), str(lesson)], cwd=ROOT,
                         capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-3000:]
    result = json.loads(out.stdout.strip().splitlines()[-1])
    assert result["opened"] is False and result["kept"] is True
    assert len(result["messages"]) == 1 and "scene.json" in result["messages"][0]
    assert "not a regular file" in result["messages"][0]
    assert "lesson.json" in result["lesson"] and "not a regular file" in result["lesson"]
    assert result["listed"] == [str(lesson), str(scene)]
