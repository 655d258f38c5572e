"""What a lesson step's words name, and whether they name what the step highlights.

The window marks what a step highlights (an object, a face, a vertex, one ray of the picked pixel's
tree, the polygon drawn at a step) and writes the names of the objects its words name
(:mod:`app.lessons.runner`).  A mark the words do not speak of shows the student something the words
do not explain: the frustum step outlined the box behind the eye while its words spoke only of
"objects entirely outside it".  :func:`step_unnamed` finds such steps, for
``python -m app lesson check`` and File → Open lesson (:func:`core.lessons.facts.check_lesson`).
"""

from __future__ import annotations

import re

from core.scene import Scene

POINTED_AT = re.compile(r"\b(marked|outlined|highlighted)\b", re.IGNORECASE)
"""Words that point at the mark itself ("the face outlined in the 3D pane")."""
RAY_WORDS = {"primary": r"\bray\b", "shadow": r"\bshadow rays?\b", "reflection": r"\breflect",
             "refraction": r"\brefract"}
"""How words speak of each kind of ray a step may highlight (the primary ray is the pixel's ray)."""
FACE_WORDS = r"\b(faces?|walls?)\b"
VERTEX_WORDS = r"\b(vertex|vertices|corners?|points?|A)\b"


def says(text: str, name: str) -> bool:
    """Whether ``text`` names ``name``: as a whole word or words, in any case, "cones" for "cone" too,
    but not the lecture's "bounding box" or "bounding sphere" (boxes around objects, not an object
    named "box").

    >>> says("Both cones stand on the ground.", "cone"), says("the cube's bounding box", "box")
    (True, False)
    >>> says("a sandbox", "box"), says("The Green pane", "green pane")
    (False, True)
    """
    return re.search(rf"(?<!bounding )(?<!\w){re.escape(name.lower())}s?(?!\w)", text.lower()) is not None


def named_objects(scene: Scene, text: str) -> list:
    """The objects ``text`` speaks of: by their name (:func:`says`), or, for objects named "object N",
    by their number in a sentence about objects ("objects 1 and 4", "objects 1 to 4")."""
    lowered = text.lower()
    numbers = set()  # the numbers of sentences about objects, "1 to 4" counting 2 and 3 too
    for sentence in re.split(r"(?<=[.;:])\s+", lowered):
        if re.search(r"\bobjects?\b", sentence):
            numbers |= {int(n) for n in re.findall(r"\b\d+\b", sentence)}
            for a, b in re.findall(r"\b(\d+) to (\d+)\b", sentence):
                numbers |= set(range(int(a), int(b) + 1))
    named = []
    for obj in scene.objects:
        number = re.fullmatch(r"object (\d+)", obj.name.lower())
        if says(lowered, obj.name) or (number and int(number.group(1)) in numbers):
            named.append(obj)
    return named


def step_words(step) -> str:
    """All a step says to the student: its title, its text and its formulas."""
    return "\n".join((step.title, step.text, *step.formulas))


def _unnamed(step, kind: str, value, raster) -> str | None:
    """Why the words of ``step`` do not name its highlight ``kind`` (``value``), or None when they do;
    ``raster()`` gives the step's recorded object-order render (a polygon is named by its object)."""
    words = step_words(step)
    if POINTED_AT.search(words):
        return None
    names = [o.name for o in named_objects(step.scene, words)]
    if kind == "object" and value not in names:
        return f"its words do not name {value!r}"
    if kind == "ray" and not re.search(RAY_WORDS[value], words, re.IGNORECASE):
        return f"its words do not speak of the {value} ray"
    if kind == "face" and value["object"] not in names and not re.search(FACE_WORDS, words, re.IGNORECASE):
        return f"its words speak of no face of {value['object']!r}"
    if kind == "vertex" and not re.search(VERTEX_WORDS, words):
        return f"its words speak of no vertex of {value['object']!r}"
    if kind == "polygon_step" and (
            drawn := step.scene.objects[raster().draw.object_index[value]].name) not in names:
        return f"its words do not name {drawn!r}, whose polygon is drawn at step {value + 1}"
    return None


def step_unnamed(lesson, k: int, raster) -> list[str]:
    """One line per highlight of step ``k`` of ``lesson`` that its words (title, text, formulas) neither
    name nor point at ("marked", "outlined", "highlighted"); ``raster()`` gives the step's recorded
    object-order render (:func:`core.lessons.facts.check_lesson` passes the one its facts used)."""
    step = lesson.steps[k]
    return [f"lesson {lesson.id}, step {k + 1} {step.title!r}, highlight.{kind}: {why} "
            "(name it, or say that it is marked)"
            for kind, value in step.highlight.items()
            if kind != "pixel" and (why := _unnamed(step, kind, value, raster))]
