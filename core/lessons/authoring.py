"""Authoring lessons: the window's state recorded as a lesson step, and the lesson file written back.

A lecturer builds a lesson without writing JSON by hand: :func:`step_record`
turns what the window shows (scene and observer, panes, settings, z-buffer step,
picked pixel, the 3D pane's viewpoint, the highlight and the heat map) and the
words typed into a form into one step of the lesson-file format, and
:func:`add_step` appends it to a lesson file (a new lesson when the file does
not exist yet), with the exercise the author typed for it (asked about the new
step's scene: its ``"step"`` is set to the new step), checks that the file still loads (a
:class:`core.lessons.lesson_file.LessonFileError` names the field path of anything wrong, and
nothing is written), and writes it atomically.  Loading the file and applying
the step shows the same window state again.
"""

from __future__ import annotations

import json
import numbers
import re
from collections.abc import Mapping
from dataclasses import asdict
from pathlib import Path

import numpy as np

from core.files import scene_file
from core.files.safe_files import write_atomic
from core.lessons.lesson_file import FORMAT, VERSION, Lesson, LessonFileError, from_dict


def step_record(*, title: str, text: str, scene, panes, image_order, object_order,
                zbuffer_step: int | None = None, pixel=None, facts=(), view=None, highlight=None,
                heat_map: str = "off") -> dict:
    """One lesson step, as its JSON object, for the window state given.

    ``scene`` is written inline (scene-file format, observer included); ``panes`` are lesson
    pane names with the one in front first; ``facts`` are fact objects (:mod:`core.lessons.facts`);
    ``view`` the 3D pane's camera (``position``, ``focal_point``, ``up``: world space, scene units);
    ``highlight`` what the window highlights (:class:`core.lessons.LessonStep`'s mapping, tuples and
    nested mappings allowed); ``heat_map`` one of :data:`core.lessons.HEAT_MAPS`.
    """
    step = {"title": title, "text": text, "scene": scene_file.to_dict(scene), "panes": list(panes),
            "image_order": asdict(image_order),
            "object_order": {k: v for k, v in asdict(object_order).items() if k != "record_steps"}}
    if zbuffer_step is not None:
        step["zbuffer_step"] = int(zbuffer_step)
    if pixel is not None:
        step["pixel"] = [int(pixel[0]), int(pixel[1])]
    if facts:
        step["facts"] = list(facts)
    if view:
        step["view"] = _plain(view)
    if highlight:
        step["highlight"] = _plain(highlight)
    if heat_map != "off":
        step["heat_map"] = heat_map
    return step


def _plain(value):
    """``value`` as JSON values: mappings as objects, tuples and arrays as lists, numbers as floats
    or ints."""
    if isinstance(value, Mapping):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple, np.ndarray)):
        return [_plain(v) for v in value]
    if isinstance(value, (bool, str)) or value is None:
        return value
    if isinstance(value, numbers.Integral):
        return int(value)
    return float(value)


def add_step(path, step: dict, exercise: dict | None = None) -> Lesson:
    """Append ``step`` to the lesson file ``path`` (created, named after the file, if missing), and
    ``exercise`` (an exercise object of :mod:`core.lessons.exercises`, without ``"step"``) to its
    exercises, asked about the new step.

    Raises
    ------
    LessonFileError
        When the file cannot be read, or the lesson with the new step would not load (every
        problem with its field path); the file is left as it was.
    """
    path = Path(path)
    if path.exists():
        try:
            data = json.loads(path.read_text(encoding="utf-8"))
        except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
            raise LessonFileError([f"cannot add a step: {exc}"], str(path)) from None
        if not isinstance(data, dict) or not isinstance(data.get("steps"), list):
            raise LessonFileError(["cannot add a step: not a lesson file"], str(path))
    else:
        lesson_id = re.sub(r"[^A-Za-z0-9_-]+", "_", path.stem) or "lesson"
        data = {"format": FORMAT, "version": VERSION, "id": lesson_id, "title": path.stem or "My lesson",
                "figures": [], "questions": [], "summary": "", "steps": []}
    data["steps"].append(step)
    if exercise is not None:
        data.setdefault("exercises", []).append({**exercise, "step": len(data["steps"]) - 1})
    try:
        lesson = from_dict(data, path)
    except LessonFileError as exc:
        raise LessonFileError(exc.problems, str(path)) from None
    write_atomic(path, (json.dumps(data, indent=2, ensure_ascii=False) + "\n").encode("utf-8"))
    return lesson
