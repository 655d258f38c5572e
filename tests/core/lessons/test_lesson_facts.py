"""Lesson facts: a step's claims are decided by the pipelines, and a false one is caught."""

import copy
import json
import re
import subprocess
import sys

import numpy as np
import pytest
from checkout import ROOT

from core.lessons.facts import check_lesson
from core.lessons.lesson_file import FILES, LessonFileError, from_dict, load_lesson, shipped_lessons

LESSONS = shipped_lessons()
BY_ID = {lesson.id: lesson for lesson in LESSONS}
SEGMENT = {"origin": [2, 1, 2], "end": [10, 6, 6], "center": [6, 4, 6], "radius": 10}


def _lesson(facts, scene="frustum_cases", **step):
    return {"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
            "steps": [{"title": "one", "text": "words", "scene": scene, "panes": ["object order"],
                       "facts": facts, **step}]}


def test_every_shipped_lesson_states_facts_and_they_all_hold():
    stated = [(lesson.id, k) for lesson in LESSONS for k, step in enumerate(lesson.steps) if step.facts]
    steps = sum(len(lesson.steps) for lesson in LESSONS)
    assert len(stated) >= steps - 2  # all but the two whose text claims nothing a fact can state
    for lesson in LESSONS:
        assert check_lesson(lesson) == [], lesson.id


def test_a_false_fact_is_reported_with_lesson_step_fact_and_what_was_computed():
    # The box stands at (7.5, 0.6, 12), behind the default eye (6, 4, 9) that looks toward (0, 0.8, 0):
    # (box - eye) . (target - eye) = 1.5 * -6 + -3.4 * -3.2 + 3 * -9 = -25.12 < 0, so it is outside.
    eye, target, box = np.array([6, 4, 9.0]), np.array([0, 0.8, 0]), np.array([7.5, 0.6, 12])
    assert np.dot(box - eye, target - eye) < 0
    lesson = from_dict(_lesson([{"fact": "frustum", "object": "box", "is": "inside"},
                                {"fact": "frustum", "object": "box", "is": "outside"}]))
    (line,) = check_lesson(lesson)
    said, computed = line.split("): computed ")
    assert said == ("lesson mine, step 1 'one', steps[0].facts[0] ('box' is inside the "
                    "frustum")
    assert computed.startswith("'box' is outside the frustum, beyond its ")
    assert line.endswith(" near planes")  # behind the eye (below), and beyond side planes too


def test_an_object_outside_the_frustum_lies_beyond_the_plane_the_fact_names_and_no_other():
    # The box's centre lies (box - eye) . axis = -25.12 / |target - eye| = -2.23 along the view axis
    # (the sums above), its bounding sphere's radius is 1.2 √3 / 2 = 1.04: wholly behind the eye, so
    # beyond the near plane (1 in front of it) and on the near side of the far one (30).
    eye, target, box = np.array([6, 4, 9.0]), np.array([0, 0.8, 0]), np.array([7.5, 0.6, 12])
    along = np.dot(box - eye, (target - eye) / np.linalg.norm(target - eye))
    radius = 0.6 * np.sqrt(3)
    assert along + radius < 0 < along - radius + 30
    fact = {"fact": "frustum", "object": "box", "is": "outside"}
    assert check_lesson(from_dict(_lesson([{**fact, "beyond": "near"}]))) == []
    (line,) = check_lesson(from_dict(_lesson([{**fact, "beyond": "far"}])))
    said, computed = line.split("): computed ")
    assert said.endswith("('box' is outside the frustum, beyond its far plane")
    assert computed.startswith("'box' is outside the frustum, beyond its ")
    assert "near" in computed and "far" not in computed


def test_observer_b_sees_object_5_off_to_its_left():
    """The observer lesson's second step says object 5 is "off to the observer's left": its bounding
    sphere lies wholly beyond the left side of B's viewing pyramid, worked out here from B's camera."""
    step = BY_ID["observer"].steps[1]
    assert "off to the observer's left" in step.text
    camera, (obj,) = step.scene.camera, [o for o in step.scene.objects if o.name == "object 5"]
    eye = np.asarray(camera.eye, float)
    forward = np.asarray(camera.target, float) - eye
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, camera.up)
    right /= np.linalg.norm(right)
    half = np.arctan(np.tan(np.radians(camera.fov_y_deg) / 2) * camera.width / camera.height)
    inward = np.cos(half) * right + np.sin(half) * forward  # the left side's inward normal
    corners = obj.vertices
    centre = (corners.min(axis=0) + corners.max(axis=0)) / 2
    assert np.dot(corners - eye, inward).max() < 0  # every corner beyond the left side
    assert np.dot(centre - eye, right) < 0
    fact = next(f for f in step.facts if f.kind == "frustum" and f.args["object"] == "object 5")
    assert fact.args["beyond"] == "left"
    wrong = {"fact": "frustum", "object": "object 5", "is": "outside", "beyond": "right"}
    lesson = from_dict(_lesson([wrong], scene="observers_top_view",
                               camera={"eye": list(camera.eye), "target": list(camera.target)}))
    (line,) = check_lesson(lesson)
    assert line.split("): computed ")[1].startswith("'object 5' is outside the frustum, beyond its left")


