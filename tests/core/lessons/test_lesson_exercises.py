"""Exercises: every shipped one is answerable by the pipelines; answers are judged against
independent computations, and a wrong answer is refused."""

import json
import math
import re
from fractions import Fraction

import numpy as np
import pytest
from brute_force import exact_triangle_solve

from core.lessons.exercises import (
    HEAT_MAP,
    PICTURES,
    RESULTS,
    a_right_pixel,
    check_exercises,
    judge,
    number,
    right_choices,
    withheld,
)
from core.lessons.facts import StepPipelines
from core.lessons.lesson_file import FILES as LESSON_FILES
from core.lessons.lesson_file import LessonFileError, from_dict, shipped_lessons

LESSONS = shipped_lessons()
BY_ID = {lesson.id: lesson for lesson in LESSONS}


def _exercise(lesson_id, question_start):
    lesson = BY_ID[lesson_id]
    ex = next(e for e in lesson.exercises if e.question.startswith(question_start))
    return ex, StepPipelines(lesson.steps[ex.step])


def test_every_lesson_ends_with_exercises_the_pipelines_answer():
    assert all(lesson.exercises for lesson in LESSONS)
    assert sum(len(lesson.exercises) for lesson in LESSONS) >= 30
    kinds = {ex.kind for lesson in LESSONS for ex in lesson.exercises}
    assert kinds == {"choose_one", "click_pixel", "number", "order", "pick_picture"}
    for lesson in LESSONS:
        assert check_exercises(lesson) == [], lesson.id


def _segment_solution(origin, end, centre, radius):
    """Question 6's quantities for a segment, in exact arithmetic: a, b, c, Δ, t1, t2, the first
    crossing's root and its x (Δ a perfect square, so the roots are fractions)."""
    d = [Fraction(e) - o for e, o in zip(end, origin, strict=True)]
    f = [Fraction(o) - c for o, c in zip(origin, centre, strict=True)]
    a = sum(v * v for v in d)
    b = 2 * sum(u * v for u, v in zip(f, d, strict=True))
    c = sum(v * v for v in f) - Fraction(radius) ** 2
    delta = b * b - 4 * a * c
    root = math.isqrt(int(delta))
    assert root * root == delta  # chosen so that a student can take the root by hand
    t1, t2 = (-b - root) / (2 * a), (-b + root) / (2 * a)
    first = t2 if c < 0 else t1  # inside (c < 0): t1 lies behind the start
    return {"a": a, "b": b, "c": c, "Δ": delta, "t1": t1, "t2": t2, "first": first,
            "x": origin[0] + d[0] * first}


def test_your_segment_every_number_of_its_solution():
    # By hand, the first segment: (4, 3, 5) to (3, 2, 3), centre (1, 8, 5), r = 6.  (i, j, k) =
    # (-1, -1, -2), a = 1 + 1 + 4 = 6; start minus centre (3, -5, 0), b = 2(-3 + 5 + 0) = 4,
    # c = 9 + 25 + 0 - 36 = -2; Δ = 16 + 48 = 64; t = (-4 ∓ 8) / 12 = -1, 1/3.  The start is inside
    # (c < 0), so the ray leaves at t2 = 1/3, x = 4 - 1/3 = 11/3, and the segment crosses (t2 ≤ 1).
    assert _segment_solution((4, 3, 5), (3, 2, 3), (1, 8, 5), 6) == {
        "a": 6, "b": 4, "c": -2, "Δ": 64, "t1": -1, "t2": Fraction(1, 3), "first": Fraction(1, 3),
        "x": Fraction(11, 3)}
    segment = _segment_questions()
    asked = ["a", "b", "c", "Δ", "t1", "t2", None, None, "x"]
    assert len(segment) == len(asked)
    lecture = 0
    for k in range(4):
        drawn = [ex.variants[k] for ex in segment]
        f = drawn[6].args["fact"]
        solved = _segment_solution(f["origin"], f["end"], f["center"], f["radius"])
        lecture += list(f["origin"]) == [2, 1, 2]
        p = StepPipelines(BY_ID["ray_sphere"].steps[drawn[0].step])
        for ex, key in zip(drawn, asked, strict=True):
            assert ex.question.count(_shown(f["origin"])) <= 1
            if key is None:
                continue
            value = float(solved[key])
            assert judge(ex, p, value).right, (k, key)
            assert not judge(ex, p, value + 2 * ex.args["tolerance"] + 0.01).right, (k, key)
        crosses = 0 <= solved["t1"] <= 1 or 0 <= solved["t2"] <= 1
        assert [drawn[6].args["choices"][i] for i in right_choices(drawn[6], p)] == [crosses]
        first = "t_far" if solved["c"] < 0 else "t_near"
        assert judge(drawn[7], p, drawn[7].args["choices"].index(first)).right
        wrong = judge(drawn[7], p, 1 - drawn[7].args["choices"].index(first))
        assert not wrong.right and wrong.sentence.endswith("is not the answer.")
    assert lecture == 0  # the lecture's own segment, worked in the step, is asked of no one


