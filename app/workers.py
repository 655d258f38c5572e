"""Long work runs off the GUI thread, with progress and cancel.

A *job* is a plain function ``job(cancelled, progress) -> result``: it checks
``cancelled`` (a :class:`threading.Event`) between pieces of work and returns
``None`` once it is set, and calls ``progress(percent, partial)`` after each
piece.  :class:`Renderer` runs jobs on the thread pool; a new job supersedes the
running one (it stops at its next piece), and results of superseded jobs are
never delivered.  Partial results reach the GUI thread at most
:data:`PROGRESS_PER_SECOND` times a second; the ones in between are dropped
(the next one shows more anyway).  Signals are queued onto the GUI thread, so
receivers may touch widgets and VTK.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable

from PySide6.QtCore import QObject, QRunnable, QThreadPool, Signal

Job = Callable[[threading.Event, Callable[[int, object], None]], object]
PROGRESS_PER_SECOND = 30


class _Signals(QObject):
    progress = Signal(int, int, object)  # job id, percent done, partial result
    finished = Signal(int, object)  # job id, result
    failed = Signal(int, str)  # job id, message


class _Runnable(QRunnable):
    def __init__(self, job_id: int, job: Job, signals: _Signals, cancelled: threading.Event):
        super().__init__()
        self.job_id, self.job, self.signals, self.cancelled = job_id, job, signals, cancelled
        self._last_progress = -float("inf")

    def run(self):
        if self.cancelled.is_set():  # superseded while it waited for a thread: nothing to do
            return
        try:
            result = self.job(self.cancelled, self._progress)
        except Exception as exc:  # shown to the user by whoever listens to `failed`
            self._emit("failed", self.job_id, f"{type(exc).__name__}: {exc}")
            return
        if result is not None:
            self._emit("finished", self.job_id, result)

    def _progress(self, percent: int, partial: object) -> None:
        now = time.perf_counter()
        if now - self._last_progress >= 1.0 / PROGRESS_PER_SECOND:
            self._last_progress = now
            self._emit("progress", self.job_id, percent, partial)

    def _emit(self, name: str, *args) -> None:
        """Report to the GUI thread, unless the job was cancelled or its window is gone."""
        if self.cancelled.is_set():
            return
        try:
            getattr(self.signals, name).emit(*args)
        except RuntimeError:  # the Renderer was deleted while this job ran: nobody to tell
            self.cancelled.set()


class Renderer(QObject):
    """Runs one job at a time for its owner; the newest job wins.

    Signals
    -------
    progress(int percent, object partial)
    finished(object result)
    failed(str message)
    """

    progress = Signal(int, object)
    finished = Signal(object)
    failed = Signal(str)

    def __init__(self, parent: QObject | None = None, pool: QThreadPool | None = None):
        super().__init__(parent)
        self._pool = pool or QThreadPool.globalInstance()
        self._latest = 0
        self._cancel: threading.Event | None = None
        self._signals = _Signals()
        self._signals.progress.connect(self._on_progress)
        self._signals.finished.connect(self._on_finished)
        self._signals.failed.connect(self._on_failed)

    @property
    def busy(self) -> bool:
        return self._cancel is not None

    def submit(self, job: Job) -> int:
        """Run ``job`` in the background, cancelling the running one; returns its id."""
        self.cancel()
        self._latest += 1
        self._cancel = threading.Event()
        self._pool.start(_Runnable(self._latest, job, self._signals, self._cancel))
        return self._latest

    def cancel(self) -> None:
        """Stop the running job, if any; its result will not be delivered."""
        if self._cancel is not None:
            self._cancel.set()
            self._cancel = None

    def _on_progress(self, job_id, percent, partial):
        if job_id == self._latest and self._cancel is not None:
            self.progress.emit(percent, partial)

    def _on_finished(self, job_id, result):
        if job_id == self._latest and self._cancel is not None:
            self._cancel = None
            self.finished.emit(result)

    def _on_failed(self, job_id, message):
        if job_id == self._latest and self._cancel is not None:
            self._cancel = None
            self.failed.emit(message)
