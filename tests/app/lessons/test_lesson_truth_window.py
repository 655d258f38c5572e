"""Lessons in the window say only what it shows: the first step is applied, not skipped; another
scene takes the step's words away; a stale vertex path goes; an opened lesson's false facts are shown."""

import json
import re

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QMessageBox
from window_helpers import RENDER_TIMEOUT_MS

from app.lessons.runner import FACE_SIDE_OVERLAY
from app.window.window_layout import in_front
from core.lessons.lesson_file import FILES, shipped_lessons

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def test_the_first_pagedown_shows_step_one_of_the_first_lesson(window, qtbot):
    panel = window.lesson_panel
    first = panel.lessons()[0].steps[0]
    assert window.lessons.step is None  # opened on the lesson without applying it
    with qtbot.waitSignal(panel.step_selected):
        panel.next()
    assert panel.step_index() == (0, 0) and window.lessons.step is first
    assert window.model.trace_settings.mode == first.image_order.mode == "raycast"  # step 1's own setting


def test_ctrl_l_takes_the_lessons_words_away_and_pagedown_brings_the_step_back(window, qtbot):
    panel = window.lesson_panel
    k = LESSONS["zbuffer"]
    panel.select(k, 2)
    step = panel.current_step()
    assert panel.text.text() == step.text
    window.reset_scene()  # File → Lecture scene, Ctrl+L
    assert step.text not in panel.text.text() and "lecture" in panel.text.text()
    assert [o.name for o in window.model.scene.objects] == ["cube", "cone", "ground"]
    with qtbot.waitSignal(panel.step_selected):
        panel.next()
    assert panel.step_index() == (k, 2) and panel.text.text() == step.text
    assert window.model.scene == step.scene and window.lessons.step is step


def test_the_vertex_path_of_one_scene_is_not_shown_with_another(window, qtbot):
    panel, oo = window.lesson_panel, window.tab("object order").widget
    panel.select(LESSONS["perspective"], 0)  # follows vertex 6 of the cube
    assert "vertex 6 of 'cube'" in " ".join(text for _, text in oo.vertex_math.rows())
    panel.select(LESSONS["zbuffer"], 0)  # three triangles, no cube
    qtbot.waitUntil(lambda: window.showing_full("object order") and oo.scene is window.model.scene,
                    timeout=RENDER_TIMEOUT_MS)
    shown = " ".join(text for _, text in oo.vertex_math.rows())
    assert "cube" not in shown and "Click a pixel" in shown


def test_a_lesson_step_that_follows_no_vertex_does_not_show_the_last_ones_path(window, qtbot):
    # The orthographic lesson follows vertex 6 of the cube; the next lesson's first step shows the
    # same lecture scene and speaks of no vertex, yet its Vertex path tab kept the cube's vertex.
    panel, oo = window.lesson_panel, window.tab("object order").widget
    ortho = shipped_lessons()[LESSONS["orthographic"]]
    k = next(i for i, step in enumerate(ortho.steps) if "vertex" in step.highlight)
    panel.select(LESSONS["orthographic"], k)
    assert "vertex 6 of 'cube'" in " ".join(text for _, text in oo.vertex_math.rows())
    panel.select(LESSONS["three_views"], 0)
    qtbot.waitUntil(lambda: window.showing_full("object order") and oo.scene is window.model.scene,
                    timeout=RENDER_TIMEOUT_MS)
    shown = " ".join(text for _, text in oo.vertex_math.rows())
    assert "cube" not in shown and "Click a pixel" in shown


def _open(window, qtbot, data, tmp_path):
    path = tmp_path / "mine.json"
    path.write_text(json.dumps(data), encoding="utf-8")
    assert window.lesson_panel.open_lesson_file(path) is not None
    qtbot.waitUntil(lambda: not window.fact_check.busy, timeout=RENDER_TIMEOUT_MS)