def _segment_questions():
    """The ray–sphere lesson's questions about one segment each student draws (its exercises that
    share a draw; the lesson's first step asks one of its own)."""
    lesson = BY_ID["ray_sphere"]
    return [ex for ex in lesson.exercises if ex.draw and ex.draw == lesson.exercises[0].draw]


def _shown(v):
    """A point as the questions write it, e.g. ``(4, 3, 5)``."""
    return "(" + ", ".join(f"{x:g}" for x in v) + ")"


def test_one_draw_gives_a_student_one_segment_for_every_question():
    from core.lessons.exercises import variant

    lesson = BY_ID["ray_sphere"]
    segment = _segment_questions()
    for seed in range(30):
        drawn = [variant(ex, seed, lesson.exercises.index(ex)) for ex in segment]
        segments = {(tuple(d.args["value" if d.kind == "number" else "fact"]["origin"]),
                     tuple(d.args["value" if d.kind == "number" else "fact"]["center"])) for d in drawn}
        assert len(segments) == 1, seed
        # The questions name that segment: the one asked first in full, the others by its ends.
        origin = _shown(drawn[0].args["value"]["origin"])
        assert all(origin in d.question for d in drawn[:8])
    starts = {variant(lesson.exercises[0], seed, 0).question for seed in range(30)}
    assert len(starts) >= 3  # students get different segments
    ex = lesson.exercises[0].variants[0]  # why names the variant's own (i, j, k), not the lecture's
    assert ex.why == "a = i² + j² + k² with (i, j, k) = (-1, -1, -2)."


def test_the_triangle_weights_from_exact_arithmetic():
    # Exact fractions (brute_force.exact_triangle_solve, Gauss-Jordan); by hand for the first
    # variant see test_image_order_answers: α = 1/5, β = 2/5, t = 2/5.
    lesson = BY_ID["ray_triangle"]
    for k in range(4):
        drawn = [ex.variants[k] for ex in lesson.exercises]
        v = drawn[0].args["value"]
        alpha, beta, _, t = exact_triangle_solve(
            *(v[key] for key in ("origin", "direction", "a", "b", "c")))
        p = StepPipelines(BY_ID["ray_sphere"].steps[drawn[0].step])
        for ex, exact in zip(drawn[:3], (alpha, beta, t), strict=True):
            assert number(ex, p) == pytest.approx(float(exact), abs=1e-12)
            assert judge(ex, p, float(exact) + 0.0005).right and not judge(ex, p, float(exact) + 0.01).right
        assert all(_shown(v["origin"]) in ex.question for ex in drawn)
    first = [ex.variants[0] for ex in lesson.exercises][0].args["value"]
    assert exact_triangle_solve(*(first[key] for key in ("origin", "direction", "a", "b", "c"))) == (
        Fraction(1, 5), Fraction(2, 5), Fraction(2, 5), Fraction(2, 5))


