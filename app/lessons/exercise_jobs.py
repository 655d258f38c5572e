"""Exercises ask the pipelines off the GUI thread: :class:`ExerciseJobs` is the panel's ``run``.

Judging an answer, revealing it or finding a pixel to "show me" runs the step's
scene through a pipeline (up to a second on the lecture scene, more for a pixel
search), so :class:`views.panels.exercise_panel.ExercisePanel` hands the work to this
runner, which does it on the thread pool (:class:`app.renders.Renderer`, the
newest request wins) and calls back on the GUI thread.
"""

from __future__ import annotations

from PySide6.QtCore import QObject

from app.renders import Renderer


class ExerciseJobs(QObject):
    """``jobs(work, done)``: run ``work()`` in the background, then ``done(result)`` on the GUI thread.

    Attributes
    ----------
    failed : the message of the last job that raised, or "".
    """

    def __init__(self, parent: QObject | None = None, on_failure=None):
        super().__init__(parent)
        self.failed = ""
        self._done = None
        self._renderer = Renderer(self)
        self._renderer.finished.connect(lambda boxed: self._done(boxed[0]))
        self._renderer.failed.connect(self._failure)
        self._on_failure = on_failure

    @property
    def busy(self) -> bool:
        return self._renderer.busy

    def __call__(self, work, done) -> None:
        self._done = done
        self._renderer.submit(lambda cancelled, progress: None if cancelled.is_set() else (work(),))

    def _failure(self, message: str) -> None:
        self.failed = message
        if self._on_failure is not None:
            self._on_failure(message)
