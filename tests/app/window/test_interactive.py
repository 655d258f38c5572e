"""Moving the observer as a user does: bursts of changes, dragging in 3D, walking with keys.

What is checked is what the user would see, never how long it took: the
frustum and the image belong to the last camera, a superseded camera's full
image never appears, and the mouse and keys move the observer as documented.
"""

from dataclasses import replace

import numpy as np
import pytest
from PySide6.QtCore import QPoint, QPointF, Qt, QTimer
from PySide6.QtGui import QWheelEvent
from PySide6.QtWidgets import QApplication
from qt_fixtures import keys_listed
from window_helpers import RENDER_TIMEOUT_MS, open_scene_file

from app.window.window_layout import in_front
from core import presets, shapes
from core.files import scene_file
from core.image_order.ray_tracing import render_trace
from views.panels.pane_cover import covered_with
from views.scene3d.observer_keys import WALK_FRACTION
from views.scene3d.scene_view import FOV_STEP_DEG


def _wait_full(qtbot, win, name=None):
    name = name or win.current.title
    qtbot.waitUntil(lambda: win.showing_full(name), timeout=RENDER_TIMEOUT_MS)


def _burst(win, n=50):
    """n camera changes in a row, as fast as the model takes them; returns the last camera."""
    start = win.model.camera
    for i in range(1, n + 1):
        win.model.set_camera(start.orbit(start.yaw_deg + 2.0 * i, start.pitch_deg + 0.3 * i))
    return win.model.camera


def _record_full_results(win, tab):
    """Note, for every full result the tab shows, its job's camera and the model's camera then."""
    cameras_of, shown = {}, []
    job, show = tab.job, tab.show

    def tagged_job(scene, preview):
        run = job(scene, preview)

        def tagged(cancelled, progress):
            result = run(cancelled, progress)
            if result is not None and not preview:
                cameras_of[id(result)] = scene.camera
            return result

        return tagged

    def recording_show(result):
        if id(result) in cameras_of:
            shown.append((cameras_of[id(result)], win.model.camera))
        return show(result)

    tab.job, tab.show = tagged_job, recording_show
    return shown


def test_after_a_burst_the_frustum_and_image_are_the_last_cameras(qtbot, window):
    tab = window.tab("image order")
    shown = _record_full_results(window, tab)
    drawn = []  # the frustum each draw of the 3D pane showed
    frustum = window.scene_view.frustum
    window.scene_view.plotter.ren_win.AddObserver("EndEvent", lambda *_: drawn.append(frustum.points.copy()))
    last = _burst(window)
    assert np.allclose(frustum.points, last.frustum_corners())
    qtbot.waitUntil(lambda: len(drawn) >= 1)
    # Fifty changes and the pane drew none of the 49 superseded cameras: a draw per change would
    # have shown the first of them.
    assert all(np.allclose(points, last.frustum_corners()) for points in drawn)
    _wait_full(qtbot, window)
    expected = render_trace(window.model.scene, window.model.trace_settings).color
    assert np.allclose(tab.widget.image.rgb, expected)
    assert tab.widget.image.note == ""  # the full image, not a preview
    assert shown and all(job_camera == model_camera for job_camera, model_camera in shown)


def test_moving_shows_previews_marked_as_such_then_the_full_image(qtbot, window):
    tab = window.tab("image order")
    seen = []
    window.image_shown.connect(lambda title, preview: seen.append(
        (preview, tab.widget.image.note, window.progress.format(), window.status_caption.text())))
    cam = window.model.camera
    window.model.set_camera(cam.orbit(cam.yaw_deg + 10, cam.pitch_deg))
    _wait_full(qtbot, window)
    assert [preview for preview, *_ in seen] == [True, False]
    _, note, progress, caption = seen[0]
    assert note == "preview" and "preview" in progress and "preview" in caption and " ms" in caption
    _, note, progress, caption = seen[1]
    assert note == "" and progress == "Image order: done" and " ms" in caption


def test_no_superseded_full_image_is_shown_on_the_object_order_tab(qtbot, window):
    window.show_tab("object order")
    _wait_full(qtbot, window, "object order")
    tab = window.tab("object order")
    shown = _record_full_results(window, tab)
    for _ in range(3):
        _burst(window, 20)
        qtbot.wait(1)  # let some previews and renders start between bursts
    _wait_full(qtbot, window, "object order")
    assert shown and all(job_camera == model_camera for job_camera, model_camera in shown)
    assert tab.widget.result.history.near == window.model.camera.near


