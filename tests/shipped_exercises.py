"""The shipped lessons' exercises, for the tests that solve each one independently.

:func:`exercise` finds one with the pipelines of its step; :func:`assert_only` checks that the
pipelines' judge takes the answer a test worked out and refuses every other choice.
"""

from __future__ import annotations

from functools import cache

from core.lessons.exercises import judge, variant
from core.lessons.facts import StepPipelines
from core.lessons.lesson_file import shipped_lessons


@cache
def lessons() -> dict:
    """The shipped lessons by id."""
    return {lesson.id: lesson for lesson in shipped_lessons()}


def exercise(lesson_id: str, index: int, variant: int | None = None):
    """Exercise ``index`` of the lesson (its ``variant``-th variant, when given) and the pipelines of
    the step it asks about: ``(exercise, StepPipelines)``."""
    lesson = lessons()[lesson_id]
    ex = lesson.exercises[index]
    if variant is not None:
        ex = ex.variants[variant]
    return ex, StepPipelines(lesson.steps[ex.step])


def assert_only(ex, p, answer) -> None:
    """``answer`` (a choice of a ``choose_one``) is judged right, and every other choice wrong."""
    choices = ex.args["choices"]
    assert answer in choices, (ex.question, answer)
    verdicts = [judge(ex, p, i).right for i in range(len(choices))]
    assert verdicts == [c == answer and type(c) is type(answer) for c in choices], (
        ex.question, answer, verdicts)


def seed_drawing(ex, index: int, k: int) -> int:
    """A student's seed that draws variant ``k`` of ``ex``, the lesson's exercise ``index``."""
    return next(s for s in range(1000) if variant(ex, s, index) is ex.variants[k])
