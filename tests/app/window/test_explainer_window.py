"""The explainer in the window: lessons drive the panes, presentation keys, worked math, new tabs."""

import ast
import re

import mpmath
import numpy as np
import pytest
from PySide6.QtCore import Qt
from PySide6.QtGui import QAction
from qt_fixtures import keys_listed
from window_helpers import RENDER_TIMEOUT_MS

from app.window.window_layout import in_front
from core import presets
from core.lessons.lesson_file import shipped_lessons
from core.object_order.depth_formats import DEPTH_FORMATS
from core.scene import Mesh, Sphere
from views.panels.cost_panel import CostPanel
from views.panels.hard_cases_panel import HardCasesPanel

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def _activate(qtbot, win):
    win.activateWindow()
    qtbot.waitUntil(win.isActiveWindow)


def _number(formula: str) -> float:
    """The number after the last ``=`` of a typeset row."""
    return float(re.findall(r"=\s*(-?[0-9.]+(?:e[-+]?[0-9]+)?)", formula)[-1])


def _find(scene, name):
    return next(o for o in scene.objects if o.name == name)


def test_the_window_opens_on_the_first_lesson_without_changing_the_scene(window):
    panel = window.lesson_panel
    assert window.lesson_dock.isVisible()
    assert panel.step_index() == (0, 0)
    assert panel.current_lesson().id == "two_orders"
    assert window.model.scene == presets.lecture_scene()
    assert set(window.visible_panes()) == {"scene 3D", "image order", "object order", "four views",
                                           "compare", "hard cases", "cost"}


def test_show_me_brings_the_step_the_pixel_the_question_names_and_the_pane_that_reads_it(qtbot, window):
    """The first exercise asks what object order's z-buffer keeps at pixel (155, 110): Show me shows
    its step, picks that pixel in both pipelines and brings the Object order tab, whose pixel history
    then lists the fragments there (the step itself opens on the Compare tab)."""
    panel, exercises = window.lesson_panel, window.exercise_panel
    panel.select(LESSONS["two_orders"], 1)
    exercises.set_lesson(panel.current_lesson())
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    assert "(155, 110)" in exercises.question.text() and "z-buffer" in exercises.question.text()
    exercises.show_button.click()
    assert panel.step_index() == (LESSONS["two_orders"], 0)
    assert window.model.buffer_pixel == (155, 110) and window.model.ray_pixel == (155, 110)
    assert window.current.title == "Object order"
    assert window.statusBar().currentMessage() == ("Exercise 1: showing step 1, whose scene it asks about, "
                                                   "with pixel (155, 110) picked in the Object order tab")


