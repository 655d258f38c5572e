"""The 3D pane for a lecture hall: the frustum's planes labelled, lines that grow with the text."""

import numpy as np
from window_helpers import RENDER_TIMEOUT_MS

from core.lessons.lesson_file import shipped_lessons
from views.panels.raytree_view import ray_tree_parts
from views.scene3d.scene_view import ENCLOSING_OPACITY

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def _actor(window, name):
    return window.scene_view.plotter.renderer.actors[name]


def _labels(window) -> list[str]:
    return [str(s) for p in window.scene_view.overlay_parts("frustum") if "labels" in p.point_data
            for s in p.point_data["labels"]]


def test_the_frustum_lesson_fills_and_labels_the_near_and_far_planes(qtbot, window):
    window.lesson_panel.select(LESSONS["frustum"], 0)
    cam = window.model.camera
    assert "frustum" in window.scene_view.overlay_names()
    assert _labels(window) == [f"near plane (the screen), n = {cam.near:g}", f"far plane, f = {cam.far:g}"]
    planes = [p for p in window.scene_view.overlay_parts("frustum") if p.n_faces == 1]
    depths = sorted(float(np.mean((p.points - cam.eye) @ cam.forward)) for p in planes)
    assert np.allclose(depths, [cam.near, cam.far])  # one quad on each plane, at its distance from the eye
    window.model.update_camera(far=9.0)  # the overlay follows the observer
    assert _labels(window)[1] == "far plane, f = 9"
    window.lesson_panel.select(LESSONS["zbuffer"], 0)  # a lesson without the overlay
    assert "frustum" not in window.scene_view.overlay_names()
    assert not window.camera_panel.frustum_labels.isChecked()
    window.camera_panel.frustum_labels.setChecked(True)  # the user's own switch
    assert "frustum" in window.scene_view.overlay_names()


def test_presentation_scale_widens_the_3d_lines_points_labels_and_axes(qtbot, window):
    window.model.set_overlay("frustum", True)
    edges, label = _actor(window, "frustum-edges"), _actor(window, "frustum:3")
    width, size = edges.prop.line_width, label.GetMapper().GetLabelTextProperty().GetFontSize()
    axes = window.scene_view.plotter.renderer.axes_widget.GetViewport()
    shafts = window.scene_view.plotter.renderer.axes_actor.GetXAxisShaftProperty()
    assert shafts.GetLineWidth() == 3  # the marker's axes are 3 px wide at x1
    window.presentation.set_scale(2.0)
    assert window.scene_view.plotter.renderer.axes_actor.GetXAxisShaftProperty().GetLineWidth() == 6
    assert edges.prop.line_width == 2 * width
    # The labels grow less than the rest (the pane does not grow): 13 pt x sqrt(2) = 18.4, drawn at 18 pt.
    assert (size, label.GetMapper().GetLabelTextProperty().GetFontSize()) == (13, 18)
    wider = window.scene_view.plotter.renderer.axes_widget.GetViewport()
    assert wider[2] - wider[0] == 2 * (axes[2] - axes[0])  # the axes' letters grow with their marker
    cam = window.model.camera
    with qtbot.waitSignal(window._tree_renderer.finished, timeout=RENDER_TIMEOUT_MS):
        window.pick_ray_tree(cam.width // 2, cam.height // 2)  # drawn after the change: scaled too
    styles = [style for _, style in ray_tree_parts(window.ray_tree[2], 1.0)]
    assert styles
    for i, style in enumerate(styles):  # pyvista's defaults: lines 1 px wide, points 5 px
        prop = _actor(window, f"ray-tree:{i}").prop
        assert prop.line_width == 2 * style.get("line_width", 1)
        assert prop.point_size == 2 * style.get("point_size", 5)
    window.presentation.set_scale(1.0)
    assert edges.prop.line_width == width


def test_the_sphere_the_exercise_starts_inside_is_drawn_see_through(qtbot, window):
    window.lesson_panel.select(LESSONS["ray_sphere"], 1)
    sphere = next(o for o in window.model.scene.objects if o.name == "exercise sphere")
    assert np.linalg.norm(np.subtract(window.model.camera.eye, sphere.center)) < sphere.radius
    assert _actor(window, f"object:{id(sphere)}").prop.opacity == ENCLOSING_OPACITY
    window.reset_scene()  # the lecture scene: the observer outside every object
    for obj in window.model.scene.objects:
        assert _actor(window, f"object:{id(obj)}").prop.opacity == obj.material.opacity
