"""The one place the current scene lives, with a signal per part that changes.

Views and panels receive this model, read from it and write to it through
:meth:`SceneModel.set_camera` / :meth:`SceneModel.set_scene`; they never keep a
copy of their own.  A signal fires only when the value really changed.
"""

from __future__ import annotations

from dataclasses import replace

from PySide6.QtCore import QObject, Signal

from core.camera import Camera, camera_problems
from core.scene import Scene


class SceneModel(QObject):
    """The current :class:`core.scene.Scene`, observable.

    Signals
    -------
    camera_changed(Camera) : the observer moved or its lens changed.
    scene_changed(Scene) : a new scene (objects, lights, background and its own camera);
        listeners of the camera read it from the scene: ``camera_changed`` does not fire too.
    """

    camera_changed = Signal(object)
    scene_changed = Signal(object)

    def __init__(self, scene: Scene, parent: QObject | None = None):
        super().__init__(parent)
        self._scene = scene

    @property
    def scene(self) -> Scene:
        return self._scene

    @property
    def camera(self) -> Camera:
        return self._scene.camera

    def set_camera(self, camera: Camera) -> bool:
        """Use ``camera`` if it is valid and different; return whether it was taken."""
        if camera == self._scene.camera or camera_problems(camera):
            return False
        self._scene = replace(self._scene, camera=camera)
        self.camera_changed.emit(camera)
        return True

    def update_camera(self, **changes) -> bool:
        """Change some camera fields (see :meth:`core.camera.Camera.replace`)."""
        return self.set_camera(self.camera.replace(**changes))

    def set_scene(self, scene: Scene) -> None:
        """Replace the whole scene (for example after opening a file)."""
        if scene == self._scene:
            return
        self._scene = scene
        self.scene_changed.emit(scene)
