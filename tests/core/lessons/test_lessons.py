"""Lesson files: the shipped lessons cover the lecture, and broken files say what is wrong where."""

import json
import re
from dataclasses import replace

import mpmath
import numpy as np
import pytest
from brute_force import hit_triangle

from core import presets
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tracing import render_trace
from core.image_order.ray_tree import trace_pixel
from core.lessons.lesson_file import (
    OVERLAYS,
    PANES,
    Lesson,
    LessonFileError,
    LessonStep,
    from_dict,
    load_lesson,
    shipped_lessons,
)
from core.object_order.pipeline import render_raster
from core.presets_trace import PRESETS_TRACE
from core.scene import Material, Scene

LESSONS = shipped_lessons()
BY_ID = {lesson.id: lesson for lesson in LESSONS}


def _figure_number(ref: str) -> int:
    return int(re.match(r"VII\.(\d+)", ref).group(1))


def test_every_shipped_lesson_loads_with_steps_text_and_a_scene():
    assert len(LESSONS) >= 14
    assert len(BY_ID) == len(LESSONS), "lesson ids are unique"
    for lesson in LESSONS:
        assert isinstance(lesson, Lesson) and lesson.title and lesson.summary
        for step in lesson.steps:
            assert isinstance(step, LessonStep)
            assert step.title.strip() and len(step.text.split()) >= 10, (lesson.id, step.title)
            assert isinstance(step.scene, Scene) and step.scene.objects
            assert step.panes and set(step.panes) <= set(PANES)
            assert set(step.overlays) <= set(OVERLAYS)
            assert all(f.count("$") >= 2 for f in step.formulas)
            if step.preset is not None:
                assert step.preset in {**presets.PRESETS, **PRESETS_TRACE}
            if step.pixel is not None:
                assert 0 <= step.pixel[0] < step.scene.camera.width
                assert 0 <= step.pixel[1] < step.scene.camera.height


def test_the_lessons_cover_every_figure_and_question_in_the_lecture_order():
    figures = {_figure_number(f) for lesson in LESSONS for f in lesson.figures}
    assert figures == set(range(1, 15))
    assert {q for lesson in LESSONS for q in lesson.questions} == set(range(1, 7))
    order = [_figure_number(f) for lesson in LESSONS for f in lesson.figures]
    assert order == sorted(order), "lessons follow the lecture's order of figures"
    assert "VII.4a" in BY_ID["back_faces"].figures and "VII.4b" in BY_ID["back_faces"].figures


def test_a_step_keeps_the_previous_steps_scene_and_panes_but_not_its_highlight():
    zbuffer = BY_ID["zbuffer"]
    assert [s.zbuffer_step for s in zbuffer.steps] == [0, 1, 2, 3]
    assert all(s.scene is zbuffer.steps[0].scene and s.panes == zbuffer.steps[0].panes for s in zbuffer.steps)
    assert dict(zbuffer.steps[0].highlight) == {}
    assert [s.highlight["polygon_step"] for s in zbuffer.steps[1:]] == [0, 1, 2]
    names = [o.name for o in zbuffer.steps[0].scene.objects]
    assert names == ["green", "blue", "yellow"]  # drawn in the lecture's order
    observer = BY_ID["observer"]
    assert observer.steps[1].scene.camera.eye == presets.OBSERVER_B.eye  # the camera override moved to B
    assert observer.steps[1].scene.objects == observer.steps[0].scene.objects


