"""The back-face step highlights what its words name: the 3D pane outlines the pyramid's back face
with its normal labelled "N: back face"; the object-order image, which never draws that face, singles
out no other polygon (no outline, no edges of the last polygon drawn, nothing in the 3D pane for it)."""

import numpy as np
from PySide6.QtGui import QAction, QKeySequence
from window_helpers import RENDER_TIMEOUT_MS

from app.lessons.runner import FACE_SIDE_OVERLAY
from core.lessons.lesson_file import shipped_lessons

LESSONS = shipped_lessons()


def test_the_back_face_step_outlines_the_back_face_and_no_front_face(window, qtbot):
    k = next(i for i, lesson in enumerate(LESSONS) if lesson.id == "back_faces")
    step = LESSONS[k].steps[0]
    assert step.highlight["face"] == {"object": "pyramid", "triangle": 2}
    window.lesson_panel.select(k, 0)
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: window.showing_full("object order") and panel.scene == step.scene,
                    timeout=RENDER_TIMEOUT_MS)
    assert window.model.step is None  # the whole picture
    for image in (panel.image, panel.depth.image):
        assert image._highlight is None
    assert panel.image.edges is None
    assert window.scene_view.overlay_parts("polygon") == []
    # The lesson's overlay: the back face's outline (its three corners among the points drawn) and
    # its normal's label.
    pyramid = step.scene.objects[0]
    corners = pyramid.vertices[pyramid.triangles[2]]
    points = np.vstack([np.asarray(poly.points) for poly in window.scene_view.overlay_parts("lesson")])
    assert all(np.isclose(points, c).all(axis=1).any() for c in corners)
    assert window.lessons.highlighted == "triangle 2 of 'pyramid'"


def test_leaving_the_step_for_another_scene_takes_its_marks_away(window, qtbot):
    """Ctrl+L (the lecture scene) after the back-face step: the pyramid is gone, and so are the outline
    of its back face, the normal's label and the status line's "Look at ..."."""
    k = next(i for i, lesson in enumerate(LESSONS) if lesson.id == "back_faces")
    window.lesson_panel.select(k, 0)
    qtbot.waitUntil(lambda: window.showing_full("object order")
                    and window.scene_view.overlay_parts("lesson") != [], timeout=RENDER_TIMEOUT_MS)
    ctrl_l = next(a for a in window.findChildren(QAction) if a.shortcut() == QKeySequence("Ctrl+L"))
    ctrl_l.trigger()  # File → Lecture scene
    qtbot.waitUntil(lambda: "pyramid" not in [obj.name for obj in window.model.scene.objects])
    assert window.scene_view.overlay_parts("lesson") == []
    assert window.scene_view.overlay_parts(FACE_SIDE_OVERLAY) == []
    assert window.lessons.highlighted == ""
    assert "Look at" not in window.statusBar().currentMessage()
    assert "Press Next (PageDown) to show this step again" in window.lesson_panel.text.text()
