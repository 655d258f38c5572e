"""The numbers a lesson step's words write, and whether its facts state them.

A number in a step's words is a claim ("their squared distances from the centre are 41 and 20", "its
corners sit on the centres of pixels (2, 2), (12, 2) and (8, 10)"), and the pipelines decide a claim
only when a fact states it (:mod:`core.lessons.facts`: ``"equals": 41``, ``"pixel": [12, 2]``), or
the step's observer holds it (its image's width and height, its near and far planes, its viewing
angle, eye and target: the numbers the window labels the frustum with, "far plane, f = 16").
:func:`unchecked_numbers` lists each number of a step's title, text, formulas and presenter's notes
that neither states, for ``python -m app lesson check`` and File → Open lesson
(:func:`core.lessons.facts.check_lesson`); the exercises use :func:`written_numbers` and
:func:`writes` to find a step that states an exercise's answer.

Integers below :data:`TRIVIAL_INTEGER` written without decimals are left out: counts, indices,
exponents and the small coordinates of the lecture's examples ("three equations", "1 − α", "r²").
"""

from __future__ import annotations

import re

from core.lessons.naming import step_words

#: A number as a step writes it: digits, a decimal point and decimals; a minus sign (ASCII or "−").
_WRITTEN = re.compile(r"(?<![\w.])[-−]?(\d+(?:\.\d+)?)(?![\w])")
#: Below this, an integer written without decimals is everywhere (coordinates, exponents, indices, "1 − α")
#: and says nothing about an answer.
TRIVIAL_INTEGER = 10


def written_numbers(text: str) -> list[tuple[float, int]]:
    """The numbers ``text`` writes (a step's words or formulas): ``(magnitude, decimals)``, leaving
    out integers below :data:`TRIVIAL_INTEGER` written without decimals.

    >>> written_numbers("t ≈ 1.56016 at (14.4813, 8.80079, −8.24063); Fig. VII.6, step 2 of 12")
    [(1.56016, 5), (14.4813, 4), (8.80079, 5), (8.24063, 5), (12.0, 0)]
    """
    out = []
    for m in _WRITTEN.finditer(text):
        digits = m.group(1)
        decimals = len(digits.partition(".")[2])
        if decimals or int(digits) >= TRIVIAL_INTEGER:
            out.append((float(digits), decimals))
    return out


def writes(n: float, decimals: int, value: float, tolerance: float) -> bool:
    """Is ``n``, written with ``decimals`` decimals, the answer ``value`` (either sign) as a student
    would copy it: ``value`` rounded to those decimals, and judged right typed in?"""
    off = abs(abs(value) - n)
    return off <= 0.5 * 10.0 ** -decimals + 1e-9 * max(1.0, n) and off <= tolerance


def _stated(value) -> list[float]:
    """Every number a fact's fields hold (its inputs and the values it claims), nested lists too."""
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return []
    if isinstance(value, (int, float)):
        return [float(value)]
    if hasattr(value, "values"):
        return [x for v in value.values() for x in _stated(v)]
    return [x for v in value for x in _stated(v)]


def unchecked_numbers(lesson) -> list[str]:
    """One line per step of ``lesson`` whose title, text, formulas or presenter's notes write a
    number that none of that step's facts states and its observer does not hold (as written: to its
    decimals, either sign); empty when every number is one of those."""
    lines = []
    for k, step in enumerate(lesson.steps):
        cam = step.scene.camera
        observer = [cam.width, cam.height, cam.near, cam.far, cam.fov_y_deg, *cam.eye, *cam.target]
        stated = [x for fact in step.facts for x in _stated(fact.args)] + [float(x) for x in observer]
        said = f"{step_words(step)}\n{step.notes}"  # the presenter's notes are read to the room too
        loose = [(n, places) for n, places in written_numbers(said)
                 if not any(writes(n, places, x, float("inf")) for x in stated)]
        if loose:
            shown = ", ".join(dict.fromkeys(f"{n:.{places}f}" for n, places in loose))
            lines.append(f"lesson {lesson.id}, step {k + 1} {step.title!r}: no fact states {shown} "
                         "(add a fact that does, or leave the number out)")
    return lines