def test_the_exercise_lesson_gives_every_number_of_the_solution():
    """Question 6 solved independently with mpmath, compared with what the lesson prints."""
    mpmath.mp.dps = 30
    o, e, c, r = [mpmath.mpf(v) for v in (2, 1, 2)], [10, 6, 6], [6, 4, 6], 10
    d = [e[k] - o[k] for k in range(3)]
    a = sum(x * x for x in d)
    b = 2 * sum(d[k] * (o[k] - c[k]) for k in range(3))
    cc = sum((o[k] - c[k]) ** 2 for k in range(3)) - r * r
    delta = b * b - 4 * a * cc
    t1, t2 = (-b - mpmath.sqrt(delta)) / (2 * a), (-b + mpmath.sqrt(delta)) / (2 * a)
    exit_point = [o[k] + t2 * d[k] for k in range(3)]
    step = BY_ID["ray_sphere"].steps[1]
    shown = " ".join(step.formulas) + " " + step.text
    numbers = {float(x) for x in re.findall(r"-?\d+(?:\.\d+)?", shown)}

    def printed(value, digits=6):
        half_unit = 0.5 * 10 ** (int(mpmath.floor(mpmath.log10(abs(value)))) - digits + 1)
        return any(abs(n - float(value)) <= half_unit for n in numbers)

    for value in (a, b, cc, delta, mpmath.sqrt(delta), t1, t2, *exit_point):
        assert printed(value), f"{mpmath.nstr(value, 8)} not in the lesson"
    assert t1 < 0 and t2 > 1  # both ends inside: no crossing on the segment itself
    assert step.pixel == (80, 60) and step.scene.camera.eye == (2.0, 1.0, 2.0)


def _flat_ids(scene: Scene):
    """Each object drawn in its own flat colour: (H, W) index of the object seen, -1 for none."""
    colors = np.eye(3)[[0, 1, 2, 0, 1, 2, 0, 1, 2]] * np.repeat([1.0, 0.6, 0.3], 3)[:, None]
    objects = tuple(replace(o, material=Material(color=tuple(colors[k]), ambient=0.2, diffuse=0.8))
                    for k, o in enumerate(scene.objects))
    image = render_raster(Scene(camera=scene.camera, objects=objects, background=(1.0, 1.0, 1.0))).color
    ids = np.full(image.shape[:2], -1)
    for k in range(len(objects)):
        ids[np.abs(image - colors[k]).max(-1) < 1e-6] = k
    return ids


def test_observers_a_and_b_see_what_the_lecture_says():
    """Fig. VII.1: from A, 5 is outside and 3 hidden, 1, 2, 4 seen; from B, 5 outside, 1 to 4 seen."""
    lesson = BY_ID["observer"]
    seen = []
    for step in lesson.steps:
        ids = _flat_ids(step.scene)
        names = [o.name for o in step.scene.objects]
        seen.append({names[k] for k in np.unique(ids) if k >= 0})
    assert seen[0] >= {"object 1", "object 2", "object 4"} and not seen[0] & {"object 3", "object 5"}
    assert seen[1] >= {"object 1", "object 2", "object 3", "object 4"} and "object 5" not in seen[1]


def test_the_lecture_scenes_shadows_lie_where_the_observer_sees_the_ground():
    """Ray cast: ground pixels darker with the cube (or the cone) present than with the ground alone."""
    scene = presets.lecture_scene()
    scene = replace(scene, camera=scene.camera.replace(width=160, height=120))
    cube, cone, ground = scene.objects
    ground_seen = _flat_ids(scene) == 2
    settings = TraceSettings(mode="raycast")
    alone = render_trace(replace(scene, objects=(ground,)), settings).color.sum(-1)
    for caster in (cube, cone):
        lit = render_trace(replace(scene, objects=(caster, ground)), settings).color.sum(-1)
        shadow = ground_seen & (lit < alone - 0.1)
        assert shadow.sum() >= 100, f"{caster.name}'s shadow covers only {shadow.sum()} visible ground pixels"


# --- broken files -------------------------------------------------------------

GOOD_STEP = {"title": "t", "text": "some words", "scene": "lecture", "panes": ["object order"]}


def _lesson(**changes):
    d = {"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
         "steps": [GOOD_STEP]}
    d.update(changes)
    return d


def _problems(d) -> list[str]:
    with pytest.raises(LessonFileError) as info:
        from_dict(d)
    return info.value.problems


