"""Lessons → Add this view as a step records the 3D pane's viewpoint, the highlight and the heat map
too: recorded, the file reloaded and its step applied, the window shows the same again."""

import json

import numpy as np
import pytest
from PySide6.QtWidgets import QMessageBox

from core.lessons.lesson_file import shipped_lessons

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def _shown(window):
    """What the window shows that the recorder used to lose: the 3D pane's camera, the highlight in
    words and as 3D points, and the heat map chosen."""
    camera = [tuple(map(float, v)) for v in window.scene_view.plotter.camera_position]
    parts = [np.asarray(poly.points).round(9).tolist() for poly in window.scene_view.overlay_parts("lesson")]
    return camera, window.lessons.highlighted, parts, window.tab("image order").widget.heat.currentText()


def test_a_recorded_step_brings_back_the_viewpoint_the_highlight_and_the_heat_map(window, qtbot, tmp_path):
    panel = window.lesson_panel
    panel.select(LESSONS["back_faces"], 0)  # the pyramid's back face highlighted, with its normal
    by_hand = [(7.0, 5.5, -6.0), (0.0, 0.8, 0.0), (0.0, 1.0, 0.0)]  # the 3D pane turned to look from behind
    window.scene_view.plotter.camera_position = by_hand
    heat = window.tab("image order").widget.heat
    heat.setCurrentIndex(next(k for k in range(heat.count()) if heat.itemText(k) == "Primitive tests"))
    before = _shown(window)
    assert before[1] == "triangle 2 of 'pyramid'" and before[2] and before[3] == "Primitive tests"

    path = tmp_path / "recorded.json"
    assert window.recorder.record(path, "From behind", "The back face, seen from behind.")
    step = json.loads(path.read_text(encoding="utf-8"))["steps"][0]
    assert step["view"] == {"position": [7.0, 5.5, -6.0], "focal_point": [0.0, 0.8, 0.0],
                            "up": [0.0, 1.0, 0.0]}
    assert step["highlight"] == {"face": {"object": "pyramid", "triangle": 2}}
    assert step["heat_map"] == "primitive tests"

    window.reset_scene()  # something else: the lecture scene, its own framing, no heat map
    heat.setCurrentIndex(0)
    window.scene_view.plotter.camera_position = [(1.0, 2.0, 3.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0)]
    assert _shown(window)[0] != before[0] and _shown(window)[3] == "Off"
    panel.open_lesson_file(path)  # loads the file and shows its first step
    after = _shown(window)
    assert after[0] == [pytest.approx(v, abs=1e-9) for v in before[0]]
    assert after[1:] == before[1:]


def test_a_highlight_naming_an_object_the_scene_no_longer_has_is_left_out(window, tmp_path):
    window.lesson_panel.select(LESSONS["back_faces"], 0)
    window.reset_scene()  # the lecture scene has no pyramid
    path = tmp_path / "recorded.json"
    assert window.recorder.record(path, "Lecture", "The lecture scene.")
    step = json.loads(path.read_text(encoding="utf-8"))["steps"][0]
    assert "highlight" not in step and "heat_map" not in step and set(step["view"]) == {
        "position", "focal_point", "up"}


def test_the_exercise_typed_in_the_form_is_written_for_the_step_and_a_bad_one_is_refused(window, qtbot,
                                                                                        tmp_path):
    window.lesson_panel.select(LESSONS["back_faces"], 0)  # the pyramid, its triangle 2 a back face
    exercise = {"kind": "choose_one", "question": "Is the highlighted face culled?", "choices": [True, False],
                "fact": {"fact": "back_face", "object": "pyramid", "triangle": 2, "is": "$choice"}}
    path = tmp_path / "recorded.json"
    assert window.recorder.record(path, "Culled?", "Look at the face.", "", json.dumps(exercise))
    assert json.loads(path.read_text(encoding="utf-8"))["exercises"] == [{**exercise, "step": 0}]
    window.lesson_panel.open_lesson_file(path)
    assert [ex.question for ex in window.lesson_panel.current_lesson().exercises] == [exercise["question"]]

    before = path.read_bytes()
    bad = {**exercise, "fact": {**exercise["fact"], "fact": "culled"}}
    assert not window.recorder.record(path, "Again", "Again.", "", json.dumps(bad))
    box = window.findChild(QMessageBox, "lesson_record_error")
    qtbot.waitUntil(box.isVisible)
    assert "exercises[1].fact (choice 0).fact: " in box.informativeText()
    assert path.read_bytes() == before
    box.close()
