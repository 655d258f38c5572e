"""Every number a lesson step or exercise writes is stated by one of its facts, so the pipelines decide it."""

import mpmath

from core.lessons.facts import check_lesson, solve_intersection
from core.lessons.lesson_file import from_dict
from core.lessons.numbers_said import unchecked_numbers

SEGMENT = {"origin": [2, 1, 2], "end": [10, 6, 6], "center": [6, 4, 6], "radius": 10}


def _lesson(text, facts=(), formulas=()):
    step = {"title": "Crossing", "text": text, "scene": "lecture", "panes": ["image order"],
            "formulas": list(formulas), "facts": list(facts)}
    return from_dict({"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
                      "steps": [step]})


def _fact(value, equals, **more):
    return {"fact": "ray_sphere", **SEGMENT, "value": value, "equals": equals, **more}


def test_a_number_no_fact_states_is_reported_with_lesson_step_and_number():
    lesson = _lesson("The start lies 41 from the centre, squared; the root is t ≈ 1.56016.")
    assert unchecked_numbers(lesson) == [
        "lesson mine, step 1 'Crossing': no fact states 41, 1.56016 (add a fact that does, or leave the "
        "number out)"]
    assert check_lesson(lesson) == unchecked_numbers(lesson)  # lesson check and File → Open lesson say it
    stated = _lesson("The start lies 41 from the centre, squared; the root is t ≈ 1.56016.",
                     [_fact("offset_squared", 41), _fact("ray_hit_t", 1.56016, tolerance=5e-6)])
    assert unchecked_numbers(stated) == [] and check_lesson(stated) == []


def test_a_number_is_stated_to_the_decimals_written_and_small_integers_are_left_out():
    facts = [_fact("ray_hit_t", 1.56016, tolerance=5e-6)]
    assert unchecked_numbers(_lesson("t ≈ 1.56, about 1.6", facts)) == []  # 1.56016 rounded as written
    assert unchecked_numbers(_lesson("t ≈ 1.57", facts)) != []
    assert unchecked_numbers(_lesson("three equations, 2 unknowns, step 9", facts)) == []
    # a fact's inputs are stated too (the segment's end), and formulas are words as well
    assert unchecked_numbers(_lesson("to (10, 6, 6)", facts)) == []
    assert unchecked_numbers(_lesson("The roots:", facts, formulas=["$t = 126 / 210$"])) != []


def test_the_lectures_segment_gives_the_squares_and_the_root_of_the_discriminant():
    # By hand: f = o - centre = (-4, -3, -4), f.f = 16 + 9 + 16 = 41; from the end (4, 2, 0): 20;
    # r^2 = 100; Δ = 126^2 + 4 * 105 * 59 = 40656, whose root mpmath gives to 30 digits.
    crossing = solve_intersection("ray_sphere", SEGMENT)
    back = solve_intersection("ray_sphere", {**SEGMENT, "origin": SEGMENT["end"], "end": SEGMENT["origin"]})
    assert (crossing.offset_squared, back.offset_squared, crossing.radius_squared) == (41, 20, 100)
    assert abs(crossing.sqrt_discriminant - float(mpmath.sqrt(40656))) < 1e-12
    missed = solve_intersection("ray_sphere", {**SEGMENT, "origin": [30, 0, 0], "end": [30, 1, 0]})
    assert missed.discriminant < 0 and missed.sqrt_discriminant is None


def test_the_observers_own_numbers_need_no_fact():
    # The window labels the frustum with them ("far plane, f = 30"); the lecture scene's observer
    # has a 320 x 240 image and a 40 degree viewing angle.
    assert unchecked_numbers(_lesson("A 320 x 240 image, a 40 degree angle, the far plane at 30.")) == []
    assert unchecked_numbers(_lesson("The far plane at 31.")) != []


def test_the_presenters_notes_are_held_to_the_same_rule():
    lesson = from_dict({"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
                        "steps": [{"title": "Crossing", "text": "The ray.", "scene": "lecture",
                                   "panes": ["image order"], "notes": "Tell them t is 1.56016."}]})
    (line,) = unchecked_numbers(lesson)
    assert "no fact states 1.56016" in line


def _asking(question, facts=(), why="", variants=None):
    """A lesson over the lecture scene with one number exercise asking ``question``."""
    ex = {"kind": "number", "question": question, "value": {"of": "hit_t", "pixel": "$at" if variants else
                                                             [132, 93]}, "tolerance": 0.01, "why": why}
    if variants:
        ex["variants"] = variants
    step = {"title": "Rays", "text": "A ray.", "scene": "lecture", "panes": ["image order"],
            "facts": list(facts)}
    return from_dict({"format": "render-explorer-lesson", "version": 1, "id": "mine", "title": "Mine",
                      "steps": [step], "exercises": [ex]})


def test_an_exercises_question_and_explanation_are_held_to_the_same_rule():
    told = "The scene has 110 triangles. How far along its ray does pixel (132, 93) meet the cube?"
    (line,) = unchecked_numbers(_asking(told))
    assert line.startswith("lesson mine, exercises[0] (The scene has 110 triangles.") and \
        "no fact states 110 (" in line
    counted = [{"fact": "primitive_tests", "pixel": [20, 10], "count": 110}]
    assert unchecked_numbers(_asking(told, counted)) == []  # its step's fact states it
    (line,) = unchecked_numbers(_asking("How far? Within 0.25 of 12.15.", why="About 12.15."))
    assert "no fact states 0.25, 12.15 (" in line  # the question's and the explanation's, each once
    # The pixel asked about is the exercise's own input, in each variant drawn.
    assert unchecked_numbers(_asking("How far along its ray does pixel {at} meet the cube?",
                                     variants=[[132, 93], [140, 95]])) == []


def test_the_scenes_own_numbers_need_no_fact():
    # The Editor lists the lecture scene's vertices and its light: a point written whole, each
    # coordinate as the scene holds it, needs no fact.  The same numbers loose, or a point the scene
    # does not hold, still do (the cone's 96 triangles hold many coordinates: one alone proves little).
    from core.presets import lecture_scene

    scene = lecture_scene()
    cube = next(o for o in scene.objects if o.name == "cube")
    corner = ", ".join(f"{c:g}" for c in cube.vertices[0])
    light = ", ".join(f"{c:g}" for c in scene.lights[0].position)
    assert unchecked_numbers(_lesson(f"A corner at ({corner}); the light at ({light}).")) == []
    assert unchecked_numbers(_lesson("A corner at (123.25, 0, 0).")) != []
    assert unchecked_numbers(_lesson(f"A corner at ({corner.replace('2.5', '2.6')}).")) != []
    assert unchecked_numbers(_lesson("The light is 12 above the ground.")) != []
    assert {o.material.ior for o in scene.objects} == {1.5}  # the default, which the Editor shows
    assert unchecked_numbers(_lesson("Glass would bend it with n = 1.5.")) == []