def test_a_broken_lesson_reports_every_problem_with_its_field_path():
    bad_scene = {"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}
    problems = _problems(_lesson(
        version=2, figures=["VII.15"], questions=[7], summary=3,
        steps=[
            {"title": "a", "text": "b", "scene": "lecture", "panes": ["object order", "zbufer"],
             "pixel": [999, 0]},
            {"title": "a", "text": "b", "scene": bad_scene, "overlays": ["grid"]},
            {"title": "a", "text": "b", "scene": "lectur", "image_order": {"mode": "pathtrace"},
             "objct_order": {}, "formulas": ["no dollars"]},
        ]))
    expected = [
        "version: unsupported version 2",
        "figures[0]: expected a lecture figure VII.1 to VII.14",
        "questions[0]: the lecture has questions 1 to 6, got 7",
        "summary: expected a string, got 3",
        "steps[0].panes[1]: unknown pane 'zbufer'",
        "steps[0].pixel: pixel (999, 0) lies outside the 320 x 240 image",
        "steps[1].scene.objects[0].radius: must be > 0, got -1",
        "steps[2].scene: unknown preset 'lectur' (did you mean 'lecture'?)",
        "steps[1].overlays[0]: unknown overlay 'grid'",
        "steps[2].objct_order: unknown field 'objct_order' (did you mean 'object_order'?)",
        "steps[2].formulas[0]: a formula is mathtext between $ signs",
        "steps[2].image_order: mode must be one of",
    ]
    for start in expected:
        assert any(p.startswith(start) for p in problems), (start, problems)


def test_a_steps_framing_is_the_scene_unless_it_says_highlight_and_carries_on_to_the_next_step():
    lesson = from_dict(_lesson(steps=[GOOD_STEP, {**GOOD_STEP, "frame": "highlight"},
                                      {"title": "c", "text": "d"}]))
    assert [step.frame for step in lesson.steps] == ["scene", "highlight", "highlight"]
    problems = _problems(_lesson(steps=[{**GOOD_STEP, "frame": "highlights"}]))
    assert problems[0].startswith("steps[0].frame: unknown framing 'highlights' (did you mean 'highlight'?)")


def test_a_first_step_must_name_its_scene_and_panes_and_objects_must_exist():
    problems = _problems(_lesson(steps=[{"title": "a", "text": "b"}]))
    assert "steps[0].scene: required field is missing" in problems
    assert "steps[0].panes: required field is missing" in problems
    vertex = {"vertex": {"object": "cube", "index": 99}}
    problems = _problems(_lesson(steps=[{**GOOD_STEP, "highlight": vertex}]))
    assert problems == ["steps[0].highlight.vertex.index: must be in [0, 7] ('cube' has 8), got 99"]
    face = {"face": {"object": "teapot", "triangle": 0}}
    problems = _problems(_lesson(steps=[{**GOOD_STEP, "highlight": face}]))
    assert problems == ["steps[0].highlight.face.object: "
                        "no object 'teapot' in the scene (objects: cube, cone, ground)"]
    problems = _problems(_lesson(steps=[{**GOOD_STEP, "camera": {"fov_y_deg": "wide"}}]))
    assert problems == ['steps[0].camera.fov_y_deg: expected a number, got "wide"']


def test_a_highlight_and_a_fact_naming_a_part_of_an_analytic_sphere_get_the_same_message():
    ball = {"objects": [{"type": "sphere", "name": "ball", "center": [0, 0, -5], "radius": 1}]}
    step = {**GOOD_STEP, "scene": ball,
            "highlight": {"face": {"object": "ball", "triangle": 0},
                          "vertex": {"object": "ball", "index": 2}},
            "facts": [{"fact": "projects_to", "object": "ball", "vertex": 2, "pixel": [0, 0]}]}
    assert _problems(_lesson(steps=[step])) == [
        "steps[0].highlight.face.triangle: 'ball' is an analytic sphere: it has no triangles",
        "steps[0].highlight.vertex.index: 'ball' is an analytic sphere: it has no vertices",
        "steps[0].facts[0].vertex: 'ball' is an analytic sphere: it has no vertices",
    ]


def test_broken_files_name_the_file_and_the_place(tmp_path):
    path = tmp_path / "lesson.json"
    path.write_text('{"format": "render-explorer-lesson",\n "version": 1,,}', encoding="utf-8")
    with pytest.raises(LessonFileError, match=r"lesson file .*lesson.json: line 2, column 15: invalid JSON"):
        load_lesson(path)
    with pytest.raises(LessonFileError, match="file not found"):
        load_lesson(tmp_path / "missing.json")
    path.write_bytes(b"\xff\xfe\x00garbage")
    with pytest.raises(LessonFileError, match="not a text file"):
        load_lesson(path)
    path.write_text("[" * 100_000, encoding="utf-8")
    with pytest.raises(LessonFileError, match="nested too deeply|invalid JSON"):
        load_lesson(path)
    path.write_text(json.dumps(_lesson()), encoding="utf-8")
    assert load_lesson(path).path == path


def test_the_ray_casting_lessons_pixel_lies_in_the_cones_shadow():
    step = BY_ID["ray_casting"].steps[1]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    assert root.hit_name == "ground"
    shadow = [c for c in root.children if c.kind == "shadow"]
    assert len(shadow) == 1 and shadow[0].hit_name == "cone"


def test_steps_and_highlighted_polygons_exist_in_the_drawing_order():
    for lesson in LESSONS:
        for step in lesson.steps:
            polygon = step.highlight.get("polygon_step")
            if step.zbuffer_step is None and polygon is None:
                continue
            drawn = len(render_raster(step.scene, replace(step.object_order, record_steps=True)).draw)
            assert (step.zbuffer_step or 0) <= drawn, (lesson.id, step.title, drawn)
            assert polygon is None or polygon < drawn, (lesson.id, step.title, drawn)


def test_the_culling_lesson_highlights_a_culled_face_then_a_front_face_of_the_notch():
    convex, notched = BY_ID["back_faces"].steps
    for step, visible in ((convex, False), (notched, True)):
        face = step.highlight["face"]
        index = [o.name for o in step.scene.objects].index(face["object"])
        result = render_raster(step.scene, step.object_order)
        assert result.faces.visible[result.face_index(index, face["triangle"])] == visible
    prism = notched.scene.objects[0]
    corners = prism.vertices[prism.triangles[notched.highlight["face"]["triangle"]]]
    normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    assert np.allclose(normal / np.linalg.norm(normal), (0, 0, 1))  # the notch's inner wall facing +z


def test_the_notch_step_shows_its_highlighted_wall_and_normal_in_the_3d_pane():
    # At 1920x1080 the pane's own framing looked at the prism from behind: the outlined wall and its
    # normal N were hidden by the solid itself and only the label "N: front face" showed.  The step's
    # viewpoint must see the wall's front side, and the line of sight to the wall's centre (where N
    # starts) must cross no other triangle of the prism (brute-force ray-triangle tests).
    notched = BY_ID["back_faces"].steps[1]
    assert notched.view, "the step sets the 3D pane's viewpoint"
    eye = np.asarray(notched.view["position"], dtype=float)
    prism = notched.scene.objects[0]
    wall = notched.highlight["face"]["triangle"]
    corners = prism.vertices[prism.triangles[wall]]
    centre = corners.mean(axis=0)
    normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    assert normal @ (eye - centre) > 0, "the viewpoint is on the wall's front side"
    sight = (centre - eye)[None, :]  # t = 1 at the wall's centre
    for k, (a, b, c) in enumerate(prism.vertices[prism.triangles]):
        if k != wall:
            assert hit_triangle(eye[None, :], sight, a, b, c)[0] >= 1 - 1e-9, k


def test_top_level_text_fields_are_checked_too():
    problems = _problems(_lesson(title="  ", id="has space", format="render-explorer-lessons"))
    assert problems == ['format: expected "render-explorer-lesson", got "render-explorer-lessons"',
                        "id: use letters, digits, '_' and '-' only, got \"has space\"",
                        "title: must not be empty"]
    # A scene's format says what the file is, and nothing more (tests/core/files/test_lesson_reader.py).
    assert _problems(_lesson(title="  ", format="render-explorer-scene")) == [
        'format: this is a scene file ("render-explorer-scene"), not a lesson file']
    assert _problems([1, 2]) == ["top level: expected an object {...}, got [1, 2]"]
    assert _problems(_lesson(steps=[])) == ["steps: a lesson needs at least one step"]
