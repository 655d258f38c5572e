"""The scene model: one signal per change, only for real changes, never an unusable camera."""

from dataclasses import replace

from app.window.state import SceneModel
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


def test_a_new_scene_clears_the_picks_and_the_step(qtbot):
    model = SceneModel(presets.lecture_scene())
    model.set_ray_pixel((10, 20))
    model.set_buffer_pixel((300, 200))
    model.set_step(4)
    cleared = []
    model.buffer_pixel_changed.connect(cleared.append)
    model.set_scene(presets.culling_pyramid())
    assert (model.ray_pixel, model.buffer_pixel, model.step) == (None, None, None)
    assert cleared == [None]


def test_a_smaller_image_drops_a_pick_that_falls_outside_it(qtbot):
    model = SceneModel(presets.lecture_scene())
    model.set_buffer_pixel((300, 200))  # inside 320 x 240
    model.set_ray_pixel((10, 10))
    model.update_camera(width=160, height=120)
    assert model.buffer_pixel is None  # (300, 200) is outside 160 x 120
    assert model.ray_pixel == (10, 10)
    model.set_ray_pixel((160, 5))  # one past the last column: no pick
    assert model.ray_pixel is None


def test_settings_and_overlays_signal_only_real_changes(qtbot):
    model = SceneModel(presets.lecture_scene())
    traces, overlays = [], []
    model.trace_settings_changed.connect(traces.append)
    model.overlays_changed.connect(overlays.append)
    model.set_trace_settings(replace(model.trace_settings))  # equal: nothing
    model.set_trace_settings(replace(model.trace_settings, accel="grid"))
    model.set_overlay("grid", True)
    model.set_overlay("grid", True)
    model.set_overlay("spheres", True)
    model.set_overlay("grid", False)
    assert [s.accel for s in traces] == ["grid"]
    assert overlays == [{"grid"}, {"grid", "spheres"}, {"spheres"}]


def test_a_refused_camera_says_which_field_is_wrong(qtbot):
    model = SceneModel(presets.lecture_scene())
    with qtbot.waitSignal(model.camera_refused) as blocker:
        assert not model.update_camera(near=model.camera.far + 1)
    assert blocker.args[0].startswith("far: must be > near")
