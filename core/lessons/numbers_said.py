"""The numbers a lesson's words write, and whether its facts state them.

A number in a step's words is a claim ("their squared distances from the centre are 41 and 20", "its
corners sit on the centres of pixels (2, 2), (12, 2) and (8, 10)"), and the pipelines decide a claim
only when a fact states it (:mod:`core.lessons.facts`: ``"equals": 41``, ``"pixel": [12, 2]``), or
the window shows it of the step's scene (:func:`scene_numbers`: the observer's image size, planes,
angle, eye and target, which label the frustum, "far plane, f = 16"; the vertices, centres, radii,
materials and lights the Editor lists).  An exercise's question and explanation are words too ("The
scene has 110 triangles"): its own fields state its inputs (the pixel asked about, the segment), and
its step's facts and scene the rest.  :func:`unchecked_numbers` lists each number of a step's title,
text, formulas and presenter's notes, and of an exercise's question and explanation, that none
states, for ``python -m app lesson check`` and File → Open lesson
(:func:`core.lessons.facts.check_lesson`); the exercises use :func:`written_numbers` and
:func:`writes` to find a step that states an exercise's answer.

Integers below :data:`TRIVIAL_INTEGER` written without decimals are left out: counts, indices,
exponents and the small coordinates of the lecture's examples ("three equations", "1 − α", "r²").
"""

from __future__ import annotations

import re

import numpy as np

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


#: Three numbers written as a point, "(1.2, 0, −1.2)".
_POINT = re.compile(r"\(\s*([^(),]+),\s*([^(),]+),\s*([^(),]+)\)")
#: A material's numbers that words speak of ("αs = 0.5", "n = 1.5"); not its colour or shading weights.
_OPTICS = ("opacity", "reflectivity", "transparency", "ior")


def scene_numbers(scene) -> list[float]:
    """The numbers the window shows of ``scene`` itself, which no fact needs to state: its observer's
    (image width and height, near and far planes, viewing angle, eye and target: what the window
    labels the frustum with, "far plane, f = 16") and its materials' opacity, reflectivity,
    transparency and index of refraction (what the Editor lists).  Its points are
    :func:`scene_points`."""
    cam = scene.camera
    observer = [cam.width, cam.height, cam.near, cam.far, cam.fov_y_deg, *cam.eye, *cam.target]
    return [float(x) for x in observer] + [float(getattr(o.material, key)) for o in scene.objects
                                           for key in _OPTICS]


def scene_points(scene) -> np.ndarray:
    """``(N, 3)``: the points the Editor lists of ``scene``: every vertex, sphere centre and light."""
    points = [np.asarray(o.vertices, float) if hasattr(o, "vertices") else np.asarray([o.center], float)
              for o in scene.objects] + [np.asarray([light.position], float) for light in scene.lights]
    return np.concatenate(points + [np.zeros((0, 3))])


def _points_said(said: str, points: np.ndarray) -> str:
    """``said`` without the points it writes that are points of ``points``, each coordinate as written
    (to its decimals)."""
    def kept(m):
        try:
            written = [c.strip().replace("−", "-") for c in m.groups()]
            xyz = np.array([float(c) for c in written])
        except ValueError:
            return m.group(0)
        half = np.array([0.5 * 10.0 ** -len(c.partition(".")[2]) for c in written])
        return "" if np.any(np.all(np.abs(points - xyz) <= half + 1e-9, axis=1)) else m.group(0)
    return _POINT.sub(kept, said)


def _loose(said: str, stated: list[float], points: np.ndarray) -> str:
    """The numbers ``said`` writes that none of ``stated`` is and no point of ``points`` holds (as
    written), joined; empty if none."""
    loose = [(n, places) for n, places in written_numbers(_points_said(said, points))
             if not any(writes(n, places, x, float("inf")) for x in stated)]
    return ", ".join(dict.fromkeys(f"{n:.{places}f}" for n, places in loose))


def unchecked_numbers(lesson) -> list[str]:
    """One line per step of ``lesson`` whose title, text, formulas or presenter's notes write a
    number that none of that step's facts states and its scene does not show (:func:`scene_numbers`;
    as written: to its decimals, either sign), and per exercise whose question or explanation writes
    one that neither its own fields (its pixels, segment, variants) nor its step's facts and scene
    state; empty when every number is one of those."""
    lines = []
    stated = []
    for k, step in enumerate(lesson.steps):
        stated.append([x for fact in step.facts for x in _stated(fact.args)] + scene_numbers(step.scene))
        said = f"{step_words(step)}\n{step.notes}"  # the presenter's notes are read to the room too
        if loose := _loose(said, stated[k], scene_points(step.scene)):
            lines.append(f"lesson {lesson.id}, step {k + 1} {step.title!r}: no fact states {loose} "
                         "(add a fact that does, or leave the number out)")
    for ex in lesson.exercises:
        drawn = ex.variants or (ex,)
        own = [x for v in drawn for x in _stated(v.args)]
        said = "\n".join(dict.fromkeys(text for v in drawn for text in (v.question, v.why)))
        if loose := _loose(said, stated[ex.step] + own, scene_points(lesson.steps[ex.step].scene)):
            lines.append(f"lesson {lesson.id}, {ex.path} ({ex.question}): no fact states {loose} "
                         "(add a fact to its step that does, or leave the number out)")
    return lines