def _drag(qtbot, widget, start: QPointF, end: QPointF):
    qtbot.mousePress(widget, Qt.MouseButton.LeftButton, pos=start.toPoint())
    middle = (start + end) / 2
    qtbot.mouseMove(widget, pos=middle.toPoint())
    qtbot.mouseMove(widget, pos=end.toPoint())
    qtbot.mouseRelease(widget, Qt.MouseButton.LeftButton, pos=end.toPoint())


def test_dragging_the_camera_glyph_moves_the_eye_and_keeps_the_target(qtbot, window):
    view = window.scene_view
    before = window.model.camera
    start = view.widget_pos(before.eye)
    end = start + QPointF(40, -25)
    _drag(qtbot, view.plotter, start, end)
    cam = window.model.camera
    assert cam.target == before.target
    assert not np.allclose(cam.eye, before.eye)
    # The eye moved in the plane through it that faces the overview camera ...
    direction = np.asarray(view.plotter.camera.direction)
    assert np.dot(np.subtract(cam.eye, before.eye), direction) == pytest.approx(0.0, abs=1e-6)
    # ... to the point under the mouse, and the frustum followed.
    landed = view.widget_pos(cam.eye)
    assert abs(landed.x() - end.x()) <= 1.5 and abs(landed.y() - end.y()) <= 1.5
    assert np.allclose(view.frustum.points, cam.frustum_corners())


def test_dragging_the_target_turns_the_observer_and_keeps_the_eye(qtbot, window):
    view = window.scene_view
    before = window.model.camera
    start = view.widget_pos(before.target)
    _drag(qtbot, view.plotter, start, start + QPointF(-30, 0))
    cam = window.model.camera
    assert cam.eye == before.eye and not np.allclose(cam.target, before.target)


def test_dragging_away_from_the_glyph_leaves_the_observer(qtbot, window):
    view = window.scene_view
    before = window.model.camera
    corner = QPointF(8, view.plotter.height() - 8)
    _drag(qtbot, view.plotter, corner, corner + QPointF(30, -30))
    assert window.model.camera == before


def test_scrolling_over_the_glyph_narrows_the_viewing_angle(qtbot, window):
    view = window.scene_view
    before = window.model.camera.fov_y_deg
    pos = view.widget_pos(window.model.camera.eye)
    event = QWheelEvent(pos, view.plotter.mapToGlobal(pos), QPoint(), QPoint(0, 120),
                        Qt.MouseButton.NoButton, Qt.KeyboardModifier.NoModifier,
                        Qt.ScrollPhase.NoScrollPhase, False)
    QApplication.sendEvent(view.plotter, event)
    assert window.model.camera.fov_y_deg == pytest.approx(before - FOV_STEP_DEG)


@pytest.mark.parametrize("key, forward, right, up", [
    (Qt.Key.Key_W, 1, 0, 0), (Qt.Key.Key_S, -1, 0, 0), (Qt.Key.Key_A, 0, -1, 0),
    (Qt.Key.Key_D, 0, 1, 0), (Qt.Key.Key_Q, 0, 0, -1), (Qt.Key.Key_E, 0, 0, 1)])
def test_walk_keys_move_eye_and_target_by_a_tenth_of_the_distance(qtbot, window, key, forward, right,
                                                                   up):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    before = window.model.camera
    qtbot.keyClick(window, key)
    cam = window.model.camera
    moved = np.subtract(cam.eye, before.eye)
    assert np.allclose(np.subtract(cam.target, before.target), moved)  # the view direction is kept
    view = np.subtract(before.target, before.eye)
    ahead = view / np.linalg.norm(view)
    side = np.array([-ahead[2], 0.0, ahead[0]]) / np.hypot(ahead[0], ahead[2])  # ahead x (0, 1, 0)
    expected = WALK_FRACTION * np.linalg.norm(view) * (forward * ahead + right * side
                                                       + up * np.array([0.0, 1.0, 0.0]))
    assert np.allclose(moved, expected)
    assert WALK_FRACTION == 0.1  # the step the Help → Keys text and the docs promise