def test_your_point_through_the_lectures_perspective_formula():
    # By hand, the first variant: A = (6, -3, 4), the eye at z = -2.  The line from A to the eye
    # (0, 0, -2) is (6s, -3s, -2 + 6s); it meets z = 0 at s = 1/3: (2, -1).  As the step's formula:
    # x' = 6 · 2 / (4 + 2) = 2, y' = -3 · 2 / 6 = -1.
    lesson = BY_ID["perspective"]
    x_asked, y_asked = lesson.exercises[1:]
    assert (x_asked.kind, y_asked.kind) == ("number", "number")
    p = StepPipelines(lesson.steps[x_asked.step])
    for k in range(4):
        x_ex, y_ex = x_asked.variants[k], y_asked.variants[k]
        point, d = x_ex.args["value"]["point"], x_ex.args["value"]["d"]
        assert y_ex.args["value"]["point"] == point  # one point for both questions
        # Where the line from A to the eye (0, 0, -d) crosses z = 0, in fractions: at s with
        # -d + s (z + d) = 0.
        s = Fraction(d) / (Fraction(point[2]) + Fraction(d))
        crossing = (s * Fraction(point[0]), s * Fraction(point[1]))
        if k == 0:
            assert crossing == (2, -1)
        for ex, exact in ((x_ex, crossing[0]), (y_ex, crossing[1])):
            assert number(ex, p) == pytest.approx(float(exact), abs=1e-12)
            assert judge(ex, p, float(exact)).right and not judge(ex, p, float(exact) + 0.1).right
            assert _shown(point) in ex.question and f"z = -{d:g}" in ex.question
            # Its why works the formula with the point's own numbers, to the same answer:
            # "x′ = x d / (z + d) = 6 · 2 / (4 + 2) = 2: ...".
            worked = re.search(r"= (−?\d+) · (\d+) / \((\d+) \+ (\d+)\) = (−?\d+):", ex.why)
            a, b, c, e, answer = (int(g.replace("−", "-")) for g in worked.groups())
            coordinate = point[0] if ex is x_ex else point[1]
            assert (a, b, c, e) == (coordinate, d, point[2], d) and answer == exact
    assert all(x_asked.variants[k].args["value"]["point"] != [4, 2, 2] for k in range(4))


def test_the_panes_sorted_far_to_near_and_a_wrong_order_refused():
    # The panes stand at z = 1.4 (red), 0.2 (green), -1.0 (blue); the eye looks down -z: far to near
    # is blue, green, red.
    ex, p = _exercise("transparency", "Sorted as the lecture says")
    assert judge(ex, p, ["blue pane", "green pane", "red pane"]).right
    assert not judge(ex, p, ["red pane", "green pane", "blue pane"]).right


def test_a_click_in_the_cubes_shadow_is_right_and_one_in_the_sky_is_not():
    ex, p = _exercise("ray_casting", "Click a pixel in the cube's shadow")
    shown = a_right_pixel(ex, p)  # "show me"
    assert shown is not None and judge(ex, p, shown).right
    root = p.tree(shown)
    assert root.hit_name == "ground" and [c.hit_name for c in root.children if c.kind == "shadow"] == ["cube"]
    wrong = judge(ex, p, (0, 0))
    assert not wrong.right and wrong.sentence.startswith("Not there: at pixel (0, 0)")