def test_every_shipped_lesson_step_shows_its_panes_scene_text_and_highlight(qtbot, window):
    panel = window.lesson_panel
    for row, lesson in enumerate(shipped_lessons()):
        for k, step in enumerate(lesson.steps):
            if k == 0:  # a click in the lesson list (the first lesson is open, not yet shown)
                item = panel.list.item(row)
                panel.list.scrollToItem(item)
                qtbot.mouseClick(panel.list.viewport(), Qt.MouseButton.LeftButton,
                                 pos=panel.list.visualItemRect(item).center())
            else:
                panel.next_button.click()
            assert panel.step_index() == (row, k)
            assert set(window.visible_panes()) == set(step.panes), (lesson.id, k)
            tabs = [p for p in step.panes if p != "scene 3D"]
            assert window.current.title.lower() == tabs[0]
            assert window.model.scene == step.scene
            assert window.model.trace_settings == step.image_order
            assert panel.text.text() == step.text
            assert panel.step_title.text() == step.title
            assert len(panel.formula_views()) == len(step.formulas)
            lit = window.scene_view.overlay_parts("lesson")
            highlight = step.highlight
            if "object" in highlight:
                obj = _find(step.scene, highlight["object"])
                assert obj.name in window.lessons.highlighted
                low, high = np.array(lit[0].bounds).reshape(3, 2).T
                if isinstance(obj, Mesh):
                    assert np.allclose(low, obj.vertices.min(axis=0)) and np.allclose(
                        high, obj.vertices.max(axis=0))
            if "face" in highlight:
                mesh = _find(step.scene, highlight["face"]["object"])
                corners = mesh.vertices[mesh.triangles[highlight["face"]["triangle"]]]
                assert any(len(p.points) == 3 and np.allclose(sorted(map(tuple, p.points)),
                                                              sorted(map(tuple, corners))) for p in lit)
            if not {"object", "face"} & set(highlight):  # only the names of the objects its text speaks of
                assert all("labels" in p.point_data for p in lit)
            if "vertex" in highlight:
                mesh = _find(step.scene, highlight["vertex"]["object"])
                point = mesh.vertices[highlight["vertex"]["index"]]
                world = window.tab("object order").widget.vertex_math.value("world")
                assert [float(v) for v in re.findall(r"-?[0-9.]+", world.split("=")[1])] == \
                    pytest.approx(point, rel=1e-5, abs=1e-5)
            expected_step = step.zbuffer_step
            if expected_step is None and "polygon_step" in highlight:
                expected_step = highlight["polygon_step"] + 1
            assert window.model.step == expected_step
            if step.pixel is not None:
                assert window.model.ray_pixel == tuple(step.pixel)
                assert window.model.buffer_pixel == tuple(step.pixel)
            if "ray" in highlight:
                qtbot.waitUntil(lambda s=step: window.ray_tree is not None
                                and window.ray_tree[:2] == tuple(s.pixel), timeout=RENDER_TIMEOUT_MS)
                tree = window.tab("image order").widget.tree
                qtbot.waitUntil(lambda h=highlight, t=tree: t.selected_kind() == h["ray"])
                assert tree.isVisible()


def test_pagedown_walks_the_zbuffer_lesson_from_anywhere_and_nothing_else_takes_it(qtbot, window):
    _activate(qtbot, window)  # typed keys go to the active window's focused widget
    panel = window.lesson_panel
    lesson = shipped_lessons()[LESSONS["zbuffer"]]
    panel.select(LESSONS["zbuffer"], 0)
    oo = window.tab("object order").widget
    spin = window.camera_panel.eye[0]
    distance_before = spin.value()
    window.controls_dock.raise_()  # its fields take the keyboard only in front
    qtbot.waitUntil(lambda: in_front(window.controls_dock))
    for k, step in enumerate(lesson.steps):
        if k:
            target = oo.scrubber.slider if k % 2 else spin  # widgets that would page or step on their own
            target.setFocus()
            qtbot.waitUntil(target.hasFocus)
            qtbot.keyClick(target, Qt.Key.Key_PageDown)
        assert panel.step_index() == (LESSONS["zbuffer"], k)
        qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
        qtbot.waitUntil(lambda s=step: oo.scrubber.step == s.zbuffer_step)
        assert f"Step {step.zbuffer_step} of 3" in oo.step_caption.text()
    assert spin.value() == distance_before
    qtbot.keyClick(oo.scrubber.slider, Qt.Key.Key_PageUp)
    assert panel.step_index() == (LESSONS["zbuffer"], len(lesson.steps) - 2)
    qtbot.waitUntil(lambda: oo.scrubber.step == lesson.steps[-2].zbuffer_step)


