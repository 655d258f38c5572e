"""A lesson step's words name what it highlights: the check that finds a mark its words never speak of,
and the whole-word names it and the window's name labels read."""

from core import presets
from core.lessons.facts import check_lesson
from core.lessons.lesson_file import from_dict
from core.lessons.naming import named_objects


def _lesson(text, highlight, scene="frustum_cases", **step):
    return from_dict({"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
                      "steps": [{"title": "Outside", "text": text, "scene": scene,
                                 "panes": ["object order", "scene 3D"], "highlight": highlight, **step}]})


def test_a_highlighted_object_its_words_do_not_name_is_reported_with_lesson_step_and_name():
    # The frustum step outlined the box behind the eye while its words spoke only of "objects
    # entirely outside it".
    lesson = _lesson("Objects entirely outside the frustum are dropped.", {"object": "box"})
    assert check_lesson(lesson) == [  # as lesson check and File → Open lesson say it
        "lesson mine, step 1 'Outside', highlight.object: its words do not name 'box' "
        "(name it, or say that it is marked)"]
    assert check_lesson(_lesson("The box lies outside the frustum.", {"object": "box"})) == []
    assert check_lesson(_lesson("The object marked lies outside.", {"object": "box"})) == []
    # the bounding box of an object is no object named "box"
    assert check_lesson(_lesson("Its bounding box lies outside.", {"object": "box"})) != []


def test_a_highlighted_ray_face_vertex_or_polygon_is_named_by_its_kind_or_its_object():
    rays = {"text": "A ray from the eye.", "scene": "lecture", "pixel": [230, 155]}
    (line,) = check_lesson(_lesson(highlight={"ray": "shadow"}, **rays))
    assert line.endswith("highlight.ray: its words do not speak of the shadow ray "
                         "(name it, or say that it is marked)")
    assert check_lesson(_lesson(highlight={"ray": "primary"}, **rays)) == []
    rays["text"] += " Its shadow ray stops at the cone."
    assert check_lesson(_lesson(highlight={"ray": "shadow"}, **rays)) == []
    face = {"face": {"object": "pyramid", "triangle": 2}}
    assert check_lesson(_lesson("Skipped.", face, scene="culling_pyramid")) != []
    assert check_lesson(_lesson("This face is skipped.", face, scene="culling_pyramid")) == []
    vertex = {"vertex": {"object": "cube", "index": 6}}
    assert check_lesson(_lesson("Parallel rays.", vertex, scene="lecture")) != []
    assert check_lesson(_lesson("Its corner A goes to A′.", vertex, scene="lecture")) == []
    # The z-buffer example draws green, then blue, then yellow (tests/core/lessons/test_lessons.py).
    second = {"highlight": {"polygon_step": 1}, "scene": "zbuffer_three_polygons"}
    (line,) = check_lesson(_lesson("The second polygon comes.", **second))
    assert "its words do not name 'blue', whose polygon is drawn at step 2" in line
    assert check_lesson(_lesson("Blue comes second.", **second)) == []


def test_a_step_names_an_object_by_its_whole_name_and_not_inside_another_word():
    # The frustum example's objects are "sphere" and "box": a sentence about a bounding box or a
    # bounding sphere does not speak of them, nor does "sandbox"; "the cones" speaks of the cone.
    scene = presets.frustum_cases()
    names = [obj.name for obj in scene.objects]
    assert "sphere" in names and "box" in names

    def named(text):
        return [obj.name for obj in named_objects(scene, text)]

    assert named("The bounding box of the sphere lies outside.") == ["sphere"]
    assert named("Its bounding sphere straddles the plane; the box is behind the observer.") == ["box"]
    assert named("A sandbox of spheres.") == ["sphere"]
    assert named("Nothing here.") == []
    lecture = presets.lecture_scene()
    assert [obj.name for obj in named_objects(lecture, "Both cones and the cube's bounding box.")] == [
        "cube", "cone"]
