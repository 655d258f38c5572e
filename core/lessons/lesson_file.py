"""Lesson files: the lecture told figure by figure, as data, checked field by field.

A lesson is a short sequence of steps.  Each step names a scene (a preset or
an inline scene in the scene-file format), the observer's camera, the panes
to show, the render settings, what to highlight, and a few sentences of
explanation with typeset formulas.  The window applies a step; this module
only reads, checks and resolves lesson files, so it stays free of Qt.  The
shipped lessons are in ``core/lessons/files`` (:data:`FILES`).

A lesson file is a JSON object::

    {"format": "render-explorer-lesson", "version": 1,
     "id": "zbuffer", "title": "...", "figures": ["VII.5"], "questions": [4],
     "summary": "...", "steps": [{...}, ...]}

Every step has a ``title`` and a ``text``.  ``formulas``, ``notes`` and
``highlight`` belong to the step they are written in; every other field, left
out, keeps the previous step's value (so the first step must give ``scene``
and ``panes``).  The loader resolves this, so each :class:`LessonStep` is
complete.  Loading reports *every* problem at once, each with its field path
(``steps[2].panes[0]: unknown pane 'zbufer' (did you mean 'object order'?)``),
as one :class:`LessonFileError`, read with :mod:`core.files.checked_json` as a
scene file is (an inline scene is one, :mod:`core.files.scene_file`).  The
README's "Lesson files" section documents the fields.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, fields
from pathlib import Path
from types import MappingProxyType

import numpy as np

from core.files import scene_file
from core.files.checked_json import (
    LESSON_FORMAT,
    CheckedFileError,
    Reader,
    join,
    nesting_depth,
    other_kind,
    read_json,
    show,
)
from core.files.scene_file import SceneFileError
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tree import KINDS
from core.lessons import exercises, facts
from core.lessons.facts import object_named, read_object_name, read_part_index, read_pixel
from core.object_order.pipeline import RasterSettings
from core.presets import PRESETS
from core.presets_trace import PRESETS_TRACE
from core.scene import Scene

FORMAT = LESSON_FORMAT
VERSION = 1
#: The panes a step can show, by the names the window gives them.
PANES = ("scene 3D", "image order", "object order", "four views", "compare", "hard cases", "cost")
#: The 3D overlays a step can switch on.
OVERLAYS = ("frustum", "bounding spheres", "grid cells", "cells the ray walks")
#: The image-order heat maps a step can lay over the traced image: none, or a count of each pixel's tests.
HEAT_MAPS = ("off", *facts.HEAT_TESTS)
#: What the 3D pane keeps in view: the scene, observer and frustum; or the highlight, eye and screen.
FRAMES = ("scene", "highlight")
#: What a step can highlight; see :class:`LessonStep`.
HIGHLIGHTS = ("polygon_step", "pixel", "face", "vertex", "ray", "object")
#: Lecture figures a lesson may name: ``VII.1`` to ``VII.14``, optionally with a part letter.
FIGURE = re.compile(r"^VII\.(1[0-4]|[1-9])[a-d]?$")
QUESTIONS = range(1, 7)
#: The folder of the lessons that come with the program.
FILES = Path(__file__).parent / "files"
MAX_FILE_BYTES = 10_000_000  # room for inline scenes; a lesson's own text is far smaller
MAX_NESTING = 40  # levels of JSON arrays and objects: a lesson's own few, and an inline scene's
#: The longest text each field may hold, in characters: enough for a page, short enough to lay out.
MAX_CHARS = {"title": 200, "summary": 2000, "text": 20_000, "notes": 20_000, "formula": 2000}
MAX_STEPS = 200

_ALL_PRESETS = {**PRESETS, **PRESETS_TRACE}
_LESSON_FIELDS = ("format", "version", "id", "title", "figures", "questions", "summary", "steps", "exercises")
_STEP_FIELDS = ("title", "text", "formulas", "notes", "scene", "camera", "view", "panes",
                "image_order", "object_order", "highlight", "zbuffer_step", "pixel", "overlays", "frame",
                "facts", "heat_map")
_VIEW_FIELDS = ("position", "focal_point", "up")


class LessonFileError(CheckedFileError):
    """A lesson file that cannot be loaded (see :class:`core.files.checked_json.CheckedFileError`)."""

    thing = "lesson"


@dataclass(frozen=True, eq=False)
class LessonStep:
    """One step of a lesson, resolved: everything the window needs to show it.

    Attributes
    ----------
    title : str, a few words shown above the text.
    text : str, the explanation (plain text, our own words).
    formulas : tuple of str, matplotlib mathtext, each wrapped in ``$...$``.
    notes : str, presenter notes (shown only in the presenter window).
    preset : str or None, the preset key of the scene (``core.presets.PRESETS``
        or ``core.presets_trace.PRESETS_TRACE``); None for an inline scene.
    scene : Scene, the scene to load, with the camera overrides applied.
    camera : mapping, the camera fields this lesson overrides (already in ``scene``).
    view : mapping, the 3D pane's viewpoint: ``position``, ``focal_point``, ``up``
        (world space, scene units); empty for the pane's own framing.
    panes : tuple of str, names from :data:`PANES`; show these, hide the rest.
        The first is the one to bring to the front.
    image_order : TraceSettings for the image-order pane.
    object_order : RasterSettings for the object-order pane.
    highlight : mapping with at most these keys (see :data:`HIGHLIGHTS`):
        ``polygon_step`` (int, polygon drawn at that step, 0-based),
        ``pixel`` ((x, y), column and row from the top left),
        ``face`` ({"object": name, "triangle": index}),
        ``vertex`` ({"object": name, "index": vertex index}, the object-order path to show),
        ``ray`` (a ray kind of ``core.image_order.ray_tree.KINDS``),
        ``object`` (an object name).
    zbuffer_step : int or None, the z-buffer scrubber's step (after that many polygons).
    pixel : (x, y) or None, the picked pixel (ray tree, pixel history, worked math).
    overlays : tuple of str, names from :data:`OVERLAYS` to show in the 3D pane.
    frame : str, from :data:`FRAMES`, what the 3D pane's own framing keeps in view:
        ``"scene"`` the objects, the observer and the frustum (when shown) with its
        labels; ``"highlight"`` what the step highlights, the eye and the screen, as
        large as they fit (the rest of the frustum may leave the pane).
    facts : tuple of :class:`core.lessons.facts.Fact`, what the text claims, in words the
        pipelines decide (``python -m app lesson check``); they belong to the step they are written in.
    heat_map : str, from :data:`HEAT_MAPS`, the heat map laid over the traced image: ``"off"``, or
        each pixel's ``"primitive tests"`` or ``"box and sphere tests"`` with the step's acceleration.
    """

    title: str
    text: str
    formulas: tuple[str, ...]
    notes: str
    preset: str | None
    scene: Scene
    camera: MappingProxyType
    view: MappingProxyType
    panes: tuple[str, ...]
    image_order: TraceSettings
    object_order: RasterSettings
    highlight: MappingProxyType
    zbuffer_step: int | None
    pixel: tuple[int, int] | None
    overlays: tuple[str, ...]
    frame: str
    facts: tuple = ()
    heat_map: str = "off"


@dataclass(frozen=True, eq=False)
class Lesson:
    """A lesson: a title, the lecture's figures and questions it shows, its steps.

    Attributes
    ----------
    id : str, short unique name (letters, digits, ``_`` and ``-``).
    title : str
    figures : tuple of str, lecture figures shown (``"VII.4a"``).
    questions : tuple of int, the lecture's end-of-chapter questions answered (1 to 6).
    summary : str, one sentence for the lesson list.
    steps : tuple of LessonStep, at least one.
    path : Path or None, the file it was read from.
    exercises : tuple of :class:`core.lessons.exercises.Exercise`, asked at the end of the lesson.
    """

    id: str
    title: str
    figures: tuple[str, ...]
    questions: tuple[int, ...]
    summary: str
    steps: tuple[LessonStep, ...]
    path: Path | None = None
    exercises: tuple = ()


def _scene(r: Reader, value, path: str) -> tuple[str | None, Scene | None]:
    if isinstance(value, str):
        key = r.choice(value, path, tuple(_ALL_PRESETS), "preset")
        return key, (_ALL_PRESETS[key][1]() if key else None)
    if isinstance(value, dict):
        try:
            return None, scene_file.from_dict(value)
        except SceneFileError as exc:
            for problem in exc.problems:
                r.problems.append(f"{path}.{problem}" if not problem.startswith("top level")
                                  else f"{path}{problem[len('top level'):]}")
            return None, None
    r.add(path, f"expected a preset name or an inline scene object, got {show(value)}")
    return None, None


def _camera(r: Reader, value, path: str, scene: Scene) -> dict | None:
    if not isinstance(value, dict):
        r.add(path, f"expected an object {{...}}, got {show(value)}")
        return None
    before = len(r.problems)
    merged = {**scene_file.to_dict(scene)["camera"], **value}
    camera = scene_file.read_camera(r, merged, path)
    return None if len(r.problems) > before else {"camera": camera, "overrides": dict(value)}


def _settings(r: Reader, value, path: str, kind):
    known = [f.name for f in fields(kind)]
    d = r.fields(value, path, known)
    if d is None:
        return None
    before = len(r.problems)
    for key, v in d.items():
        if key not in known:
            continue
        default = getattr(kind(), key)
        if isinstance(default, bool) and not isinstance(v, bool):
            r.add(f"{path}.{key}", f"expected true or false, got {show(v)}")
        elif isinstance(default, (int, float)) and not isinstance(default, bool) and (
            isinstance(v, bool) or not isinstance(v, (int, float))
        ):
            r.add(f"{path}.{key}", f"expected a number, got {show(v)}")
        elif isinstance(default, str) and not isinstance(v, str):
            r.add(f"{path}.{key}", f"expected a string, got {show(v)}")
    if len(r.problems) > before:
        return None
    try:
        return kind(**{k: v for k, v in d.items() if k in known})
    except ValueError as exc:  # the settings' own checks, e.g. an unknown mode
        for message in str(exc).split("; "):
            r.add(path, message)
        return None


def _object_part(r: Reader, value, path: str, scene: Scene | None, part: str, index_key: str):
    """A ``{"object": name, index_key: k}`` naming part ``k`` (a ``part``: triangle or vertex) of a mesh."""
    d = r.fields(value, path, ["object", index_key], ["object", index_key])
    if d is None or "object" not in d or index_key not in d:
        return None
    name = read_object_name(r, d["object"], f"{path}.object", scene)
    obj = object_named(scene, name)
    index = read_part_index(r, d[index_key], f"{path}.{index_key}", obj, part)
    if obj is None or index is None:
        return None
    return MappingProxyType({"object": name, index_key: index})


def _highlight(r: Reader, value, path: str, scene: Scene | None) -> MappingProxyType:
    d = r.fields(value, path, HIGHLIGHTS) or {}
    out = {}
    for key, v in d.items():
        p = f"{path}.{key}"
        if key == "polygon_step":
            got = r.integer(v, p)
            if got is not None and got < 0:
                r.add(p, f"must be >= 0, got {got}")
                got = None
        elif key == "pixel":
            got = read_pixel(r, v, p, scene)
        elif key == "face":
            got = _object_part(r, v, p, scene, "triangle", "triangle")
        elif key == "vertex":
            got = _object_part(r, v, p, scene, "vertex", "index")
        elif key == "ray":
            got = r.choice(v, p, KINDS, "ray kind")
        elif key == "object":
            got = read_object_name(r, v, p, scene)
        else:
            continue
        if got is not None:
            out[key] = got
    return MappingProxyType(out)


def _formulas(r: Reader, value, path: str) -> tuple[str, ...]:
    out = []
    for k, v in enumerate(r.listing(value, path)):
        text = r.string(v, f"{path}[{k}]", MAX_CHARS["formula"])
        if text is None:
            continue
        if not (text.count("$") >= 2 and text.count("$") % 2 == 0):
            r.add(f"{path}[{k}]", f"a formula is mathtext between $ signs, got {show(text)}")
            continue
        out.append(text)
    return tuple(out)


def _text(r: Reader, d: dict, key: str, path: str, required: bool) -> str:
    if key not in d:
        return ""
    got = r.string(d[key], join(path, key), MAX_CHARS[key])
    if got is not None and required and not got.strip():
        r.add(join(path, key), "must not be empty")
    return got or ""


def _read_step(r: Reader, value, path: str, previous: dict) -> dict:
    """The step's fields, resolved against ``previous`` (the last step's values)."""
    first = not previous
    required = ["title", "text", *(["scene", "panes"] if first else [])]
    d = r.fields(value, path, _STEP_FIELDS, required)
    if d is None:
        return previous
    out = dict(previous)
    out.update(title=_text(r, d, "title", path, True), text=_text(r, d, "text", path, True),
               notes=_text(r, d, "notes", path, False),
               formulas=_formulas(r, d["formulas"], f"{path}.formulas") if "formulas" in d else ())
    if "scene" in d:
        out["preset"], out["scene"] = _scene(r, d["scene"], f"{path}.scene")
        out["camera"] = MappingProxyType({})
    scene = out.get("scene")
    if "camera" in d and scene is not None:
        got = _camera(r, d["camera"], f"{path}.camera", scene)
        if got is not None:
            out["scene"] = Scene(camera=got["camera"], objects=scene.objects, lights=scene.lights,
                                 background=scene.background)
            out["camera"] = MappingProxyType(got["overrides"])
            scene = out["scene"]
    if "view" in d:
        needed = ["position", "focal_point"] if d["view"] != {} else []  # {} resets the framing
        v = r.fields(d["view"], f"{path}.view", _VIEW_FIELDS, needed) or {}
        got = {k: r.vector(v[k], f"{path}.view.{k}") for k in _VIEW_FIELDS if k in v}
        out["view"] = MappingProxyType({k: x for k, x in got.items() if x is not None})
        _check_view(r, out["view"], f"{path}.view")
    if "panes" in d:
        panes = r.choices(d["panes"], f"{path}.panes", PANES, "pane")
        if panes is not None and not panes:
            r.add(f"{path}.panes", "name at least one pane to show")
        out["panes"] = panes or ()
    if "overlays" in d:
        out["overlays"] = r.choices(d["overlays"], f"{path}.overlays", OVERLAYS, "overlay") or ()
    if "frame" in d:
        out["frame"] = r.choice(d["frame"], f"{path}.frame", FRAMES, "framing") or "scene"
    if "heat_map" in d:
        out["heat_map"] = r.choice(d["heat_map"], f"{path}.heat_map", HEAT_MAPS, "heat map") or "off"
    for key, kind in (("image_order", TraceSettings), ("object_order", RasterSettings)):
        if key in d:
            out[key] = _settings(r, d[key], f"{path}.{key}", kind) or kind()
    if "zbuffer_step" in d:
        got = r.integer(d["zbuffer_step"], f"{path}.zbuffer_step")
        if got is not None and got < 0:
            r.add(f"{path}.zbuffer_step", f"must be >= 0, got {got}")
        out["zbuffer_step"] = got
    if "pixel" in d:
        out["pixel"] = read_pixel(r, d["pixel"], f"{path}.pixel", scene)
    elif "scene" in d or "camera" in d:
        out["pixel"] = None  # a picked pixel belongs to one image
    out["highlight"] = _highlight(r, d["highlight"], f"{path}.highlight", scene) if "highlight" in d \
        else MappingProxyType({})
    out["facts"] = facts.read_facts(r, d["facts"], f"{path}.facts", scene) if "facts" in d else ()
    return out


def _check_view(r: Reader, view, path: str) -> None:
    """Refuse a viewpoint the 3D pane cannot look from: the eye on its focal point, no up or an up
    along the line of sight."""
    if "position" not in view or "focal_point" not in view:
        return
    sight = np.subtract(view["focal_point"], view["position"])
    if not np.linalg.norm(sight) > 1e-9 * max(1.0, np.abs(view["position"]).max()):
        r.add(f"{path}.focal_point", "must differ from position (the pane would look nowhere)")
        return
    if "up" not in view:
        return
    up = np.asarray(view["up"])
    if not np.linalg.norm(up) > 0:
        r.add(f"{path}.up", "must not be (0, 0, 0)")
    elif not np.linalg.norm(np.cross(sight / np.linalg.norm(sight), up)) > 1e-6 * np.linalg.norm(up):
        r.add(f"{path}.up", "must not point along the line of sight (position to focal_point)")


_STEP_DEFAULTS = dict(view=MappingProxyType({}), overlays=(), frame="scene", zbuffer_step=None, pixel=None,
                      image_order=TraceSettings(), object_order=RasterSettings(),
                      camera=MappingProxyType({}), preset=None, scene=None, panes=(), heat_map="off")


def from_dict(d, path: Path | None = None) -> Lesson:
    """Build a :class:`Lesson` from the parsed JSON of a lesson file.

    Raises
    ------
    LessonFileError
        Listing every problem found, each with its field path.
    """
    r = Reader()
    if other_kind(d, FORMAT):
        raise LessonFileError([other_kind(d, FORMAT)])
    if nesting_depth(d, MAX_NESTING) > MAX_NESTING:
        raise LessonFileError([f"top level: arrays and objects nested more than {MAX_NESTING} levels deep"])
    data = r.fields(d, "", _LESSON_FIELDS, ["format", "version", "id", "title", "steps"])
    if data is None:
        raise LessonFileError(r.problems)
    r.header(data, FORMAT, VERSION)
    lesson_id = r.string(data["id"], "id") if "id" in data else None
    if lesson_id is not None and not re.fullmatch(r"[A-Za-z0-9_-]+", lesson_id):
        r.add("id", f"use letters, digits, '_' and '-' only, got {show(lesson_id)}")
    title = _text(r, data, "title", "", True)
    figures = []
    for k, v in enumerate(r.listing(data.get("figures", []), "figures")):
        text = r.string(v, f"figures[{k}]")
        if text is not None and not FIGURE.match(text):
            r.add(f"figures[{k}]",
                  f"expected a lecture figure VII.1 to VII.14 (e.g. \"VII.4a\"), got {show(v)}")
        elif text is not None:
            figures.append(text)
    questions = []
    for k, v in enumerate(r.listing(data.get("questions", []), "questions")):
        q = r.integer(v, f"questions[{k}]")
        if q is not None and q not in QUESTIONS:
            r.add(f"questions[{k}]", f"the lecture has questions 1 to 6, got {q}")
        elif q is not None:
            questions.append(q)
    steps, previous = [], {}
    raw_steps = r.listing(data.get("steps", []), "steps")
    if "steps" in data and isinstance(data["steps"], list) and not raw_steps:
        r.add("steps", "a lesson needs at least one step")
    if len(raw_steps) > MAX_STEPS:
        r.add("steps", f"at most {MAX_STEPS} steps are allowed, got {len(raw_steps):,}")
        raw_steps = []
    for k, v in enumerate(raw_steps):
        previous = _read_step(r, v, f"steps[{k}]", previous)
        steps.append(previous)
    summary = _text(r, data, "summary", "", False)
    if r.problems:
        raise LessonFileError(r.problems)
    resolved = tuple(LessonStep(**{**_STEP_DEFAULTS, **s}) for s in steps)
    asked = exercises.read_exercises(r, data.get("exercises", []), "exercises", resolved)
    if r.problems:
        raise LessonFileError(r.problems)
    return Lesson(id=lesson_id, title=title, figures=tuple(figures), questions=tuple(questions),
                  summary=summary, steps=resolved, path=path, exercises=asked)


def load_lesson(path) -> Lesson:
    """Load and check one lesson file.

    Raises :class:`LessonFileError` for anything wrong: a missing or unreadable
    file, a FIFO or device, a file over :data:`MAX_FILE_BYTES`, invalid JSON
    (with its line and column), or invalid content.  The file is read as a
    scene file is (:func:`core.files.checked_json.read_json`).
    """
    path = Path(path)
    data = read_json(path, MAX_FILE_BYTES, LessonFileError)
    try:
        return from_dict(data, path)
    except LessonFileError as exc:
        raise LessonFileError(exc.problems, str(path)) from None


def shipped_lessons() -> list[Lesson]:
    """The lessons that come with the program, in the lecture's order (file names sort so)."""
    return [load_lesson(p) for p in sorted(FILES.glob("*.json"))]