def test_the_lectures_numbers_are_facts_of_the_worked_intersection():
    # i, j, k = 8, 5, 4: a = 64 + 25 + 16 = 105; b = 2 (8 (2-6) + 5 (1-4) + 4 (2-6)) = -126;
    # c = 16 + 9 + 16 - 100 = -59; Δ = 126² + 4·105·59 = 40656.
    right = [{"fact": "ray_sphere", **SEGMENT, "value": v, "equals": x}
             for v, x in (("a", 105), ("b", -126), ("c", -59), ("hit", False))]
    right.append({"fact": "ray_sphere", **SEGMENT, "value": "discriminant", "equals": 40656,
                  "tolerance": 1e-8})
    assert check_lesson(from_dict(_lesson(right))) == []
    wrong = [{"fact": "ray_sphere", **SEGMENT, "value": "a", "equals": 1}]
    (line,) = check_lesson(from_dict(_lesson(wrong)))
    assert line.endswith("computed a = 105")


def test_z_buffer_facts_follow_the_drawing_order():
    # Pixel (80, 60) is the image centre, the ray along the axis x = y = 0.  There green's plane
    # (through (-2,-1.4,-1.5), (1.2,-1.4,-0.5), (-0.6,1.6,-1)) has z = -0.97, blue's z = 0.84 and
    # yellow's z = 0.01 (solved by hand from their corners): blue is nearest, then yellow, then green.
    facts = [{"fact": "zbuffer_keeps", "pixel": [80, 60], "object": "green", "after": 1},
             {"fact": "zbuffer_keeps", "pixel": [80, 60], "object": "blue", "after": 2},
             {"fact": "zbuffer_keeps", "pixel": [80, 60], "object": "blue", "after": 3},
             {"fact": "ztest_fails", "pixel": [80, 60], "object": "yellow", "after": 3},
             {"fact": "ztest_fails", "pixel": [80, 60], "object": "blue", "is": False},
             {"fact": "zbuffer_keeps", "pixel": [0, 0], "object": None}]
    assert check_lesson(from_dict(_lesson(facts, scene="zbuffer_three_polygons"))) == []
    (line,) = check_lesson(from_dict(_lesson(
        [{"fact": "zbuffer_keeps", "pixel": [80, 60], "object": "yellow"}], scene="zbuffer_three_polygons")))
    assert "computed after 3 polygons it keeps triangle 0 of 'blue'" in line


def test_bad_facts_are_refused_with_their_field_path():
    facts = [{"fact": "frustum", "object": "nobody", "is": "outside"},
             {"fact": "frustum", "object": "cube", "is": "half"},
             {"fact": "zbuffer_keeps", "pixel": [9999, 0], "object": "cube"},
             {"fact": "clipped", "object": "ground", "plane": "front"},
             {"fact": "telepathy"},
             {"fact": "ray_sphere", "origin": [0, 0, 0], "center": [0, 0, 0], "radius": 1,
              "value": "a", "equals": 1},
             {"fact": "frustum", "object": "cube", "is": "inside", "beyond": "left"},
             {"fact": "frustum", "object": "box", "is": "outside", "beyond": "behind"}]
    with pytest.raises(LessonFileError) as info:
        from_dict(_lesson(facts))
    problems = info.value.problems
    assert problems[0].startswith("steps[0].facts[0].object: no object 'nobody' in the scene")
    assert problems[1].startswith("steps[0].facts[1].is: unknown frustum state 'half'")
    assert problems[2].startswith("steps[0].facts[2].pixel: pixel (9999, 0) lies outside")
    assert problems[3].startswith("steps[0].facts[3].plane: unknown plane 'front'")
    assert problems[4].startswith('steps[0].facts[4].fact: unknown fact "telepathy"')
    assert problems[5].startswith('steps[0].facts[5]: give either "end"')
    assert problems[6].startswith("steps[0].facts[6].beyond: only an object outside the frustum lies beyond")
    assert problems[7].startswith("steps[0].facts[7].beyond: unknown plane 'behind'")
    assert len(problems) == 8