def test_an_opened_lesson_with_a_false_fact_shows_the_author_what_was_computed(window, qtbot, tmp_path):
    data = json.loads((FILES / "03_frustum.json").read_text(encoding="utf-8"))
    _open(window, qtbot, data, tmp_path)  # every fact true: no dialog, the status bar says so
    assert window.fact_check.failures == [] and window.fact_check.dialog is None
    assert "Every fact" in window.statusBar().currentMessage()

    fact = data["steps"][1]["facts"][0]
    assert fact == {"fact": "frustum", "object": "box", "is": "outside", "beyond": "near"}
    fact["beyond"] = "far"  # false: the box stands behind the eye, far nearer than the end plane
    _open(window, qtbot, data, tmp_path)
    box = window.findChild(QMessageBox, "lesson_facts")
    qtbot.waitUntil(lambda: box is not None and box.isVisible())
    (line,) = window.fact_check.failures
    said, computed = line.split("): computed ")
    assert said.endswith("steps[1].facts[0] ('box' is outside the frustum, "
                         "beyond its far plane")
    assert computed.startswith("'box' is outside the frustum, beyond its ")
    assert computed.endswith(" near planes") and "far" not in computed
    assert line in box.informativeText()
    assert box.text().startswith("1 problem in 'The viewing pyramid and the frustum': a fact the ")
    box.close()


def _lesson_labels(window) -> list[str]:
    """The words the lesson writes in the 3D pane: objects' names and a face's side."""
    view = window.scene_view
    parts = [poly for overlay in ("lesson", FACE_SIDE_OVERLAY) for poly in view.overlay_parts(overlay)]
    return [str(t) for poly in parts if "labels" in poly.point_data for t in poly.point_data["labels"]]


def test_the_objects_the_text_names_are_labelled_in_the_3d_pane(window, qtbot):
    window.lesson_panel.select(LESSONS["observer"], 1)  # "Object 5 is now outside ... objects 1 to 4"
    labels = _lesson_labels(window)
    assert {"object 1", "object 2", "object 3", "object 4", "object 5"} <= set(labels)
    window.lesson_panel.select(LESSONS["perspective"], 0)  # "here a corner of the cube"
    assert _lesson_labels(window) == ["cube"]
    window.lesson_panel.select(LESSONS["frustum"], 0)  # a pyramid, the eye and the screen: no object
    assert _lesson_labels(window) == []


def test_the_highlighted_back_face_has_its_normal_drawn_pointing_away_from_the_eye(window, qtbot):
    import numpy as np

    window.lesson_panel.select(LESSONS["back_faces"], 0)
    step = window.lesson_panel.current_step()
    pyramid = step.scene.objects[0]
    a, b, c = pyramid.vertices[pyramid.triangles[step.highlight["face"]["triangle"]]]
    normal = np.cross(b - a, c - a)  # outward: the faces wind counter-clockwise seen from outside
    centroid = (a + b + c) / 3
    assert np.dot(normal, np.asarray(step.scene.camera.eye) - centroid) < 0  # a back face, by hand
    assert "N: back face" in _lesson_labels(window)
    arrow = max(window.scene_view.overlay_parts("lesson"), key=lambda p: p.n_points)  # the arrow mesh
    tip = arrow.points[np.argmax(arrow.points @ normal)]
    assert np.dot(tip - centroid, normal) > 0  # drawn from the face outwards, along N


