"""Lessons as the room sees them: what a step talks about fits the 3D pane, its text fits the panel."""

import itertools

import numpy as np
import pytest
import pyvista as pv
from vtkmodules.vtkRenderingCore import vtkTextRenderer
from window_helpers import RENDER_TIMEOUT_MS, presenting_on_1280x720

from core.lessons.lesson_file import shipped_lessons
from views.panels.image_order_panel import IMAGE_SHARE, TREE_ROWS
from views.panels.raytree_view import RayKindLegend
from views.panels.side_column import SideColumn

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}
FRUSTUM_LESSONS = ("observer", "frustum", "perspective", "orthographic")
WHOLE_FRUSTUM = ("observer", "frustum")
"""The lessons about the frustum itself show all of it; the projection lessons frame their cube."""
CUBE_SHARE = 0.15
"""In the projection lessons the cube is at least this share of the 3D pane's height (once 6-9 %)."""


def _settled(view) -> bool:
    """The pane's picture has the pane's size and the camera its framing chose."""
    plotter = view.plotter
    ratio = plotter.devicePixelRatioF()
    size = (round(plotter.width() * ratio), round(plotter.height() * ratio))
    return tuple(plotter.ren_win.GetSize()) == size and plotter.camera_position == view._framed_at


def _label_boxes(view) -> list[tuple[str, tuple[float, float, float, float]]]:
    """Each frustum label as drawn: its text and its box in widget pixels (x0, y0, x1, y1), y down."""
    view.plotter.render()
    (_, _, _, labels), ratio = view.overlay_parts("frustum"), view.plotter.devicePixelRatioF()
    actor = next(actor for poly, actor, _ in view._overlays["frustum"] if poly is labels)
    mapper, measure, box = actor.GetMapper(), vtkTextRenderer(), [0, 0, 0, 0]
    drawn = pv.wrap(mapper.GetInput())  # what the labels say and where, as VTK's mapper is given it
    assert [s.replace("\n", " ") for s in drawn.point_data["labels"]] == list(labels.point_data["labels"])
    boxes = []
    for k, label in enumerate(drawn.point_data["labels"]):
        measure.GetBoundingBox(mapper.GetLabelTextProperty(), str(label), box, view.plotter.ren_win.GetDPI())
        p = view.widget_pos(drawn.points[k])  # VTK's measure of what it draws, around that point
        boxes.append((str(label), (p.x() + box[0] / ratio, p.y() - box[3] / ratio,
                                   p.x() + box[1] / ratio, p.y() - box[2] / ratio)))
    return boxes


def _outside(view, whole_frustum: bool) -> list[str]:
    """What of the frustum overlay leaves the pane: corners (if it should all show), or labels."""
    edges, pane = view.overlay_parts("frustum")[2], (view.plotter.width(), view.plotter.height())
    problems = []
    for point in edges.points if whole_frustum else ():
        p = view.widget_pos(point)
        if not (0 <= p.x() <= pane[0] and 0 <= p.y() <= pane[1]):
            problems.append(f"corner {np.round(point, 2)} at ({p.x():.0f}, {p.y():.0f})")
    for label, (x0, y0, x1, y1) in _label_boxes(view)[:None if whole_frustum else 1]:  # near plane first
        if not (x0 >= -1 and x1 <= pane[0] + 1 and y0 >= -1 and y1 <= pane[1] + 1):
            problems.append(f"label {label!r} at ({x0:.0f}, {y0:.0f})-({x1:.0f}, {y1:.0f}) in a pane {pane}")
    return problems


def _on_lines(view) -> list[str]:
    """Labels that cover a frustum edge: sampled every pixel along the edges, each as thick as drawn."""
    plotter = view.plotter
    camera = plotter.camera
    eye, ahead = np.array(camera.position), np.array(camera.direction)
    edges = view.overlay_parts("frustum")[2]
    half = next(a for p, a, _ in view._overlays["frustum"] if p is edges).prop.line_width / 2
    half /= plotter.devicePixelRatioF()
    lines = edges.lines.reshape(-1, 3)[:, 1:]
    problems = []
    for label, (x0, y0, x1, y1) in _label_boxes(view):
        for a, b in lines:
            ends = edges.points[[a, b]]
            if np.any((ends - eye) @ ahead <= 0):  # behind the overview camera: not drawn there
                continue
            pa, pb = (view.widget_pos(e) for e in ends)
            t = np.linspace(0, 1, 2 + int(np.hypot(pa.x() - pb.x(), pa.y() - pb.y())))[:, None]
            xy = np.array([pa.x(), pa.y()]) * (1 - t) + np.array([pb.x(), pb.y()]) * t
            xy = xy[(xy[:, 0] >= 0) & (xy[:, 0] <= plotter.width()) & (xy[:, 1] >= 0)
                    & (xy[:, 1] <= plotter.height())]  # what the pane shows of the edge
            dx = np.maximum(0, np.maximum(x0 - xy[:, 0], xy[:, 0] - x1))
            dy = np.maximum(0, np.maximum(y0 - xy[:, 1], xy[:, 1] - y1))
            if np.any(np.hypot(dx, dy) < half):
                problems.append(f"label {label!r} at {np.round((x0, y0, x1, y1))} covers the edge {a}-{b}")
    return problems