def test_a_stage_that_changes_no_pixel_and_one_that_does():
    # A convex solid's front faces never overlap on the screen, so with back faces culled the z-test
    # decides nothing (Fig. VII.4a); the L-shaped prism's arm hides part of its notch's wall, so
    # without the z-test the wall, drawn later, shows through (Fig. VII.4b).
    no_z = {"fact": "changes_picture", "stage": "z_test", "is": False}
    convex = from_dict(_lesson([no_z, {**no_z, "stage": "back_face_culling"}], scene="culling_pyramid"))
    assert check_lesson(convex) == []
    (line,) = check_lesson(from_dict(_lesson([no_z], scene="culling_notched")))
    assert "steps[0].facts[0] (switching z_test does not change the object-order image): computed switched " \
           "off, " in line and line.endswith((" pixels differ", " pixel differs"))
    assert check_lesson(from_dict(_lesson([{"fact": "changes_picture", "stage": "z_test"}],
                                          scene="culling_notched"))) == []
    with pytest.raises(LessonFileError) as info:
        from_dict(_lesson([{"fact": "changes_picture", "stage": "painter"}]))
    assert info.value.problems[0].startswith("steps[0].facts[0].stage: unknown stage 'painter'")


def _run_check(*files) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "app", "lesson", "check", *map(str, files)],
                          cwd=ROOT, capture_output=True, text=True, encoding="utf-8", timeout=600)


def test_lesson_check_passes_on_the_shipped_lessons_fails_on_a_false_fact_and_refuses_a_bad_file(tmp_path):
    out = _run_check(*sorted(FILES.glob("*.json")))
    assert out.returncode == 0, out.stdout + out.stderr
    assert "all" in out.stdout and "facts hold" in out.stdout

    # The observer lesson with its first fact turned false: object 5 "inside" the frustum.
    data = json.loads((FILES / "02_observer.json").read_text(encoding="utf-8"))
    false = copy.deepcopy(data)
    first = false["steps"][0]["facts"][0]
    assert first["fact"] == "frustum" and first["object"] == "object 5" and first["is"] == "outside"
    first["is"] = "inside"
    lying = tmp_path / "lying.json"
    lying.write_text(json.dumps(false), encoding="utf-8")
    out = _run_check(lying)
    assert out.returncode == 1
    (line,) = out.stdout.splitlines()
    assert line.startswith(f"{lying}: lesson observer, step 1 'Observer A', steps[0].facts[0]")
    assert "computed 'object 5' is outside the frustum, beyond its " in line

    broken = tmp_path / "broken.json"
    broken.write_text("{not json", encoding="utf-8")
    out = _run_check(broken, FILES / "05_zbuffer.json")
    assert out.returncode == 2
    assert "broken.json" in out.stderr and "invalid JSON" in out.stderr and "Traceback" not in out.stderr
    assert load_lesson(FILES / "05_zbuffer.json").steps  # the other file was still checked: no line for it
    assert out.stdout == ""


def test_lesson_check_in_a_process_reports_an_unnamed_highlight_and_an_unstated_number_and_a_bad_stage(
        tmp_path):
    # The frustum lesson with the words that hid its marked box (and a number no fact states): exit 1,
    # one line each; a changes_picture fact naming no stage: exit 2, the field's path, no traceback.
    data = json.loads((FILES / "03_frustum.json").read_text(encoding="utf-8"))
    step = data["steps"][1]
    step["text"] = step["text"].replace("like the one marked on the eye's side of the front plane, ", "")
    step["text"] += " The end plane lies 16.5 units away."
    words = tmp_path / "words.json"
    words.write_text(json.dumps(data), encoding="utf-8")
    out = _run_check(words)
    assert out.returncode == 1 and "Traceback" not in out.stderr
    lines = out.stdout.splitlines()
    assert len(lines) == 2
    assert "highlight.object: its words do not name 'box'" in lines[0]
    assert lines[1].endswith("no fact states 16.5 (add a fact that does, or leave the number out)")
    step["facts"].append({"fact": "changes_picture", "stage": "painter"})
    words.write_text(json.dumps(data), encoding="utf-8")
    out = _run_check(words)
    assert out.returncode == 2 and out.stdout == "" and "Traceback" not in out.stderr
    assert "steps[1].facts[8].stage: unknown stage 'painter'" in out.stderr


def test_lesson_check_in_a_process_refuses_the_new_facts_fields_written_wrong_and_names_them(tmp_path):
    # The first lesson with its same_surfaces fact given "is": "maybe" and its primitive_tests fact a
    # count of -1: exit 2, each field's path, no traceback, nothing on standard output.
    data = json.loads((FILES / "01_two_orders.json").read_text(encoding="utf-8"))
    facts = data["steps"][0]["facts"]
    k = next(i for i, f in enumerate(facts) if f["fact"] == "same_surfaces")
    facts[k]["is"] = "maybe"
    tests = data["steps"][1]["facts"]
    j = next(i for i, f in enumerate(tests) if f["fact"] == "primitive_tests")
    tests[j]["count"] = -1
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(data), encoding="utf-8")
    out = _run_check(bad)
    assert out.returncode == 2 and out.stdout == "" and "Traceback" not in out.stderr
    assert f"steps[0].facts[{k}].is: expected true or false, got \"maybe\"" in out.stderr
    assert f"steps[1].facts[{j}].count: must be >= 0, got -1" in out.stderr