def test_a_focused_number_box_takes_the_arrow_keys(qtbot, window):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    window.controls_dock.raise_()  # its fields take the keyboard only in front
    qtbot.waitUntil(lambda: in_front(window.controls_dock))
    box = window.camera_panel.near
    box.setFocus()
    qtbot.waitUntil(box.hasFocus)
    before = window.model.camera
    qtbot.keyClick(box, Qt.Key.Key_Up)
    cam = window.model.camera
    assert cam.near == pytest.approx(before.near + box.singleStep())
    assert cam.eye == before.eye  # the observer did not orbit


def test_tab_never_walks_into_a_dock_covered_by_another_tab(qtbot, window):
    """Qt keeps a dock tabbed behind another "visible", only moved off screen: Tab walked from the
    scene editor into the Controls, Lessons and Exercises behind it, and an arrow key there moved the
    observer unseen."""
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    window.editor.dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.editor.dock))
    covered = [window.controls_dock, window.lesson_dock, window.exercise_dock]
    assert not any(in_front(dock) for dock in covered)
    window.editor.panel.tree.setFocus()
    qtbot.waitUntil(window.editor.panel.tree.hasFocus)
    reached = []
    for _ in range(80):  # round the window's whole focus chain
        qtbot.keyClick(QApplication.focusWidget(), Qt.Key.Key_Tab)
        reached.append(QApplication.focusWidget())
    assert window.editor.panel.tree in reached  # round and back
    assert not [w for w in reached if any(dock.isAncestorOf(w) for dock in covered)]
    window.controls_dock.raise_()  # in front again, its fields take the keyboard
    qtbot.waitUntil(lambda: in_front(window.controls_dock))
    box = window.camera_panel.eye[0]
    box.setFocus()
    qtbot.waitUntil(box.hasFocus)


def test_eye_boxes_take_the_whole_range_a_scene_file_allows(qtbot, window):
    box = window.camera_panel.eye[0]
    box.setValue(10_000.0)
    assert window.model.camera.eye[0] == 10_000.0
    window.camera_panel.eye[1].setValue(3.5)  # editing another box keeps the first one's value
    assert window.model.camera.eye[0] == 10_000.0


def test_help_lists_every_key(window):
    text = keys_listed(window)
    for key in ("W", "A", "S", "D", "Q", "E", "Left", "Right", "Up", "Down", "P", "F5", "Esc"):
        assert f"  {key} " in text, key
    assert "Drag the camera glyph" in text
    for keys in ("Ctrl+Shift+Z or Ctrl+Y ", ". or B ", "Ctrl++ or Ctrl+= "):  # every key of an entry
        assert keys in text, keys


def test_ctrl_y_redoes_and_ctrl_equals_enlarges_the_text_as_in_other_programs(qtbot, window):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    window.editor.add_light()
    try:
        window.editor.undo_action.trigger()
        lights = len(window.model.scene.lights)
        qtbot.keyClick(window, Qt.Key.Key_Y, Qt.KeyboardModifier.ControlModifier)
        assert len(window.model.scene.lights) == lights + 1
    finally:
        window.editor.stack.setClean()  # closing asks nothing
    size = QApplication.font().pointSizeF()
    try:
        qtbot.keyClick(window, Qt.Key.Key_Equal, Qt.KeyboardModifier.ControlModifier)
        assert QApplication.font().pointSizeF() == pytest.approx(1.25 * size, rel=0.05)
    finally:
        window.scale_text(0.8)


def test_a_tab_shown_again_shows_its_own_progress_and_status(qtbot, window):
    window.show_tab("four views")
    _wait_full(qtbot, window, "four views")
    assert window.progress.format() == "Four views: done"
    window.show_tab("image order")
    assert window.progress.format() == "Image order: done"
    assert "rays" in window.status_caption.text()


def test_a_failed_render_resets_the_progress_and_says_why(qtbot, window):
    tab = window.tab("compare")

    def broken(scene, preview):
        def run(cancelled, progress):
            raise MemoryError("the image does not fit")
        return run

    tab.job = broken
    window.show_tab("compare")
    qtbot.waitUntil(lambda: "failed" in window.progress.format(), timeout=RENDER_TIMEOUT_MS)
    assert window.progress.value() == 0
    assert "the image does not fit" in window.status_caption.text()
    assert "the image does not fit" in covered_with(tab.widget)  # the tab's old pictures are marked stale