def test_an_exercise_the_pipelines_cannot_answer_is_reported_and_bad_ones_refused():
    step = {"title": "one", "text": "words", "scene": "zbuffer_three_polygons", "panes": ["object order"]}
    both_seen = {"kind": "choose_one", "question": "Which is drawn?", "choices": ["green", "blue"],
                 "fact": {"fact": "seen", "object": "$choice"}}
    lesson = {"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
              "steps": [step], "exercises": [both_seen]}
    (line,) = check_exercises(from_dict(lesson))
    assert line == "lesson mine, exercises[0] (Which is drawn?): 2 choices are right (green, blue)"
    lesson["exercises"] = [
        {"kind": "guess", "question": "?"},
        {"kind": "click_pixel", "question": "?", "fact": {"fact": "seen", "object": "green"}},
        {"kind": "number", "question": "?", "tolerance": 1, "value": {"of": "weight"}},
        {"kind": "order", "question": "?", "items": ["green"], "by": "drawing_order", "step": 3},
        {"kind": "click_pixel", "question": "?", "fact": [
            {"fact": "zbuffer_keeps", "pixel": "$pixel", "object": "green"},
            {"fact": "seen", "object": "blue"},
            {"fact": "zbuffer_keeps", "pixel": "$pixel", "object": "purple"}]},
        {"kind": "click_pixel", "question": "?", "fact": []}]
    with pytest.raises(LessonFileError) as info:
        from_dict(lesson)
    assert info.value.problems[:4] == [
        "exercises[0].kind: unknown exercise kind \"guess\" "
        "(known: choose_one, click_pixel, number, order, pick_picture)",
        'exercises[1].fact: the fact must say "pixel": "$pixel" (the clicked pixel)',
        'exercises[2].value.of: unknown quantity "weight" '
        "(known: ray_sphere, ray_triangle, depth, hit_t, primitive_tests, blend, perspective)",
        "exercises[3].step: the lesson has steps 0 to 0, got 3"]
    assert info.value.problems[4] == ('exercises[4].fact[1]: the fact must say "pixel": "$pixel" '
                                      "(the clicked pixel)")
    assert info.value.problems[5].startswith("exercises[4].fact[2].object: no object 'purple' in the scene")
    assert info.value.problems[6:] == ["exercises[5].fact: give at least one fact"]
    lesson["exercises"] = [
        {"kind": "number", "question": "?", "tolerance": 1,
         "value": {"of": "perspective", "point": [1, 2, 3]}},
        {"kind": "number", "question": "?", "tolerance": 1,
         "value": {"of": "perspective", "point": [1, 2, -3], "d": 2, "component": 2}}]
    with pytest.raises(LessonFileError) as info:
        from_dict(lesson)
    assert info.value.problems == [
        "exercises[0].value.d: required field is missing",
        "exercises[0].value.component: required field is missing",
        "exercises[1].value.component: 0 (x′) or 1 (y′), got 2",
        "exercises[1].value.point: must lie in front of the eye (z > -d = -2), got z = -3"]


def test_variants_draw_other_pixels_by_seed_and_each_is_judged_by_its_own_answer():
    from core.lessons.exercises import variant

    ex = BY_ID["zbuffer"].exercises[0]
    assert len(ex.variants) == 5
    drawn = {variant(ex, seed).question for seed in range(40)}
    assert len(drawn) >= 4  # different students, different pixels
    assert variant(ex, 7) is variant(ex, 7)  # one student keeps one variant
    # By hand from the three planes (see test_lesson_facts): at the centre (80, 60) blue is nearest;
    # at (58, 59), left of blue's corner (-0.6, -0.9), only green covers the pixel.
    answers = {}
    for v in ex.variants:
        p = StepPipelines(BY_ID["zbuffer"].steps[v.step])
        (right,) = right_choices(v, p)
        answers[v.question.split("pixel ")[1].rstrip("?")] = v.args["choices"][right]
    assert answers["(80, 60)"] == "blue" and answers["(58, 59)"] == "green"


def test_questions_2_and_3_pick_the_picture_drawn_from_the_named_view():
    from core import presets
    from core.lessons.exercises import pictures

    ex, p = _exercise("three_views", "Question 3. Which picture is the top view?")
    drawn = pictures(ex, p)
    assert set(drawn) == {"front", "side", "top", "observer"}

    def cone_box(rgb):  # the cone is the only blue object: (0.15, 0.55, 0.75) lit
        ys, xs = np.nonzero((rgb[..., 2] > rgb[..., 0] + 0.2) & (rgb[..., 2] > 0.2))
        return xs.max() - xs.min() + 1, ys.max() - ys.min() + 1

    # From above the cone is a circle (as wide as deep); from the side a triangle 2r wide and h high.
    w, h = cone_box(drawn["top"])
    assert abs(w / h - 1) < 0.15
    w, h = cone_box(drawn["side"])
    assert w / h == pytest.approx(2 * presets.CONE_RADIUS / presets.CONE_HEIGHT, rel=0.15)
    assert judge(ex, p, "top").right
    wrong = judge(ex, p, "front")
    # It does not say which view was picked: the next question on these pictures asks for the side view.
    assert not wrong.right and wrong.sentence == "Not that one: it is not the top view."


