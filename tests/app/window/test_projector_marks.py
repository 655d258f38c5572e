"""The perspective and orthographic lessons draw A, its projection A′ on the screen and the projector."""

import re

import numpy as np
import pytest
from window_helpers import RENDER_TIMEOUT_MS

from core.lessons.lesson_file import shipped_lessons
from views.scene3d.projector_lines import PROJECTOR_OVERLAY

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def _marks(window):
    """The drawn projector's points (A, A′, its far end), and the labels' texts."""
    parts = window.scene_view.overlay_parts(PROJECTOR_OVERLAY)
    line = next(p for p in parts if p.n_lines)
    labels = next(p for p in parts if "labels" in p.point_data)
    return line.points, [str(s) for s in labels.point_data["labels"]]


def _basis(cam):
    """The observer's right, up and forward, from eye, target and up by hand (numpy)."""
    forward = np.subtract(cam.target, cam.eye) / np.linalg.norm(np.subtract(cam.target, cam.eye))
    right = np.cross(forward, cam.up) / np.linalg.norm(np.cross(forward, cam.up))
    return right, np.cross(right, forward), forward


def _pixel_by_hand(cam, point):
    """The pixel of a point on the near plane: its offset across the screen over the screen's half size."""
    right, up, _ = _basis(cam)
    half_h = cam.ortho_height / 2 if cam.projection == "orthographic" else \
        cam.near * np.tan(np.radians(cam.fov_y_deg) / 2)
    offset = np.subtract(point, cam.eye)
    x_n, y_n = offset @ right / (half_h * cam.width / cam.height), offset @ up / half_h
    return np.array([(x_n + 1) / 2 * cam.width, (1 - y_n) / 2 * cam.height])


def _shown_pixel(window):
    """The pixel the object-order pane's vertex path shows for the highlighted corner."""
    text = window.tab("object order").widget.vertex_math.value("pixel")
    return np.array([float(v) for v in re.findall(r"= (-?[\d.e+-]+)(?:,|\$)", text)])


@pytest.mark.parametrize("lesson", ["perspective", "orthographic"])
def test_the_lesson_marks_a_corner_its_projection_on_the_screen_and_the_projector(qtbot, window, lesson):
    window.lesson_panel.select(LESSONS[lesson], 0)
    cam = window.model.camera
    cube = next(o for o in window.model.scene.objects if o.name == "cube")
    a = cube.vertices[6]
    (drawn_a, image, source), labels = _marks(window)
    assert labels == ["A", "A′"]
    assert np.allclose(drawn_a, a)
    _, _, forward = _basis(cam)
    depth = (a - cam.eye) @ forward
    assert np.isclose((image - cam.eye) @ forward, cam.near)  # on the screen
    if lesson == "perspective":  # on the line from A to the eye, which the projector reaches
        assert np.allclose(image, cam.eye + (a - cam.eye) * cam.near / depth)
        assert np.allclose(source, cam.eye)
    else:  # straight along the viewing direction
        assert np.allclose(image, a - (depth - cam.near) * forward)
        assert np.allclose(source, image)
    assert np.allclose(_pixel_by_hand(cam, image), _shown_pixel(window), atol=1e-3)  # 6 digits shown


def test_the_label_font_draws_the_prime_of_a_prime(qtbot, window):
    # VTK's own Arial has no glyph for ′ and drew "A′" as a bare "A"; the pane's font has one.
    from vtkmodules.vtkRenderingCore import vtkTextRenderer

    window.lesson_panel.select(LESSONS["perspective"], 0)
    qtbot.waitUntil(lambda: window.scene_view.view is not None, timeout=RENDER_TIMEOUT_MS)  # VTK loaded
    qtbot.waitUntil(lambda: PROJECTOR_OVERLAY in window.scene_view.view._overlays)  # drawn a turn later
    (actor,) = [actor for _, actor, style in window.scene_view.view._overlays[PROJECTOR_OVERLAY]
                if "label_size" in style]
    text = actor.GetMapper().GetLabelTextProperty()
    widths = {}
    for label in ("A", "A′"):
        box = [0, 0, 0, 0]
        vtkTextRenderer().GetBoundingBox(text, label, box, 72)
        widths[label] = box[1] - box[0]
    assert widths["A′"] >= widths["A"] + 2


def test_the_marks_follow_the_observer_and_leave_with_the_lesson_step(qtbot, window):
    window.lesson_panel.select(LESSONS["perspective"], 0)
    a = next(o for o in window.model.scene.objects if o.name == "cube").vertices[6]
    window.model.update_camera(eye=(7.0, 6.0, 5.0))  # as a drag of the eye in the 3D pane does
    cam = window.model.camera
    _, image, source = _marks(window)[0]
    _, _, forward = _basis(cam)
    assert np.allclose(source, (7.0, 6.0, 5.0))
    assert np.allclose(image, cam.eye + (a - cam.eye) * cam.near / ((a - cam.eye) @ forward))
    # The object-order pane works the corner's path again once it has drawn the moved camera's image.
    qtbot.waitUntil(lambda: np.allclose(_pixel_by_hand(cam, image), _shown_pixel(window), atol=1e-3),
                    timeout=RENDER_TIMEOUT_MS)
    window.show_tab("image order")  # the marks stay with the frustum on every tab
    assert PROJECTOR_OVERLAY in window.scene_view.overlay_names()
    window.model.set_overlay("frustum", False)  # no screen shown: no projection onto it
    assert PROJECTOR_OVERLAY not in window.scene_view.overlay_names()
    window.model.set_overlay("frustum", True)
    assert PROJECTOR_OVERLAY in window.scene_view.overlay_names()
    window.lesson_panel.select(LESSONS["zbuffer"], 0)  # a step that highlights no corner
    assert PROJECTOR_OVERLAY not in window.scene_view.overlay_names()
