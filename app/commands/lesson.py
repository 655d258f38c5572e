"""``python -m app lesson check FILE...``: does every lesson step say what the pipelines compute?

Examples::

    python -m app lesson check core/lessons/files/*.json
    python -m app lesson check my_lesson.json

Each file is loaded (every problem with its field path, as File → Open lesson shows them) and every
step's scene is run through the pipelines to decide its facts (:mod:`core.lessons.facts`) and answer
its exercises (:mod:`core.lessons.exercises`: exactly one right choice, some right pixel, a number).
It prints one line per fact that does not hold (lesson, step, fact, what was computed), highlight
its step's words do not name (:func:`core.lessons.naming.step_unnamed`), step or exercise that
writes a number no fact states (:func:`core.lessons.numbers_said.unchecked_numbers`), exercise the
pipelines cannot answer, or exercise whose answer a step's words state
(:func:`core.lessons.exercises.stated_answers`: it would be recall), and exits 1; 0 when all of it
holds in every file; 2 when a file cannot be read or is not a valid lesson (the other files are
still checked). Only :mod:`core` is imported, so it answers without Qt.
"""

from __future__ import annotations

import argparse
import sys

from core.in_words import counted
from core.lessons.exercises import check_exercises
from core.lessons.facts import check_lesson
from core.lessons.lesson_file import LessonFileError, load_lesson


def add_parser(sub) -> argparse.ArgumentParser:
    """Add the ``lesson`` command (with ``check``) to ``sub``."""
    parser = sub.add_parser("lesson", help="check lesson files against the pipelines",
                            description="Work with lesson files.")
    actions = parser.add_subparsers(dest="action", metavar="ACTION", required=True)
    check = actions.add_parser(
        "check", help="run every step's scene and check every fact it states",
        description="Load each lesson, run every step's scene through the pipelines and check every "
                    "fact. Exit status 0 when all hold, 1 when one does not, 2 for an unreadable file.")
    check.add_argument("files", nargs="+", metavar="FILE", help="lesson JSON files")
    check.set_defaults(run=run_check)
    return parser


def run_check(args) -> int:
    status, facts, exercises = 0, 0, 0
    for name in args.files:
        try:
            lesson = load_lesson(name)
        except LessonFileError as exc:
            print(f"error: {exc}", file=sys.stderr)
            status = 2
            continue
        facts += sum(len(step.facts) for step in lesson.steps)
        exercises += len(lesson.exercises)
        failures = check_lesson(lesson) + check_exercises(lesson)
        for line in failures:
            print(f"{name}: {line}")
        if failures and status == 0:
            status = 1
    if status == 0:
        print(f"{counted(len(args.files), 'lesson file')}: all {facts} facts hold, every number written is "
              f"a fact's, every highlight is named; the pipelines answer all {exercises} exercises")
    return status