def _glass_ball_lesson(exercise):
    # Looking down -z at a glass ball (centre 0, radius 1) with an opaque ball (centre (0, 0, -10),
    # radius 3) behind it.  The centre pixel's ray runs along the axis, so it meets every surface
    # head-on and refraction does not bend it: A at z = 1 (t = 9 from the eye at z = 10), B where it
    # leaves the glass at z = -1 (2 further on), C on the opaque ball at z = -7 (6 further on).
    scene = {"format": "render-explorer-scene", "version": 1,
             "camera": {"eye": [0, 0, 10], "target": [0, 0, 0], "up": [0, 1, 0], "near": 0.1, "far": 50,
                        "width": 41, "height": 41},
             "lights": [{"position": [5, 5, 10]}],
             "objects": [{"type": "sphere", "name": "glass", "center": [0, 0, 0], "radius": 1,
                          "material": {"transparency": 0.9, "ior": 1.5}},
                         {"type": "sphere", "name": "wall", "center": [0, 0, -10], "radius": 3}]}
    step = {"title": "one", "text": "words", "scene": scene, "panes": ["image order"],
            "image_order": {"mode": "raytrace"}}
    return from_dict({"format": "render-explorer-lesson", "version": 1, "id": "tree", "title": "Tree",
                      "steps": [step], "exercises": [exercise]})


def test_the_ray_tree_is_put_in_order_last_hits_first_as_in_fig_vii_11():
    a, b, c = "primary", "primary/refraction", "primary/refraction/refraction"
    lesson = _glass_ball_lesson({"kind": "order", "question": "?", "items": [a, b, c],
                                 "by": "ray_tree_colours", "pixel": [20, 20]})
    (ex,) = lesson.exercises
    p = StepPipelines(lesson.steps[0])
    rays = dict(p.tree((20, 20)).colour_order())
    hits = [(rays[k].hit_name, rays[k].t, rays[k].front_face) for k in (a, b, c)]
    assert hits == [("glass", pytest.approx(9), True), ("glass", pytest.approx(2), False),
                    ("wall", pytest.approx(6), True)]
    assert check_exercises(lesson) == []
    # The second stage: C's colour first, then B's (it needs C's), then A's (it needs B's): the pixel.
    assert judge(ex, p, [c, b, a]).right
    wrong = judge(ex, p, [a, b, c])
    assert not wrong.right and wrong.sentence == "Not that order: 1 of 3 in its place."  # b, in the middle
    assert judge(ex, p, [b, c, a]).sentence == "Not that order: 1 of 3 in its place."  # a, last
    assert judge(ex, p, [a, c, b]).sentence == "Not that order: 0 of 3 in their place."


def test_a_ray_tree_order_off_one_branch_or_not_traced_is_reported_and_bad_paths_refused():
    branches = _glass_ball_lesson({"kind": "order", "question": "?", "by": "ray_tree_colours",
                                   "pixel": [20, 20], "items": ["primary/reflection", "primary/refraction"]})
    assert check_exercises(branches) == [
        "lesson tree, exercises[0] (?): on separate branches, so in no one order: "
        "primary/reflection and primary/refraction"]
    # The wall is opaque: nothing is refracted at C.
    beyond = _glass_ball_lesson({"kind": "order", "question": "?", "by": "ray_tree_colours",
                                 "pixel": [20, 20],
                                 "items": ["primary", "primary/refraction/refraction/refraction"]})
    assert check_exercises(beyond) == [
        "lesson tree, exercises[0] (?): not traced at pixel (20, 20): "
        "primary/refraction/refraction/refraction"]
    with pytest.raises(LessonFileError) as info:
        _glass_ball_lesson({"kind": "order", "question": "?", "by": "ray_tree_colours",
                            "items": ["primary", "refraction/primary"]})
    assert info.value.problems == [
        "exercises[0].pixel: required field is missing (the pixel whose ray tree is ordered)",
        'exercises[0].items[1]: expected a ray\'s path such as "primary/refraction/reflection" '
        "(primary, then reflection or refraction), got 'refraction/primary'"]