def test_no_bounding_sphere_shown_by_a_lesson_swamps_the_scene():
    """A step that shows bounding spheres keeps each well inside the scene's extent (a ground
    plane's sphere, as wide as the ground, once filled the 3D pane)."""
    from core.object_order.pipeline import object_mesh

    for lesson in LESSONS:
        for step in lesson.steps:
            if "bounding spheres" not in step.overlays:
                continue
            points = np.vstack([np.asarray(object_mesh(o).vertices) for o in step.scene.objects])
            diagonal = float(np.linalg.norm(points.max(axis=0) - points.min(axis=0)))
            radii = [o.bounding_sphere()[1] for o in step.scene.objects]
            assert max(radii) < diagonal / 3, (lesson.id, step.title, max(radii), diagonal)


def test_drawn_in_the_other_order_draws_blue_first_and_ends_with_the_same_picture():
    from dataclasses import replace

    from core.object_order.pipeline import render_raster

    first, other, final = BY_ID["zbuffer_piercing"].steps
    assert "other order" in other.title
    pictures = []
    for step in (first, final):
        result = render_raster(step.scene, replace(step.object_order, record_steps=True))
        names = [step.scene.objects[k].name for k in result.draw.object_index]
        pictures.append((names, result.color))
    assert pictures[0][0] == ["green", "blue"] and pictures[1][0] == ["blue", "green"]
    assert np.array_equal(pictures[0][1], pictures[1][1])  # pixel for pixel, as the text says
    assert other.highlight["polygon_step"] == 0 and other.zbuffer_step == 1  # blue alone first


def test_only_steps_showing_an_image_order_pane_speak_of_shadows():
    """Object order draws no shadows (they come with the next lecture's shading)."""
    for lesson in LESSONS:
        for step in lesson.steps:
            if "shadow" in step.text.lower():
                assert "image order" in step.panes, (lesson.id, step.title)


def test_a_step_whose_words_give_t_gives_the_t_its_picked_pixels_ray_shows():
    """The ray tree, the Worked math and the verdict above them show a step's picked pixel's ray, which
    runs along a direction of length 1; a step that works a crossing with another direction (the
    lecture's d = (−0.5, −0.3, −6)) and wrote only that t (1.00642) told the student a t the window did
    not show (6.06696). Every step that writes t for its picked pixel also writes the window's, and the
    verdict writes it with the same digits (it wrote "t = 16" where the step wrote 15.9869)."""
    from core.image_order.ray_tree import trace_pixel
    from core.lessons.numbers_said import writes, written_numbers
    from core.pixel_verdict import trace_verdict

    checked = []
    for lesson in LESSONS:
        for k, step in enumerate(lesson.steps):
            said = re.findall(r"\bt ≈ ([-−]?\d+\.\d+)", step.text)
            if step.pixel is None or not said:
                continue
            root = trace_pixel(step.scene, *step.pixel, step.image_order)
            assert any(writes(n, places, root.t, 0.5 * 10.0 ** -places)
                       for n, places in written_numbers(" ".join(said))), (lesson.id, k, said, root.t)
            verdict = trace_verdict(root, step.scene, step.image_order.mode, *step.pixel).sentence
            assert re.search(r"at t = ([\d.]+)", verdict).group(1) in said, (lesson.id, k, verdict, said)
            checked.append(lesson.id)
    assert checked == ["ray_sphere", "ray_triangle"]


def test_the_two_orders_find_the_same_surfaces_on_flat_faces_and_not_on_a_true_sphere():
    # The lecture scene is all flat faces: the z-buffer and the first hit find the same plane, so
    # the same depth, at every pixel (tests/core/test_compare.py works that out by brute force).  A
    # sphere is drawn as facets inscribed in it: where it shows, the z-buffer's depth is nearer.
    same = {"fact": "same_surfaces"}
    assert check_lesson(from_dict(_lesson([same], scene="lecture"))) == []
    assert check_lesson(from_dict(_lesson([{**same, "is": False}], scene="lone_sphere"))) == []
    (line,) = check_lesson(from_dict(_lesson([same], scene="lone_sphere")))
    assert "(object order and image order find the same surface at every pixel): computed they find " \
           "different surfaces at " in line