def test_a_picked_sphere_pixel_shows_the_quadratic_worked_out(qtbot, window):
    window.lesson_panel.select(LESSONS["ray_sphere"], 0)
    scene = window.model.scene
    sphere = next(o for o in scene.objects if isinstance(o, Sphere))
    cam = scene.camera
    x, y = cam.width // 2, cam.height // 2
    window.tab("image order").widget.image.pixel_clicked.emit(x, y)  # a click on the traced image
    qtbot.waitUntil(lambda: window.ray_tree is not None and window.ray_tree[:2] == (x, y),
                    timeout=RENDER_TIMEOUT_MS)
    root = window.ray_tree[2]
    math_pane = window.tab("image order").widget.worked_math
    mpmath.mp.dps = 30
    o = [mpmath.mpf(float(v)) for v in root.origin]
    d = [mpmath.mpf(float(v)) for v in root.direction]
    c = [mpmath.mpf(float(v)) for v in sphere.center]
    oc = [o[i] - c[i] for i in range(3)]
    a = sum(v * v for v in d)
    b = 2 * sum(d[i] * oc[i] for i in range(3))
    cc = sum(v * v for v in oc) - mpmath.mpf(sphere.radius) ** 2
    delta = b * b - 4 * a * cc
    assert delta > 0  # the centre pixel's ray crosses the sphere
    t1, t2 = (-b - mpmath.sqrt(delta)) / (2 * a), (-b + mpmath.sqrt(delta)) / (2 * a)
    for label, exact in (("a", a), ("b", b), ("c", cc), ("Δ", delta), ("t_near", t1), ("t_far", t2)):
        assert _number(math_pane.value(label)) == pytest.approx(float(exact), rel=1e-5), label
    details = window.tab("image order").widget.details
    assert details.tabText(details.indexOf(math_pane)) == "Worked math"


def test_f11_presents_with_larger_text_and_dot_blanks(qtbot, window):
    _activate(qtbot, window)
    base = window.font().pointSizeF()
    presentation = window.presentation
    with qtbot.waitSignal(presentation.scale_changed):
        qtbot.keyClick(window, Qt.Key.Key_F11)
    assert presentation.presenting()
    assert window.font().pointSizeF() == pytest.approx(base * presentation.scale())
    assert presentation.scale() > 1
    qtbot.waitUntil(window.isFullScreen)
    qtbot.waitUntil(lambda: window.geometry().size() == window.screen().geometry().size())
    qtbot.keyClick(window, Qt.Key.Key_Period)
    assert presentation.blanked()
    qtbot.keyClick(window, Qt.Key.Key_Period)
    assert not presentation.blanked()
    qtbot.keyClick(window, Qt.Key.Key_Escape)
    assert not presentation.presenting()
    assert window.font().pointSizeF() == pytest.approx(base)
    qtbot.waitUntil(lambda: not window.isFullScreen())


def test_hard_cases_and_cost_tabs_show_their_panels(qtbot, window):
    _activate(qtbot, window)
    hard = window.tab("hard cases")
    qtbot.keyClick(window, Qt.Key.Key_5, Qt.KeyboardModifier.ControlModifier)
    assert window.current is hard
    assert isinstance(hard.widget, HardCasesPanel) and hard.widget.isVisible()
    cases = hard.widget.cases  # shown once, the panel works out every case and marks it passed or not
    qtbot.waitUntil(lambda: all(cases.item(i).text()[0] in "✓✗" for i in range(cases.count())),
                    timeout=RENDER_TIMEOUT_MS)
    qtbot.keyClick(window, Qt.Key.Key_6, Qt.KeyboardModifier.ControlModifier)
    cost = window.tab("cost")
    assert window.current is cost
    assert isinstance(cost.widget, CostPanel) and cost.widget.isVisible()
    assert cost.widget.scene is window.model.scene
    window.lesson_panel.select(LESSONS["zbuffer"], 0)  # a new scene: the sweep follows it
    assert cost.widget.scene is window.model.scene
    assert cost.widget.scene == shipped_lessons()[LESSONS["zbuffer"]].steps[0].scene


def test_z_test_and_depth_format_switches_set_the_raster_settings(qtbot, window):
    window.show_tab("object order")
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    box = panel.switches["z_test"]
    assert box.isChecked() and box.toolTip()
    box.click()  # as a click on the box does
    assert window.model.raster_settings.z_test is False
    assert window.model.raster_settings.record_steps
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    combo = panel.depth_format
    assert [combo.itemData(i) for i in range(combo.count())] == list(DEPTH_FORMATS)
    assert "z-fighting" in combo.toolTip()
    combo.setCurrentIndex(combo.findData("int16"))
    assert window.model.raster_settings.depth_format == "int16"
    assert window.model.raster_settings.z_test is False  # the other switches stay as they were


