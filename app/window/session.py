"""The last session, kept for the next start: the scene and the observer, in the user's settings.

When the app ends (its window closed), :func:`remember` stores the scene (as the text of a
scene file, or only its file's path when that text would be very long) and the
observer (the camera) in the user's settings (:mod:`views.user_settings`).  Edits the user
chose to discard are not stored: the scene kept is the one last saved (or
opened).  At the next start without a scene file on the command line,
:func:`restore` loads them back through the scene file's loader, so stored
settings that no longer load (a mesh file moved away, a hand-edited file) are
reported in the status bar and the window keeps the lecture scene.
"""

from __future__ import annotations

import json
from dataclasses import replace
from pathlib import Path

from app.window.undo_commands import scene_at
from core.files import scene_file
from core.files.mesh_files import read_mesh
from views.user_settings import user_settings

MAX_SCENE_CHARS = 2_000_000
"""A longer scene text (large inline meshes) is not stored; its file's path is, if it has one."""
SCENE, SCENE_PATH, OBSERVER = KEYS = ("session/scene", "session/scene_path", "session/observer")


def remember(window) -> None:
    """Store the scene ``window`` shows (as last saved or opened) and its observer."""
    editor, model = window.editor, window.model
    path = window.scene_path
    scene = scene_at(editor.stack, editor.stack.cleanIndex(), model.scene)
    text = "" if scene is None else json.dumps(scene_file.to_dict(scene, path.parent if path else None))
    store = user_settings()
    store.setValue(SCENE, text if len(text) <= MAX_SCENE_CHARS else "")
    store.setValue(SCENE_PATH, str(path) if path is not None else "")  # the file holds the saved scene
    store.setValue(OBSERVER, json.dumps(scene_file.to_dict(model.scene)["camera"]))
    store.sync()


def restore(window) -> bool:
    """Show the stored scene and observer in ``window``; returns whether there was one to show."""
    store = user_settings()
    text, path, observer = (str(store.value(key, "") or "") for key in KEYS)
    if not (text or path or observer):
        return False
    path = Path(path) if path else None
    try:
        if text:
            scene = scene_file.from_dict(json.loads(text), path.parent if path else None, read_mesh)
        elif path is not None:
            scene = scene_file.load(path, read_mesh=read_mesh)
        else:
            scene = window.model.scene
        if observer:
            scene = replace(scene, camera=scene_file.from_dict({"camera": json.loads(observer)}).camera)
    except ValueError as exc:  # a SceneFileError, or json's error
        window.statusBar().showMessage(f"The last session could not be restored, so the lecture scene is "
                                       f"shown: {exc} (in {store.fileName()})", 15000)
        return False
    window.scene_path = path
    window.setWindowTitle(f"Render Explorer — {path.name if path else 'last session'}")
    window.model.set_scene(scene)
    return True