def test_exercises_follow_the_lesson_a_click_answers_and_progress_shows_in_the_list(window, qtbot):
    panel, exercises = window.lesson_panel, window.exercise_panel
    k = LESSONS["ray_casting"]
    panel.select(k, 0)
    assert exercises.lesson is panel.current_lesson()
    assert exercises.question.text() == "Click a pixel in the cube's shadow."
    window.exercise_dock.raise_()  # the student opens the Exercises tab
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    with qtbot.waitSignal(panel.step_selected):  # "show me": the shadow step, a pixel in the shadow
        exercises.show_button.click()
    qtbot.waitUntil(lambda: window.model.ray_pixel is not None, timeout=RENDER_TIMEOUT_MS)
    assert panel.step_index() == (k, 1)
    pixel = window.model.ray_pixel
    image = window.tab("image order").widget.image
    qtbot.mouseClick(image, Qt.MouseButton.LeftButton, pos=image.widget_pos(*pixel).toPoint())  # the student
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("Right"), timeout=RENDER_TIMEOUT_MS)
    # Right, but not at the first try: Show me gave a right pixel.
    assert "1/3 done, 0 right at first try" in panel.list.item(k).text()


def test_reveal_on_a_click_a_pixel_exercise_picks_the_pixel_it_names(window, qtbot):
    """Reveal names a pixel in the cube's shadow and picks it in the shadow step's image, where the
    student looks for it (it only named it: the student had to find (x, y) in the picture)."""
    panel, exercises = window.lesson_panel, window.exercise_panel
    k = LESSONS["ray_casting"]
    panel.select(k, 0)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    assert exercises.question.text() == "Click a pixel in the cube's shadow."
    window.model.set_ray_pixel((0, 0))  # the student's own pick, in the sky
    exercises.reveal_button.click()
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("The answer:"), timeout=RENDER_TIMEOUT_MS)
    named = re.search(r"pixel \((\d+), (\d+)\)", exercises.feedback.text())
    assert named is not None
    assert window.model.ray_pixel == (int(named[1]), int(named[2]))
    assert panel.step_index() == (k, 1)  # the shadow step, whose scene the question asks about
    assert window.current.title == "Image order"


def test_add_this_view_as_a_step_round_trips_the_window_state(window, qtbot, tmp_path):
    panel = window.lesson_panel
    k = LESSONS["zbuffer"]
    panel.select(k, 2)  # blue drawn: step 2, the object-order tab in front
    window.model.set_buffer_pixel((87, 74))
    before = (window.model.scene, window.model.trace_settings, window.model.raster_settings,
              window.model.step, window.visible_panes(), window.current.title)
    path = tmp_path / "my lesson.json"
    facts = '[{"fact": "zbuffer_keeps", "pixel": [87, 74], "object": "blue"}]'
    assert window.recorder.record(path, "Blue wins", "Blue is nearest here.", facts)
    assert window.recorder.record(path, "Again", "The same view twice: blue wins again.")  # names the mark
    window.reset_scene()  # something else in the window
    lesson = panel.open_lesson_file(path)  # the file loads, and its first step is shown
    assert [s.title for s in lesson.steps] == ["Blue wins", "Again"] and lesson.id == "my_lesson"
    qtbot.waitUntil(lambda: not window.fact_check.busy, timeout=RENDER_TIMEOUT_MS)
    assert window.fact_check.failures == []  # the recorded fact holds
    after = (window.model.scene, window.model.trace_settings, window.model.raster_settings,
             window.model.step, window.visible_panes(), window.current.title)
    assert after[0] == before[0] and after[1:4] == before[1:4]
    assert set(after[4]) == set(before[4]) and after[5] == before[5]
    assert window.model.buffer_pixel == (87, 74)

    bad = '[{"fact": "zbuffer_keeps", "pixel": [87, 74], "object": "purple"}]'
    assert not window.recorder.record(path, "Bad", "words", bad)
    box = window.findChild(QMessageBox, "lesson_record_error")
    qtbot.waitUntil(lambda: box is not None and box.isVisible())
    assert "steps[2].facts[0].object: no object 'purple' in the scene" in box.informativeText()
    box.close()
    assert len(json.loads(path.read_text(encoding="utf-8"))["steps"]) == 2  # nothing written