def test_the_heat_map_is_withheld_while_a_question_counts_intersection_tests_and_only_then():
    # The heat map colours each pixel by its tests: it answers "how many tests", "which pixels are
    # tested", "which method costs fewer", and nothing else an exercise asks.
    counting = set()
    for lesson in LESSONS:
        for k, ex in enumerate(lesson.exercises):
            hidden = withheld(ex)
            assert hidden[0] == RESULTS and (PICTURES in hidden) == (ex.kind == "pick_picture")
            if HEAT_MAP in hidden:
                counting.add((lesson.id, k))
    asked = {(lesson.id, k) for lesson in LESSONS for k, ex in enumerate(lesson.exercises)
             if re.search(r"primitive tests|tested against", ex.question)}
    assert counting == asked and len(asked) == 3, (counting, asked)


def test_every_shipped_exercise_has_an_independent_solution():
    # How many exercises of each lesson the tests solve without the pipelines (this file,
    # test_object_order_answers, test_image_order_answers, test_view_answers).  A lesson that gains
    # an exercise fails here until a test works its answer out independently.
    solved = {"two_orders": 3, "observer": 3, "frustum": 3, "back_faces": 2, "zbuffer": 4,
              "zbuffer_piercing": 4, "transparency": 3, "perspective": 3, "orthographic": 1,
              "three_views": 5, "rasterization": 4, "ray_casting": 3, "ray_tracing": 3, "acceleration": 4,
              "ray_sphere": 10, "ray_triangle": 4}
    assert {lesson.id: len(lesson.exercises) for lesson in LESSONS} == solved


def _tiny_lesson(text, exercise, formulas=()):
    step = {"title": "one", "text": text, "formulas": list(formulas), "scene": "zbuffer_three_polygons",
            "panes": ["object order"]}
    return from_dict({"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
                      "steps": [step], "exercises": [exercise]})


SEGMENT = {"of": "ray_sphere", "origin": [2, 1, 2], "end": [10, 6, 6], "center": [6, 4, 6], "radius": 10}


def test_a_number_a_step_writes_is_reported_and_one_it_does_not_is_not():
    # Question 6's a = 8² + 5² + 4² = 105 and t2 = (126 + √40656) / 210 = 1.560158...
    ask_a = {"kind": "number", "question": "What is a?", "tolerance": 0.5, "value": {**SEGMENT, "value": "a"}}
    ask_t2 = {"kind": "number", "question": "What is t2?", "tolerance": 0.005,
              "value": {**SEGMENT, "value": "t_far"}}
    (line,) = check_exercises(_tiny_lesson("Here a = 105.", ask_a))
    assert line == ("lesson mine, exercises[0] (What is a?): a step states the answer: "
                    "steps[0].text writes 105, the answer 105")
    (line,) = check_exercises(_tiny_lesson("Words.", ask_t2, [r"$t_2 \approx 1.56016$"]))
    assert line.endswith("steps[0].formulas[0] writes 1.56016, the answer 1.56016")
    # Either sign: b = -126 is given away by "126²" as well.
    ask_b = {**ask_a, "question": "What is b?", "value": {**SEGMENT, "value": "b"}}
    assert check_exercises(_tiny_lesson("Words.", ask_b, [r"$\Delta = 126^2 + 4 \cdot 105 \cdot 59$"]))
    # Not reported: the numbers the step writes are not the answer rounded (8.80079 is within a's
    # tolerance of 9 but not 9 rounded), or are small integers, or are rounded too coarsely to be
    # judged right (t2 ≈ 1.6, 0.04 off with a tolerance of 0.005).
    assert check_exercises(_tiny_lesson("From (2, 1, 2) to (10, 6, 6): t2 ≈ 1.6, y = 8.80079.", ask_t2)) == []
    ask_small = {**ask_a, "value": {"of": "ray_sphere", "origin": [0, 0, 0], "end": [2, 1, 2],
                                    "center": [9, 9, 9], "radius": 1, "value": "a"}}  # a = 9
    assert check_exercises(_tiny_lesson("A corner at (9, 0, 9); 9 pixels.", ask_small)) == []


