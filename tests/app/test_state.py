"""The scene model: one signal per change, only for real changes, never an unusable camera."""

from dataclasses import replace

from app.state import SceneModel
from core import presets


def test_camera_signal_fires_once_per_real_change(qtbot):
    model = SceneModel(presets.lecture_scene())
    seen = []
    model.camera_changed.connect(seen.append)
    assert not model.update_camera(fov_y_deg=model.camera.fov_y_deg)  # same value: no signal
    assert model.update_camera(fov_y_deg=55.0)
    assert [c.fov_y_deg for c in seen] == [55.0]
    assert model.scene.camera.fov_y_deg == 55.0


def test_unusable_camera_is_refused(qtbot):
    model = SceneModel(presets.lecture_scene())
    before = model.camera
    seen = []
    model.camera_changed.connect(seen.append)
    assert not model.update_camera(near=before.far + 1)
    assert not model.update_camera(eye=before.target)
    assert model.camera == before and seen == []


def test_new_scene_fires_scene_changed_only(qtbot):
    model = SceneModel(presets.lecture_scene())
    scenes, cameras = [], []
    model.scene_changed.connect(scenes.append)
    model.camera_changed.connect(cameras.append)
    other = presets.culling_pyramid()
    model.set_scene(other)
    model.set_scene(replace(other))  # equal: nothing happens
    assert scenes == [other] and cameras == []
    assert model.camera == other.camera
