"""A recorded step keeps the 3D pane's viewpoint, the highlight and the heat map through the file."""

from types import MappingProxyType

import numpy as np
import pytest

from core.image_order.flat_scene import TraceSettings
from core.lessons.authoring import add_step, step_record
from core.lessons.exercises import right_choices
from core.lessons.facts import StepPipelines
from core.lessons.lesson_file import LessonFileError, load_lesson
from core.object_order.pipeline import RasterSettings
from core.presets import culling_pyramid


def test_the_viewpoint_highlight_and_heat_map_are_written_and_read_back(tmp_path):
    scene = culling_pyramid()
    view = {"position": np.array([7.0, 5.5, -6.0]), "focal_point": (0.0, 0.8, 0.0), "up": (0, 1, 0)}
    highlight = MappingProxyType({"face": MappingProxyType({"object": "pyramid", "triangle": np.int64(2)}),
                                  "pixel": (80, 60), "ray": "shadow"})
    step = step_record(title="t", text="w", scene=scene, panes=["object order"], image_order=TraceSettings(),
                       object_order=RasterSettings(), view=view, highlight=highlight,
                       heat_map="box and sphere tests")
    lesson = add_step(tmp_path / "l.json", step)
    again = load_lesson(tmp_path / "l.json").steps[0]
    for read in (lesson.steps[0], again):
        assert dict(read.view) == {"position": (7.0, 5.5, -6.0), "focal_point": (0.0, 0.8, 0.0),
                                   "up": (0.0, 1.0, 0.0)}
        assert dict(read.highlight["face"]) == {"object": "pyramid", "triangle": 2}
        assert read.highlight["pixel"] == (80, 60) and read.highlight["ray"] == "shadow"
        assert read.heat_map == "box and sphere tests"
    plain = step_record(title="t", text="w", scene=scene, panes=["object order"], image_order=TraceSettings(),
                        object_order=RasterSettings())
    assert not {"view", "highlight", "heat_map"} & set(plain)  # nothing to say: the defaults


CULLED = {"kind": "choose_one", "question": "Is triangle {t} of the pyramid culled as a back face?",
          "choices": [True, False], "why": "Its normal points away from the eye.",
          "fact": {"fact": "back_face", "object": "pyramid", "triangle": 0, "is": "$choice"}}


def _record(scene):
    return step_record(title="t", text="w", scene=scene, panes=["object order"], image_order=TraceSettings(),
                       object_order=RasterSettings())


def test_an_exercise_typed_for_a_step_is_asked_about_that_step_and_answered_by_the_pipelines(tmp_path):
    scene = culling_pyramid()
    pyramid = scene.objects[0]
    path = tmp_path / "l.json"
    add_step(path, _record(scene))
    for t in range(len(pyramid.triangles)):
        exercise = {**CULLED, "question": CULLED["question"].format(t=t),
                    "fact": {**CULLED["fact"], "triangle": t}}
        add_step(path, _record(scene), exercise)
    lesson = load_lesson(path)
    assert [ex.step for ex in lesson.exercises] == list(range(1, len(pyramid.triangles) + 1))
    eye = np.asarray(scene.camera.eye, dtype=float)
    for t, ex in enumerate(lesson.exercises):
        assert ex.question == f"Is triangle {t} of the pyramid culled as a back face?"
        # Independent answer: a face is a back face when its outward normal (counter-clockwise
        # corners) points away from the eye, N . (E - P) < 0 (the lecture's test).
        a, b, c = pyramid.vertices[pyramid.triangles[t]]
        back = np.cross(b - a, c - a) @ (eye - a) < 0
        right = [ex.args["choices"][i] for i in right_choices(ex, StepPipelines(lesson.steps[ex.step]))]
        assert right == [bool(back)], t
    assert {True, False} <= {bool(np.cross(b - a, c - a) @ (eye - a) < 0)
                             for a, b, c in pyramid.vertices[pyramid.triangles]}  # both answers occur


def test_a_bad_exercise_is_refused_with_its_field_path_and_the_file_is_left_as_it_was(tmp_path):
    path = tmp_path / "l.json"
    add_step(path, _record(culling_pyramid()))
    before = path.read_bytes()
    bad = {**CULLED, "choices": [True], "fact": {**CULLED["fact"], "object": "teapot"}}
    with pytest.raises(LessonFileError) as caught:
        add_step(path, _record(culling_pyramid()), bad)
    assert "exercises[0].choices: give at least two choices" in caught.value.problems
    assert any(p.startswith("exercises[0].fact (choice 0).object: ") and "teapot" in p
               for p in caught.value.problems), caught.value.problems
    assert path.read_bytes() == before