def _cube_share(view, scene) -> float:
    """The highlighted cube's height on the pane, as a share of the pane's height."""
    cube = next(obj for obj in scene.objects if obj.name == "cube")
    ys = [view.widget_pos(v).y() for v in cube.vertices]
    assert all(0 <= view.widget_pos(v).x() <= view.plotter.width() for v in cube.vertices)
    assert min(ys) >= 0 and max(ys) <= view.plotter.height()
    return (max(ys) - min(ys)) / view.plotter.height()


def _check_frustum_lessons(qtbot, window):
    view = window.scene_view.view
    for lesson_id in FRUSTUM_LESSONS:
        lesson = shipped_lessons()[LESSONS[lesson_id]]
        for k, step in enumerate(lesson.steps):
            assert "frustum" in step.overlays
            window.lesson_panel.select(LESSONS[lesson_id], k)
            qtbot.waitUntil(lambda: _settled(view))  # noqa: B023 (waited for at once)
            assert view.plotter.width() > 200 and view.plotter.height() > 150
            assert _outside(view, lesson_id in WHOLE_FRUSTUM) == [], (lesson_id, k)
            assert _on_lines(view) == [], (lesson_id, k)
            if lesson_id not in WHOLE_FRUSTUM:
                assert _cube_share(view, step.scene) >= CUBE_SHARE, (lesson_id, k)


@pytest.mark.parametrize("size", [(1280, 720), (1920, 1080)])
def test_frustum_lessons_show_their_subject_and_labels_clear_of_the_lines_in_the_3d_pane(qtbot, window, size):
    window.resize(*size)
    qtbot.waitUntil(lambda: window.size().width() == size[0])
    _check_frustum_lessons(qtbot, window)


def _box_distance(box, point) -> float:
    (x0, y0, x1, y1), (x, y) = box, (point.x(), point.y())
    return float(np.hypot(max(x0 - x, 0.0, x - x1), max(y0 - y, 0.0, y - y1)))


@pytest.mark.parametrize("size", [(1280, 720), (1920, 1080)])
def test_the_frustums_two_labels_each_lie_nearer_their_own_plane_than_the_other(qtbot, window, size):
    # At 1280x720 the observer lesson's overview carried the near plane's label (one long line, no room
    # beside the pyramid's apex) across the drawing to beyond the far plane, and the far plane's label
    # down to the apex: each beside the other's plane, joined to its own by a leader 186 px long.
    window.resize(*size)
    qtbot.waitUntil(lambda: window.size().width() == size[0])
    view = window.scene_view.view
    pane = (view.plotter.width(), view.plotter.height())
    checked = []
    for lesson_id in FRUSTUM_LESSONS:
        for k in range(len(shipped_lessons()[LESSONS[lesson_id]].steps)):
            window.lesson_panel.select(LESSONS[lesson_id], k)
            qtbot.waitUntil(lambda: _settled(view))  # noqa: B023 (waited for at once)
            (near, near_box), (far, far_box) = _label_boxes(view)
            actor = next(actor for poly, actor, _ in view._overlays["frustum"]
                         if poly is view.overlay_parts("frustum")[3])
            near_at, far_at = (view.widget_pos(point) for point in actor._anchors.points)
            if all(0 <= p.x() <= pane[0] and 0 <= p.y() <= pane[1] for p in (near_at, far_at)):
                where = (lesson_id, k)
                assert _box_distance(near_box, near_at) < _box_distance(near_box, far_at), (where, near)
                assert _box_distance(far_box, far_at) < _box_distance(far_box, near_at), (where, far)
                checked.append((lesson_id, k))
    assert ("observer", 0) in checked and len(checked) >= 3  # steps with both planes in view


@pytest.mark.parametrize("scale", [1.5, 2.0])
def test_frustum_lessons_keep_their_labels_inside_the_3d_pane_and_off_its_lines_while_presenting(
        qtbot, window, scale):
    window.presentation.set_presenting(True)
    window.presentation.set_scale(scale)
    qtbot.waitUntil(lambda: window.scene_view.view.line_scale == scale)
    qtbot.waitUntil(window.presentation.settled)  # the panes' new sizes, before the labels are placed
    _check_frustum_lessons(qtbot, window)
    window.presentation.set_presenting(False)