def test_opening_a_smaller_scene_after_picking_a_buffer_pixel_clears_the_pick(qtbot, window, tmp_path):
    window.show_tab("object order")
    _wait_full(qtbot, window, "object order")
    panel = window.tab("object order").widget
    qtbot.mouseClick(panel.image, Qt.MouseButton.LeftButton, pos=panel.image.widget_pos(300, 220).toPoint())
    picked = window.model.buffer_pixel
    assert picked is not None and picked[0] >= 160 and panel.history.rowCount() > 0
    small = presets.culling_pyramid()
    small = replace(small, camera=small.camera.replace(width=160, height=120))
    path = tmp_path / "small.json"
    scene_file.save(small, path)
    assert open_scene_file(qtbot, window, path)
    assert window.model.buffer_pixel is None and panel.history.rowCount() == 0
    _wait_full(qtbot, window, "object order")
    assert panel.image.rgb.shape == (120, 160, 3) and panel.picked is None
    assert window.progress.format() == "Object order: done"


def test_a_minutes_long_unaccelerated_render_is_announced_and_does_not_block_previews(qtbot, window):
    scene = window.model.scene
    heavy = replace(scene, objects=(shapes.uv_sphere((0.0, 0.8, 0.0), 1.5, 200, 200),),
                    camera=scene.camera.replace(width=160, height=120))  # 80,000 triangles
    window.model.set_scene(heavy)
    panel = window.tab("image order").widget
    panel.accel.setCurrentIndex(panel.accel.findData("none"))
    assert "may take minutes" in window.status_caption.text()
    previews = []
    window.image_shown.connect(lambda title, preview: previews.append(preview))
    start = window.model.camera
    mover = QTimer()
    mover.timeout.connect(lambda: window.model.set_camera(  # the observer keeps moving
        start.orbit(window.model.camera.yaw_deg + 1, start.pitch_deg)))
    mover.start(40)
    qtbot.waitUntil(lambda: True in previews, timeout=60_000)
    mover.stop()
    window.cancel_render()


def test_only_the_visible_tab_renders_while_the_observer_moves(qtbot, window):
    started = {title: 0 for title in window.tab_titles()}
    for tab in window.tabs:
        def counting(scene, preview, job=tab.job, title=tab.title):
            started[title] += 1
            return job(scene, preview)
        tab.job = counting
    _burst(window, 30)
    _wait_full(qtbot, window)
    assert started["Image order"] >= 1
    assert {t: n for t, n in started.items() if t != "Image order"} == {
        "Object order": 0, "Four views": 0, "Compare": 0, "Hard cases": 0, "Cost": 0}
    window.show_tab("compare")  # a hidden tab renders once it is shown
    _wait_full(qtbot, window, "compare")
    assert started["Compare"] == 1


def test_the_object_order_step_lives_in_the_model(qtbot, window):
    window.show_tab("object order")
    _wait_full(qtbot, window, "object order")
    panel = window.tab("object order").widget
    assert window.model.step is None and panel.scrubber.step == panel.result.history.n_steps
    panel.scrubber.set_step(3)
    assert window.model.step == 3
    window.model.set_step(5)
    assert panel.scrubber.step == 5
    qtbot.waitUntil(lambda: "Step 5" in panel.step_caption.text())
    window.model.set_raster_settings(replace(window.model.raster_settings, back_face_culling=False))
    assert not panel.switches["back_face_culling"].isChecked()  # the switch shows the model
    _wait_full(qtbot, window, "object order")
    assert panel.scrubber.step == 5  # the chosen step is kept across renders


def test_the_frustum_shows_its_edges_while_moving_and_its_faces_once_at_rest(qtbot, window):
    view = window.scene_view
    faces = view.plotter.renderer.actors["frustum"]
    edges = view.plotter.renderer.actors["frustum-edges"]
    _burst(window, 5)
    assert edges.GetVisibility() and not faces.GetVisibility()
    qtbot.waitUntil(lambda: faces.GetVisibility(), timeout=5000)
    assert view.plotter.renderer.GetUseFXAA()


def test_tabs_that_work_in_their_panel_say_how_to_start_in_the_progress_bar(window):
    window.show_tab("cost")
    assert "press Run" in window.progress.format() and window.progress.value() == 0
    window.show_tab("hard cases")
    assert window.progress.format().startswith("Hard cases: pick a case")
