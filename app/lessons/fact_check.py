"""File → Open lesson checks the lesson's facts, off the GUI thread, and shows the author what is false.

:func:`core.lessons.facts.check_step` runs each step's scene through the
pipelines; for a lesson of many steps that takes seconds, so
:class:`LessonFactCheck` runs it as a job (:class:`app.renders.Renderer`, the
newest lesson opened wins), reports progress in the status bar and, when a
fact does not hold, a highlight is not named by its step's words or a number is no
fact's, opens a dialog listing every failure in the words of ``python -m app lesson check``.
"""

from __future__ import annotations

from PySide6.QtCore import QObject
from PySide6.QtWidgets import QMessageBox, QWidget

from app.renders import Renderer
from core.in_words import counted
from core.lessons.facts import check_lesson


class LessonFactCheck(QObject):
    """Checks the facts of opened lessons for ``window`` (a QMainWindow with a status bar).

    Attributes
    ----------
    failures : the failure lines of the last lesson checked (empty when every fact held).
    dialog : the dialog that listed them, or None.
    """

    def __init__(self, window: QWidget):
        super().__init__(window)
        self.window = window
        self.failures: list[str] = []
        self.dialog: QMessageBox | None = None
        self._lesson = None
        self._renderer = Renderer(self)
        self._renderer.finished.connect(self._done)
        self._renderer.failed.connect(lambda message: self._done([f"the check stopped: {message}"]))

    @property
    def busy(self) -> bool:
        return self._renderer.busy

    def check(self, lesson) -> None:
        """Check every fact, highlight and number of ``lesson`` in the background
        (:func:`core.lessons.facts.check_lesson`); a dialog lists what does not hold."""
        self._lesson = lesson
        facts = sum(len(step.facts) for step in lesson.steps)
        self.window.statusBar().showMessage(f"Checking the {counted(facts, 'fact')} of lesson "
                                            f"{lesson.title!r}…")

        def job(cancelled, progress):
            return None if cancelled.is_set() else check_lesson(lesson)

        self._renderer.submit(job)

    def _done(self, failures: list[str]) -> None:
        self.failures = list(failures)
        lesson = self._lesson
        if not failures:
            self.window.statusBar().showMessage(
                f"Every fact of lesson {lesson.title!r} holds, every number it writes is a fact's and every "
                "highlight is named", 8000)
            return
        problems = counted(len(failures), "problem")
        self.window.statusBar().showMessage(f"{problems} in what lesson {lesson.title!r} says", 15000)
        box = QMessageBox(QMessageBox.Icon.Warning, "What the lesson says that does not hold",
                          f"{problems} in {lesson.title!r}: a fact the pipelines do not compute, a highlight "
                          "its step's words do not name, or a number no fact states:",
                          QMessageBox.StandardButton.Ok, self.window)
        box.setInformativeText("\n".join(failures[:8]) + (
            f"\n... and {len(failures) - 8} more" if len(failures) > 8 else ""))
        box.setDetailedText("\n".join(failures))
        box.setObjectName("lesson_facts")
        self.dialog = box
        box.open()
