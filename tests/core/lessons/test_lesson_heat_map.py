"""The heat map in lessons: a step turns it on, and its facts compare the tests a pixel costs, or
count one ray's."""

import pytest
from verdict_scenes import _down

from core.files import scene_file
from core.lessons.facts import check_lesson
from core.lessons.lesson_file import LessonFileError, from_dict, shipped_lessons
from core.scene import Scene
from core.shapes import box


def _box_lesson(facts, **step):
    """One step over a 12-triangle box seen from straight above, ray cast, with no light: with no
    acceleration each pixel's one ray (no shadow ray, no secondary ray) tests all 12 triangles, so
    the mean is exactly 12 a pixel; with bounding spheres the rays that miss the box's sphere (radius
    sqrt(3), while the image is about 2 x 9 tan 20 deg = 6.6 wide at the box) test none."""
    scene = Scene(camera=_down(), objects=(box((0, 0, 0), 2.0, name="box"),))
    return {"format": "render-explorer-lesson", "version": 1, "id": "heat", "title": "Heat",
            "steps": [{"title": "one", "text": "words", "scene": scene_file.to_dict(scene),
                       "panes": ["image order"], "image_order": {"mode": "raycast"}, "facts": facts, **step},
                      {"title": "two", "text": "more words"}]}


def test_the_acceleration_lesson_shows_the_heat_map_and_states_bvh_below_grid_below_none():
    lesson = next(lesson for lesson in shipped_lessons() if lesson.id == "acceleration")
    (step,) = [s for s in lesson.steps if s.heat_map != "off"]
    assert step.heat_map == "primitive tests" and step.panes[0] == "image order"
    stated = {(f.args["accel"], f.args["fewer_than"]) for f in step.facts if f.kind == "tests_per_pixel"}
    assert stated == {("bvh", "grid"), ("grid", "none")}
    assert check_lesson(lesson) == []


def test_tests_per_pixel_holds_when_fewer_and_reports_the_means_when_not():
    right = [{"fact": "tests_per_pixel", "accel": "spheres", "fewer_than": "none"},
             {"fact": "tests_per_pixel", "accel": "none", "fewer_than": "spheres", "is": False}]
    assert check_lesson(from_dict(_box_lesson(right))) == []
    wrong = [{"fact": "tests_per_pixel", "accel": "none", "fewer_than": "spheres",
              "tests": "primitive tests"}]
    (line,) = check_lesson(from_dict(_box_lesson(wrong)))
    assert "(none costs fewer primitive tests a pixel than spheres): computed none 12, spheres " in line
    # No acceleration tests no box or sphere at all, while the grid's cells walked are its box
    # tests (every ray that meets the box enters one): none's 0 a pixel is the fewer.
    cells = [{"fact": "tests_per_pixel", "accel": "none", "fewer_than": "grid",
              "tests": "box and sphere tests"}]
    assert check_lesson(from_dict(_box_lesson(cells))) == []
    wrong = [{"fact": "tests_per_pixel", "accel": "grid", "fewer_than": "none",
              "tests": "box and sphere tests"}]
    (line,) = check_lesson(from_dict(_box_lesson(wrong)))
    assert "computed grid " in line and line.endswith(", none 0 box and sphere tests a pixel")


def test_primitive_tests_counts_every_triangle_with_no_acceleration_and_none_where_the_sphere_says_miss():
    # The box is 12 triangles.  The camera looks straight down: the middle pixel's ray meets the
    # box, the corner's passes about 3 units from its centre, outside its sphere (radius sqrt(3)).
    scene = from_dict(_box_lesson([])).steps[0].scene
    (box_mesh,) = scene.objects
    every = len(box_mesh.triangles)
    middle, corner = [scene.camera.width // 2, scene.camera.height // 2], [0, 0]
    none = [{"fact": "primitive_tests", "pixel": pixel, "count": every} for pixel in (middle, corner)]
    assert check_lesson(from_dict(_box_lesson(none, image_order={"mode": "raycast", "accel": "none"}))) == []
    spheres = [{"fact": "primitive_tests", "pixel": corner, "count": 0},
               {"fact": "primitive_tests", "pixel": middle, "count": every}]
    culled = {"mode": "raycast", "accel": "spheres"}
    assert check_lesson(from_dict(_box_lesson(spheres, image_order=culled))) == []
    wrong = [{"fact": "primitive_tests", "pixel": corner, "count": 1}]
    (line,) = check_lesson(from_dict(_box_lesson(wrong, image_order={"mode": "raycast", "accel": "none"})))
    assert line.endswith(f"(the ray through pixel (0, 0) makes 1 primitive test): computed {every} "
                         "primitive tests")


def test_a_steps_heat_map_carries_to_the_next_step_and_is_off_unless_given():
    on = from_dict(_box_lesson([], heat_map="box and sphere tests"))
    assert [s.heat_map for s in on.steps] == ["box and sphere tests"] * 2
    assert [s.heat_map for s in from_dict(_box_lesson([])).steps] == ["off", "off"]


@pytest.mark.parametrize("step, message", [
    ({"heat_map": "primitive"},
     "steps[0].heat_map: unknown heat map 'primitive' (did you mean 'primitive tests'?)"),
    ({"heat_map": 1}, "steps[0].heat_map: expected a string, got 1"),
    ({"facts": [{"fact": "tests_per_pixel", "accel": "octree", "fewer_than": "none"}]},
     "steps[0].facts[0].accel: unknown acceleration method 'octree'"),
    ({"facts": [{"fact": "tests_per_pixel", "accel": "bvh", "fewer_than": "grid", "tests": "cells"}]},
     "steps[0].facts[0].tests: unknown count 'cells'"),
    ({"facts": [{"fact": "tests_per_pixel", "accel": "bvh"}]},
     "steps[0].facts[0].fewer_than: required field is missing"),
])
def test_a_bad_heat_map_or_tests_fact_is_refused_with_its_field_path(step, message):
    with pytest.raises(LessonFileError) as err:
        from_dict(_box_lesson(**{"facts": [], **step}))
    assert any(p.startswith(message) for p in err.value.problems), err.value.problems
