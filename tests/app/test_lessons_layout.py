"""Lessons as the room sees them: what a step talks about fits the 3D pane, its text fits the panel."""

import numpy as np
import pytest
from PySide6.QtCore import QRect
from PySide6.QtGui import QScreen
from vtkmodules.vtkRenderingCore import vtkTextRenderer
from window_helpers import open_window

from core.lessons import shipped_lessons

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}
FRUSTUM_LESSONS = ("observer", "frustum", "perspective", "orthographic")


def _settled(view) -> bool:
    """The pane's picture has the pane's size and the camera its framing chose."""
    plotter = view.plotter
    ratio = plotter.devicePixelRatioF()
    size = (round(plotter.width() * ratio), round(plotter.height() * ratio))
    return tuple(plotter.ren_win.GetSize()) == size and plotter.camera_position == view._framed_at


def _outside(view) -> list[str]:
    """What of the frustum overlay leaves the pane: corners, or labels (their whole text)."""
    (_, _, edges, labels), pane = view.overlay_parts("frustum"), view.plotter.ren_win.GetSize()
    measure, box = vtkTextRenderer(), [0, 0, 0, 0]
    text = next(actor for poly, actor, _ in view._overlays["frustum"] if poly is labels).GetMapper()
    problems = []
    for point in edges.points:
        p = view.widget_pos(point)
        if not (0 <= p.x() <= pane[0] and 0 <= p.y() <= pane[1]):
            problems.append(f"corner {np.round(point, 2)} at ({p.x():.0f}, {p.y():.0f})")
    for point, label in zip(labels.points, labels.point_data["labels"], strict=True):
        measure.GetBoundingBox(text.GetLabelTextProperty(), str(label), box, view.plotter.ren_win.GetDPI())
        half, tall = (box[1] - box[0]) / 2, box[3] - box[2]  # VTK's own measure of what it draws
        p = view.widget_pos(point)
        if not (half <= p.x() <= pane[0] - half and tall <= p.y() <= pane[1]):
            problems.append(f"label {label!r} anchored at ({p.x():.0f}, {p.y():.0f}) in a pane {pane}")
    return problems


def _check_frustum_lessons(qtbot, window):
    view = window.scene_view.view
    for lesson_id in FRUSTUM_LESSONS:
        lesson = shipped_lessons()[LESSONS[lesson_id]]
        for k, step in enumerate(lesson.steps):
            assert "frustum" in step.overlays
            window.lesson_panel.select(LESSONS[lesson_id], k)
            qtbot.waitUntil(lambda: _settled(view))  # noqa: B023 (waited for at once)
            assert view.plotter.width() > 200 and view.plotter.height() > 150
            assert _outside(view) == [], (lesson_id, k)


@pytest.mark.parametrize("size", [(1280, 720), (1920, 1080)])
def test_frustum_lessons_show_both_planes_and_their_labels_inside_the_3d_pane(qtbot, window, size):
    window.resize(*size)
    qtbot.waitUntil(lambda: window.size().width() == size[0])
    _check_frustum_lessons(qtbot, window)


@pytest.mark.parametrize("scale", [1.5, 2.0])
def test_frustum_lessons_keep_their_labels_inside_the_3d_pane_while_presenting(qtbot, window, scale):
    window.presentation.set_presenting(True)
    window.presentation.set_scale(scale)
    qtbot.waitUntil(lambda: window.scene_view.view.line_scale == scale)
    _check_frustum_lessons(qtbot, window)
    window.presentation.set_presenting(False)


LINES = 10
"""At 1280x720 and text x2 a lesson step shows at least this many lines of its words (or all of them)."""


def _words_shown(panel) -> int:
    return panel.scroll.viewport().height()


def test_at_1280x720_and_text_x2_every_lesson_step_shows_its_words_whole_or_ten_lines(qtbot, monkeypatch):
    screen = QRect(0, 0, 1280, 720)
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: screen)
    monkeypatch.setattr(QScreen, "geometry", lambda self: screen)
    window = open_window(qtbot)
    window.presentation.set_presenting(True)
    window.presentation.set_scale(2.0)
    panel = window.lesson_panel
    line = panel.text.fontMetrics().lineSpacing()
    for row, lesson in enumerate(shipped_lessons()):
        for k, step in enumerate(lesson.steps):
            panel.select(row, k)
            qtbot.waitUntil(lambda: _words_shown(panel) >= LINES * line
                            or panel.scroll.verticalScrollBar().maximum() == 0, timeout=5000)
            if "scene 3D" in step.panes:  # the 3D pane keeps its share all the same
                assert window.scene_pane.height() >= 0.25 * window.centralWidget().height(), (lesson.id, k)
    window.presentation.set_presenting(False)
