"""Exercises: every shipped one is answerable by the pipelines; answers are judged against
independent computations, and a wrong answer is refused."""

import math
from fractions import Fraction

import numpy as np
import pytest

from core.files.lesson_file import LessonFileError, from_dict, shipped_lessons
from core.lessons.exercises import a_right_pixel, check_exercises, judge, number, right_choices
from core.lessons.facts import StepPipelines

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


def test_question_6_every_number_of_its_solution():
    # i, j, k = 8, 5, 4; a = 105, b = -126, c = -59, Δ = 126² + 4·105·59 = 40656 (by hand);
    # t = (126 ∓ √40656) / 210; the ray leaves at x = 2 + 8 t2.
    t1, t2 = (126 - math.sqrt(40656)) / 210, (126 + math.sqrt(40656)) / 210
    expected = {"Question 6": 105, "What is b?": -126, "What is c?": -59,
                "What is the discriminant": 40656, "What is the smaller root": t1,
                "What is the larger root": t2, "Where does the ray leave": 2 + 8 * t2}
    for start, value in expected.items():
        ex, p = _exercise("ray_sphere", start)
        assert judge(ex, p, value).right, start
        assert not judge(ex, p, value + 10 * ex.args["tolerance"] + 1).right, start
    ex, p = _exercise("ray_sphere", "Does the segment itself")
    assert [ex.args["choices"][i] for i in right_choices(ex, p)] == [False]  # both ends inside
    ex, p = _exercise("ray_sphere", "Continued as a ray")
    assert judge(ex, p, ex.args["choices"].index("t_far")).right
    verdict = judge(ex, p, ex.args["choices"].index("t_near"))
    assert not verdict.right and verdict.sentence == "“t1, the smaller root” is not the answer."


def test_the_triangle_weights_from_exact_arithmetic():
    # Cramer's rule in fractions: α = 481/1558, β = 957/3116, t = 784/779 (see the lesson's text).
    for start, exact in (("For the ray o + t d", Fraction(481, 1558)),
                         ("What is β", Fraction(957, 3116)), ("What is t, in units", Fraction(784, 779))):
        ex, p = _exercise("ray_triangle", start)
        assert number(ex, p) == pytest.approx(float(exact), abs=1e-12)
        assert judge(ex, p, float(exact) + 0.0005).right and not judge(ex, p, float(exact) + 0.01).right


def test_the_panes_sorted_far_to_near_and_a_wrong_order_refused():
    # The panes stand at z = 1.4 (red), 0.2 (green), -1.0 (blue); the eye looks down -z: far to near
    # is blue, green, red.
    ex, p = _exercise("transparency", "Sorted as the lecture says")
    assert judge(ex, p, ["blue pane", "green pane", "red pane"]).right
    assert not judge(ex, p, ["red pane", "green pane", "blue pane"]).right


def test_observer_a_does_not_see_object_5():
    # Object 5's centre (-5.5, 0.7, 6.5) seen from A's eye (0, 1, 8) looking down -z lies
    # atan(5.5 / 1.5) = 75° off the axis, far beyond half of any usual field of view.
    assert math.degrees(math.atan2(5.5, 1.5)) > 60
    ex, p = _exercise("observer", "From observer A")
    assert judge(ex, p, ex.args["choices"].index("object 5")).right
    assert not judge(ex, p, ex.args["choices"].index("object 3")).right  # inside, only hidden


def test_the_top_left_rule_on_the_edges_centres():
    # Pixel (11, 7)'s centre (3.5, -1.5) in world units lies on the edge from (5.5, -4.5) to (-0.5, 4.5):
    # x = 5.5 - 6 s, y = -4.5 + 9 s at s = 1/3.  That edge is a right edge: not the triangle's.
    assert (Fraction(11) + Fraction(1, 2) - 8, 6 - (Fraction(7) + Fraction(1, 2))) == (
        Fraction(11, 2) - 6 * Fraction(1, 3), Fraction(-9, 2) + 9 * Fraction(1, 3))
    ex, p = _exercise("rasterization", "The centre of pixel (11, 7)")
    assert judge(ex, p, ex.args["choices"].index(None)).right
    assert not judge(ex, p, ex.args["choices"].index("triangle")).right


def test_a_click_in_the_cones_shadow_is_right_and_one_in_the_sky_is_not():
    ex, p = _exercise("ray_casting", "Click a pixel in the cone's shadow")
    shown = a_right_pixel(ex, p)  # "show me"
    assert shown is not None and judge(ex, p, shown).right
    root = p.tree(shown)
    assert root.hit_name == "ground" and [c.hit_name for c in root.children if c.kind == "shadow"] == ["cone"]
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
        "(known: ray_sphere, ray_triangle, depth, hit_t, blend)",
        "exercises[3].step: the lesson has steps 0 to 0, got 3"]
    assert info.value.problems[4] == ('exercises[4].fact[1]: the fact must say "pixel": "$pixel" '
                                      "(the clicked pixel)")
    assert info.value.problems[5].startswith("exercises[4].fact[2].object: no object 'purple' in the scene")
    assert info.value.problems[6:] == ["exercises[5].fact: give at least one fact"]


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


def test_every_shipped_exercise_has_an_independent_solution():
    # How many exercises of each lesson the tests solve without the pipelines (this file,
    # test_object_order_answers, test_image_order_answers, test_view_answers).  A lesson that gains
    # an exercise fails here until a test works its answer out independently.
    solved = {"two_orders": 2, "observer": 3, "frustum": 2, "back_faces": 2, "zbuffer": 3,
              "zbuffer_piercing": 3, "transparency": 3, "perspective": 1, "orthographic": 1,
              "three_views": 5, "rasterization": 2, "ray_casting": 2, "ray_tracing": 3, "acceleration": 2,
              "ray_sphere": 9, "ray_triangle": 4}
    assert {lesson.id: len(lesson.exercises) for lesson in LESSONS} == solved