def test_the_lessons_dock_toggles_from_the_view_menu(qtbot, window):
    view = next(a.menu() for a in window.menuBar().actions() if a.text() == "&View")
    toggle = next(a for a in view.actions() if a.text() == "Lessons")
    assert in_front(window.lesson_dock) and toggle.isChecked()
    toggle.trigger()
    assert not window.lesson_dock.isVisible() and not toggle.isChecked()
    toggle.trigger()
    assert window.lesson_dock.isVisible()


def test_ctrl_shift_l_and_e_bring_their_dock_forward_from_behind_another_tab(qtbot, window):
    """Tabbed behind another dock, Lessons and the scene editor were hidden by their key's first press
    and shown, still behind, by the second: the key now brings the dock to the front, and hides it
    only when it is in front."""
    lessons = next(a for a in window.findChildren(QAction) if a.text() == "Lessons")
    editor = window.editor
    editor_key = next(a for a in editor.keyed_actions if a.text() == "Scene editor")
    window.exercise_dock.raise_()  # Exercises in front of Lessons and the scene editor
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    assert not in_front(window.lesson_dock) and not lessons.isChecked()
    lessons.trigger()  # Ctrl+Shift+L
    qtbot.waitUntil(lambda: in_front(window.lesson_dock))
    assert lessons.isChecked()
    editor_key.trigger()  # Ctrl+Shift+E
    qtbot.waitUntil(lambda: in_front(editor.dock))
    assert not in_front(window.lesson_dock) and not lessons.isChecked()
    editor_key.trigger()  # in front: hidden
    assert not editor.dock.isVisible() and not editor_key.isChecked()


def test_a_closed_exercises_dock_comes_back_with_ctrl_shift_x(qtbot, window):
    # Its title's button closes it, and nothing brought it back.
    exercises = next(a for a in window.findChildren(QAction)
                     if a.text() == "Exercises" and a.shortcut().toString() == "Ctrl+Shift+X")
    assert "Ctrl+Shift+X" in keys_listed(window) and "Exercises" in keys_listed(window)
    window.exercise_dock.close()
    qtbot.waitUntil(lambda: not window.exercise_dock.isVisible())
    exercises.trigger()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    assert exercises.isChecked()


def test_a_picked_buffer_pixel_follows_its_polygons_nearest_corner_to_the_screen(qtbot, window):
    window.show_tab("object order")
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    cam = window.model.camera
    panel.image.pixel_clicked.emit(cam.width // 2, cam.height // 2)  # a click in image memory
    rows = panel.vertex_math.rows()
    heading = rows[0][1]
    name = re.search(r"corner \d+ of (.+), triangle \d+", heading)
    assert name is not None, heading
    obj = _find(window.model.scene, name.group(1))
    world = [float(v) for v in re.findall(r"-?[0-9.]+(?:e[-+]?[0-9]+)?",
                                          panel.vertex_math.value("world").split("=")[1])]
    # The corner shown is one of that object's own vertices (the centre polygon is not clipped).
    assert np.min(np.abs(obj.vertices - world).max(axis=1)) < 1e-4
    assert "pixel" in dict(rows)


def test_a_vertex_path_shown_by_one_lesson_is_worked_again_with_the_next_lessons_projection(qtbot, window):
    panel = window.lesson_panel
    vertex_math = window.tab("object order").widget.vertex_math
    panel.select(LESSONS["perspective"], 0)  # shows a cube corner's path under perspective
    assert vertex_math.value("clip ← view").endswith("[0.0, 0.0, -1.0, 0.0]]")  # w = -z_view
    panel.select(LESSONS["orthographic"], 0)
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    assert window.model.camera.projection == "orthographic"
    # An orthographic projection keeps w = 1: its matrix's last row is (0, 0, 0, 1).
    assert vertex_math.value("clip ← view").endswith("[0.0, 0.0, 0.0, 1.0]]")
    assert np.allclose(ast.literal_eval(vertex_math.value("clip ← view")), window.model.camera.clip_from_view)