def test_a_choice_or_a_pixel_a_step_names_for_the_asked_pixel_is_reported():
    data = json.loads((LESSON_FILES / "12_ray_casting.json").read_text(encoding="utf-8"))
    # The shadow step picks (230, 155) and says "This pixel lies on the ground in the cone's shadow".
    data["exercises"] = [
        {"kind": "choose_one", "question": "What blocks the shadow ray of pixel (230, 155)?",
         "choices": ["cube", "cone", "ground"], "step": 1,
         "fact": {"fact": "shadow", "pixel": [230, 155], "object": "$choice"}},
        {"kind": "click_pixel", "question": "Click a pixel in the cone's shadow.", "step": 1,
         "fact": {"fact": "shadow", "pixel": "$pixel", "object": "cone"}},
        {"kind": "click_pixel", "question": "Click a pixel in the cube's shadow.", "step": 1,
         "fact": {"fact": "shadow", "pixel": "$pixel", "object": "cube"}}]
    lines = check_exercises(from_dict(data))
    assert lines == [
        "lesson ray_casting, exercises[0] (What blocks the shadow ray of pixel (230, 155)?): a step states "
        "the answer: steps[1].text says of pixel (230, 155) the answer 'cone': “This pixel lies on the "
        "ground in the cone's shadow: its shadow ray stops at the cone.”",
        "lesson ray_casting, exercises[1] (Click a pixel in the cone's shadow.): a step states the answer: "
        "steps[1] points at pixel (230, 155), a right answer"]


def test_the_lectures_worked_question_6_asked_again_is_reported():
    # The shipped lesson keeps the lecture's solution in step 1 (a = 105, ..., t2 ≈ 1.56016, the
    # exit (14.4813, ...)): asking those very numbers is recall, and the check says where they stand.
    data = json.loads((LESSON_FILES / "15_ray_sphere.json").read_text(encoding="utf-8"))
    ray = {"of": "ray_sphere", "origin": [2, 1, 2], "direction": [8, 5, 4], "center": [6, 4, 6], "radius": 10}
    data["exercises"] = [
        {"kind": "number", "question": "What is a?", "tolerance": 0.5, "value": {**SEGMENT, "value": "a"},
         "step": 1},
        {"kind": "number", "question": "What is c?", "tolerance": 0.5, "value": {**SEGMENT, "value": "c"},
         "step": 1},
        {"kind": "number", "question": "Give x.", "tolerance": 0.005,
         "value": {**ray, "value": "point", "component": 0}, "step": 1}]
    lines = check_exercises(from_dict(data))
    assert [line.split(": a step states the answer: ")[1] for line in lines] == [
        "steps[1].text, steps[1].formulas[0], steps[1].formulas[1], steps[1].formulas[2] write 105, "
        "the answer 105",
        "steps[1].formulas[0], steps[1].formulas[1] write 59, the answer -59",
        "steps[1].text, steps[1].formulas[3] write 14.4813, the answer 14.4813"]


def test_exercises_sharing_a_draw_must_list_as_many_variants():
    segments = [{"origin": [0, 0, 0], "end": [4, 0, 0], "center": [9, 9, 9], "radius": 1},
                {"origin": [1, 0, 0], "end": [1, 4, 0], "center": [9, 9, 9], "radius": 1}]
    value = {"of": "ray_sphere", "origin": "$at.origin", "end": "$at.end", "center": "$at.center",
             "radius": "$at.radius"}
    ask = {"kind": "number", "question": "From {at.origin} to {at.end}: a?", "tolerance": 0.5,
           "value": {**value, "value": "a"}, "variants": segments, "draw": "segment"}
    lesson = _tiny_lesson("Words.", ask)
    (ex,) = lesson.exercises
    assert [v.question for v in ex.variants] == ["From (0, 0, 0) to (4, 0, 0): a?",
                                                 "From (1, 0, 0) to (1, 4, 0): a?"]
    data = {"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
            "steps": [{"title": "one", "text": "Words.", "scene": "zbuffer_three_polygons",
                       "panes": ["object order"]}],
            "exercises": [ask, {**ask, "value": {**value, "value": "b"}, "variants": segments[:1]}]}
    with pytest.raises(LessonFileError) as info:
        from_dict(data)
    assert info.value.problems == ["exercises[1].variants: draw 'segment': exercises[0] lists 2 variants, "
                                   "this one 1; list as many"]