LINES = 10
"""At 1280x720 and text x2 a lesson step shows at least this many lines of its words (or all of them)."""


def _lecture_hall_window(qtbot, monkeypatch):
    """The window on a 1280x720 screen, presenting, with text twice its size."""
    return presenting_on_1280x720(qtbot, monkeypatch, 2.0)


def _words_shown(panel) -> int:
    return panel.scroll.viewport().height()


def test_at_1280x720_and_text_x2_every_lesson_step_shows_its_words_whole_or_ten_lines(qtbot, monkeypatch):
    window = _lecture_hall_window(qtbot, monkeypatch)
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


def test_at_1280x720_and_text_x2_a_step_pointing_at_a_ray_shows_four_rows_of_the_ray_tree(qtbot, monkeypatch):
    """The image gives the tree room (it kept about a row and a half), but keeps its share."""
    window = _lecture_hall_window(qtbot, monkeypatch)
    panel = window.tab("image order").widget
    steps = [(row, k) for row, lesson in enumerate(shipped_lessons())
             for k, step in enumerate(lesson.steps) if "ray" in step.highlight]
    assert steps  # the ray-casting and ray-tracing lessons point at rays
    for row, k in steps:
        window.lesson_panel.select(row, k)
        qtbot.waitUntil(lambda: panel.tree.topLevelItemCount() > 0)
        qtbot.waitUntil(lambda: panel.tree.viewport().height() >= TREE_ROWS * panel.tree.sizeHintForRow(0))
        assert panel.details.currentIndex() == 0, (row, k)
        image, details = panel.split.sizes()
        assert image >= IMAGE_SHARE * (image + details) - 1, (row, k)  # the image keeps its share
    window.presentation.set_presenting(False)


def test_the_acceleration_lessons_settings_and_ray_colours_fit_beside_the_image_at_1920x1080(qtbot, window):
    # With the heat map's scale shown, the settings column scrolled and cut the ray-colour legend
    # (it needed 616 px of the 568 the image row had).
    window.show()
    window.setGeometry(window.screen().availableGeometry())  # the whole 1920 x 1080 screen
    qtbot.waitUntil(lambda: window.width() == 1920)
    panel = window.tab("image order").widget
    column = panel.findChild(SideColumn)
    legend = column.findChild(RayKindLegend)
    lesson = LESSONS["acceleration"]
    for k in (2, 3):  # both together in 3D; the heat map
        window.lesson_panel.select(lesson, k)
        qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)

        def fits(k=k):
            bottom = legend.mapTo(column.viewport(), legend.rect().bottomLeft()).y()
            assert panel.heat_scale.isVisible() == (k == 3)
            assert column.verticalScrollBar().maximum() == 0  # nothing to scroll to
            assert legend.isVisible() and bottom < column.viewport().height()  # the legend whole

        qtbot.waitUntil(fits)


def test_at_1280x720_the_heat_maps_colour_scale_shows_beside_the_image_without_scrolling(qtbot, window):
    # The heat-map step says "dark for none, bright for the most any pixel took": the scale that
    # says which is which sat below the settings, out of the column's view at 1280x720.
    window.show()
    window.resize(1280, 720)
    qtbot.waitUntil(lambda: window.width() == 1280)
    panel = window.tab("image order").widget
    column = panel.findChild(SideColumn)
    window.lesson_panel.select(LESSONS["acceleration"], 3)
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)

    def shown_whole():
        scale = panel.heat_scale
        assert scale.isVisible()
        top = scale.mapTo(column.viewport(), scale.rect().topLeft()).y()
        assert top >= 0 and top + scale.height() <= column.viewport().height(), (top, scale.height())

    qtbot.waitUntil(shown_whole)


def _overlay_label_boxes(view, name: str) -> list[tuple[str, tuple[float, float, float, float], bool]]:
    """Every label overlay ``name`` draws: its text, its box in widget pixels (x0, y0, x1, y1), y down,
    and whether the point it names is in the pane."""
    view.plotter.render()
    ratio, measure, box, boxes = view.plotter.devicePixelRatioF(), vtkTextRenderer(), [0, 0, 0, 0], []
    dpi, pane = view.plotter.ren_win.GetDPI(), (view.plotter.width(), view.plotter.height())
    for _, actor, style in view._overlays.get(name, []):
        if "label_size" not in style:
            continue
        mapper = actor.GetMapper()
        drawn = pv.wrap(mapper.GetInput())
        for k, label in enumerate(drawn.point_data["labels"]):
            measure.GetBoundingBox(mapper.GetLabelTextProperty(), str(label), box, dpi)
            p, named = view.widget_pos(drawn.points[k]), view.widget_pos(actor._anchors.points[k])
            boxes.append((str(label), (p.x() + box[0] / ratio, p.y() - box[3] / ratio,
                                       p.x() + box[1] / ratio, p.y() - box[2] / ratio),
                          0 <= named.x() <= pane[0] and 0 <= named.y() <= pane[1]))
    return boxes