def test_the_grid_step_outlines_the_cells_its_picked_ray_walks_as_its_words_say(window, qtbot):
    # "A ray walks only through the cells it crosses, outlined here for the picked pixel's ray": the step
    # showed the grid's occupied cells only.  Every cell of the grid that the segment from the eye to the
    # hit crosses (a slab test of each cell, by brute force, cells only touched at a corner or edge left
    # to either side) is outlined, and only those.
    import numpy as np

    from core.image_order.flat_scene import trace_scene

    panel = window.lesson_panel
    k = LESSONS["acceleration"]
    panel.select(k, 1)
    step = panel.current_step()
    assert "cells the ray walks" in step.overlays and "walk" in window.model.overlays
    assert window.tab("image order").widget.show_walk.isChecked()
    qtbot.waitUntil(lambda: window.ray_tree is not None and window.ray_tree[:2] == tuple(step.pixel),
                    timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: len(window.scene_view.overlay_parts("walk")) > 0, timeout=RENDER_TIMEOUT_MS)
    (outlines,) = window.scene_view.overlay_parts("walk")
    shown = {tuple(np.round(low, 9)) for low in outlines.points.reshape(-1, 8, 3)[:, 0]}  # boxes' low corners
    root = window.ray_tree[2]
    grid = trace_scene(step.scene).geometry.accel("grid")[0]
    nx, ny, nz = grid.resolution
    every = np.array([(i, j, kk) for kk in range(nz) for j in range(ny) for i in range(nx)])
    boxes = grid.cell_boxes(every)
    with np.errstate(divide="ignore", invalid="ignore"):
        t0 = (boxes[:, 0] - root.origin) / root.direction
        t1 = (boxes[:, 1] - root.origin) / root.direction
    enter = np.nanmax(np.minimum(t0, t1), axis=1)
    leave = np.nanmin(np.maximum(t0, t1), axis=1)
    tolerance = 1e-9 * root.t
    surely = (enter < leave - tolerance) & (leave > tolerance) & (enter < root.t - tolerance)
    maybe = (enter <= leave + tolerance) & (leave >= -tolerance) & (enter <= root.t + tolerance)
    crossed = {tuple(np.round(b[0], 9)) for b in boxes[surely]}
    touched = {tuple(np.round(b[0], 9)) for b in boxes[maybe]}
    assert len(crossed) >= 3 and crossed <= shown <= touched
    panel.select(k, 2)  # the next step shows the grid and the spheres, not the walk
    assert "walk" not in window.model.overlays


def test_a_polygon_the_lesson_numbers_is_the_one_the_window_numbers_so(window, qtbot):
    # "Polygon 1: green" stood over a caption "Step 1 of 3: polygon 0 — green": the lesson counts the
    # polygons drawn from one, as the z-buffer's steps, its pixel history and the status bar's pointer
    # do.  Every step that points at a drawn polygon: the caption, the pointer and the words agree.
    panel, oo = window.lesson_panel, window.tab("object order").widget
    pointed = [(k, s) for k, lesson in enumerate(panel.lessons()) for s, step in enumerate(lesson.steps)
               if "polygon_step" in step.highlight]
    assert len(pointed) >= 3
    for k, s in pointed:
        panel.select(k, s)
        step = panel.current_step()
        n = step.highlight["polygon_step"] + 1  # drawn at step n, counted from one
        qtbot.waitUntil(lambda n=n: window.showing_full("object order") and oo.scene is window.model.scene
                        and oo.scrubber.step == n, timeout=RENDER_TIMEOUT_MS)
        caption = re.match(r"Step (\d+) of \d+: polygon (\d+) — (\w+)", oo.step_caption.text())
        drawn = step.scene.objects[oo.result.draw.object_index[n - 1]].name
        assert caption.groups() == (str(n), str(n), drawn)
        assert f"the polygon drawn at step {n}" in window.statusBar().currentMessage()
        for written in re.findall(r"[Pp]olygon (\d+)", f"{step.title} {step.text}"):
            assert int(written) == n, (step.title, oo.step_caption.text())