def test_at_1280x720_and_text_x2_the_perspective_lessons_labels_are_whole_in_the_3d_pane(qtbot, monkeypatch):
    # The 3D pane is short there (about 480 x 125): A's label, the point projected, was placed flush with
    # the pane's right edge and lost the right leg of its A (the glyphs' outline reaches past the box
    # measured).  A label of a point in view is whole in the pane, clear of its edges (one of a point out
    # of view, the far plane's, is not drawn there).
    window = _lecture_hall_window(qtbot, monkeypatch)
    view = window.scene_view.view
    window.lesson_panel.select(LESSONS["perspective"], 0)
    qtbot.waitUntil(lambda: _settled(view) and "projector" in view.overlay_names(), timeout=RENDER_TIMEOUT_MS)
    pane = (view.plotter.width(), view.plotter.height())

    def whole() -> bool:
        labels = [b for name in view.overlay_names() for b in _overlay_label_boxes(view, name)]
        assert {"A", "A′"} <= {text for text, _, named_in_view in labels if named_in_view}
        for text, (x0, y0, x1, y1), named_in_view in labels:
            if named_in_view:
                # A pixel clear of the edges: the glyphs' outline reaches past the box measured.
                assert x0 >= 1 and y0 >= 1 and x1 <= pane[0] - 1 and y1 <= pane[1] - 1, (text, (x0, x1), pane)
        return True

    qtbot.waitUntil(whole, timeout=5000)
    window.presentation.set_presenting(False)


@pytest.mark.parametrize("lesson", ["observer", "frustum", "perspective"])
def test_at_1280x720_and_text_x2_the_3d_panes_labels_do_not_cover_one_another(qtbot, monkeypatch, lesson):
    # In a 3D pane of about 480 x 125 px no spot clear of the lines was left for some labels, and each
    # was put centred above its point: "object 3", "object 4" and "object 2" were drawn over one another
    # and over "near plane (the screen)".  A label may cross a line there, never another label.
    window = _lecture_hall_window(qtbot, monkeypatch)
    view = window.scene_view.view
    k = LESSONS[lesson]
    for step in range(len(shipped_lessons()[k].steps)):
        window.lesson_panel.select(k, step)
        qtbot.waitUntil(lambda: _settled(view), timeout=RENDER_TIMEOUT_MS)
        pane = (view.plotter.width(), view.plotter.height())
        boxes = [(text, b) for name in view.overlay_names() for text, b, _ in _overlay_label_boxes(view, name)
                 if b[0] < pane[0] and b[2] > 0 and b[1] < pane[1] and b[3] > 0]  # drawn in the pane
        assert len(boxes) >= 2, (lesson, step)
        for (one, a), (other, b) in itertools.combinations(boxes, 2):
            overlap = min(a[2], b[2]) - max(a[0], b[0]), min(a[3], b[3]) - max(a[1], b[1])
            assert min(overlap) <= 0, (lesson, step, one, other)
    window.presentation.set_presenting(False)


def test_at_1280x720_and_text_x2_the_3d_panes_labels_keep_their_size_while_the_view_turns(qtbot, monkeypatch):
    # Where the labels at their presenting size find no room clear of one another, they are drawn as
    # at text x1.  Turning the view by hand, they shrank and grew by turns (four times in 180 degrees
    # here), each frame placing them at both sizes.  Now they shrink once and stay so until the
    # next framing (a lesson step's), which asks again which size fits.
    window = _lecture_hall_window(qtbot, monkeypatch)
    view = window.scene_view.view

    def framed():
        window.lesson_panel.select(LESSONS["observer"], 0)
        qtbot.waitUntil(lambda: _settled(view), timeout=RENDER_TIMEOUT_MS)
        return [actor for name in view.overlay_names() for _, actor, style in view._overlays[name]
                if "label_size" in style]

    def sizes(actors):
        return tuple(actor.GetMapper().GetLabelTextProperty().GetFontSize() for actor in actors)

    actors = framed()
    full, small = sizes(actors), tuple(actor._unscaled[1] for actor in actors)
    assert actors and full > small  # framed, they fit at their presenting size
    seen = [full]
    for _ in range(90):  # turned by hand, 2 degrees a frame
        view.plotter.camera.Azimuth(2)
        view.plotter.render()
        seen.append(sizes(actors))
    assert small in seen  # somewhere they found no room at full size
    assert seen == [full] * seen.index(small) + [small] * (len(seen) - seen.index(small))
    window.lesson_panel.select(LESSONS["observer"], 1)
    actors = framed()
    assert sizes(actors) == full  # framed again: at their presenting size
    window.presentation.set_presenting(False)
