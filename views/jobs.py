"""Long work off the GUI thread: run a job on a thread pool, with progress, cancel, result or failure.

A *job* is a plain function ``job(cancelled, progress) -> result``: it checks
``cancelled`` (a :class:`core.stopping.StopRequest`) between pieces of work and
returns ``None`` once it is set, and calls ``progress(percent, partial)`` after
each piece.  A compiled kernel it runs stops within a pixel or a triangle once
``cancelled`` is set (:mod:`core.stopping`); the job then ends with
:class:`~core.stopping.StoppedError` and delivers nothing.

- :class:`JobRun` runs one job once on a pool's thread and reports to a
  :class:`JobSignals`, each report tagged with the job's id; a panel that keeps
  several jobs in flight (say, at two priorities) sorts them by id.
- :class:`JobRunner` runs one job at a time for its owner: a new job supersedes
  the running one, and what a superseded or cancelled job reports is never
  delivered.

Signals are queued onto the GUI thread, so receivers may touch widgets and VTK.  What a job held
(its function and what that holds, its signals, its result) is let go of on the GUI thread too, so a
widget or a signals object is never destroyed on a pool's thread (:data:`_held`).
"""

from __future__ import annotations

import functools
import itertools
import threading
import time
from collections.abc import Callable

import shiboken6
from PySide6.QtCore import QCoreApplication, QObject, QRunnable, Qt, QThreadPool, Signal, Slot

from core import stopping

Job = Callable[[threading.Event, Callable[[int, object], None]], object]


class JobSignals(QObject):
    """What jobs report, each with the id of the job it is from, to ``owner``'s receivers.

    It has no Qt parent: Qt must not destroy an object while another thread emits its signal (a
    runner deleted while its job reported crashed the process within a few runs), so the runs that
    report to it keep it (:data:`_held`) until they end, and ``owner``'s deletion only stops their
    reports (``owner_gone``).
    """

    progress = Signal(int, int, object)  # job id, percent done, partial result
    finished = Signal(int, object)  # job id, result
    failed = Signal(int, str)  # job id, message

    def __init__(self, owner: QObject | None = None):
        super().__init__()
        self.owner_gone = threading.Event()
        if owner is not None:  # a plain callable: PySide ties a method's connection to its object
            owner.destroyed.connect(functools.partial(threading.Event.set, self.owner_gone))


class JobRun(QRunnable):
    """One run of ``job`` on a pool's thread, reported to ``signals`` as job ``job_id``.

    Parameters
    ----------
    cancelled : set it to stop the job; nothing is reported after that (``None``: never cancelled).
    progress_per_second : partial results reach ``signals`` at most this often, the first one always;
        the ones in between are dropped (the next one shows more anyway).  ``None``: every one.
    prepare : called on the job's thread before the job starts (say, to lower the thread's priority).
    """

    def __init__(self, job_id: int, job: Job, signals: JobSignals,
                 cancelled: stopping.StopRequest | None = None, progress_per_second: float | None = None,
                 prepare: Callable[[], None] | None = None):
        super().__init__()
        self.job_id, self.job, self.signals = job_id, job, signals
        self.cancelled = cancelled if cancelled is not None else stopping.StopRequest()
        self._interval = 1.0 / progress_per_second if progress_per_second else 0.0
        self._prepare = prepare
        self._last_progress = -float("inf")
        self._started = False
        self._key = next(_keys)
        _held[self._key] = [job, signals, prepare]
        global _reaper
        if _reaper is None or not shiboken6.isValid(_reaper):  # made here, on the GUI thread
            _reaper = _Reaper()

    def run(self):
        self._started = True
        result = None
        try:
            if self.cancelled.is_set():  # superseded while it waited for a thread: nothing to do
                return
            if self._prepare is not None:
                self._prepare()
            try:
                with stopping.stopped_by(self.cancelled):
                    result = self.job(self.cancelled, self._progress)
            except stopping.StoppedError:  # cancelled in a kernel: nothing to deliver
                return
            except Exception as exc:  # shown to the user by whoever listens to `failed`
                self._emit("failed", self.job_id, f"{type(exc).__name__}: {exc}")
                return
            if result is not None:
                self._emit("finished", self.job_id, result)
        finally:
            _held[self._key].append(result)  # kept by the GUI thread until it lets go
            self.job = self.signals = self._prepare = result = None
            _let_go_on_gui_thread(self._key)

    def __del__(self):
        if not getattr(self, "_started", True):  # never run (superseded before it started)
            _held.pop(self._key, None)

    def _progress(self, percent: int, partial: object) -> None:
        now = time.perf_counter()
        if now - self._last_progress >= self._interval:
            self._last_progress = now
            self._emit("progress", self.job_id, percent, partial)

    def _emit(self, name: str, *args) -> None:
        """Report to the GUI thread, unless the job was cancelled or whoever listened is gone."""
        if self.signals.owner_gone.is_set():  # nobody to tell: the job may stop
            self.cancelled.set()
        if not self.cancelled.is_set():
            getattr(self.signals, name).emit(*args)


_held: dict[int, list] = {}
"""What each run's job holds (its function, signals and result), by run: the GUI thread lets go of it.

A pool's thread that dropped the last reference to one of them destroyed it there, and a widget or an
object whose signals the GUI thread receives, destroyed off the GUI thread, crashed the process (a
job whose function held the last reference to a parentless widget, its runner gone, did so within a
few hundred runs).  So the run keeps them here too and drops its own references first; then the GUI
thread, told the run has ended, lets go of them (:class:`_Reaper`).  Once the application is gone,
the pool's thread lets go of them itself."""
_keys = itertools.count()


class _Reaper(QObject):
    """Lets go of what a finished run's job held (:data:`_held`), on the GUI thread."""

    ended = Signal(int)

    def __init__(self):
        super().__init__(QCoreApplication.instance())  # goes with the application
        self.ended.connect(self._let_go, Qt.ConnectionType.QueuedConnection)

    @Slot(int)
    def _let_go(self, key: int) -> None:
        _held.pop(key, None)


_reaper: _Reaper | None = None


def _let_go_on_gui_thread(key: int) -> None:
    """Tell the GUI thread that run ``key`` has ended, so it lets go of what its job held."""
    reaper = _reaper
    if reaper is not None and shiboken6.isValid(reaper):
        reaper.ended.emit(key)
    else:
        _held.pop(key, None)


def own_thread(parent: QObject) -> QThreadPool:
    """A pool of one thread for ``parent``'s quick jobs (a picture to paint).

    On the shared pool such a job waited behind the renders, and ran on a thread a render
    had left at its lowered priority (:mod:`core.give_way`) while it held
    Python's lock, which the window then waited for.
    """
    pool = QThreadPool(parent)
    pool.setMaxThreadCount(1)
    return pool


class JobRunner(QObject):
    """Runs one job at a time for its owner; the newest job wins.

    A new job cancels the running one (it stops at its next piece), and only the
    newest job's reports are delivered, none after :meth:`cancel`.
    ``progress_per_second`` and ``prepare`` are those of :class:`JobRun`.

    Signals
    -------
    progress(int percent, object partial)
    finished(object result)
    failed(str message)
    """

    progress = Signal(int, object)
    finished = Signal(object)
    failed = Signal(str)

    def __init__(self, parent: QObject | None = None, pool: QThreadPool | None = None,
                 progress_per_second: float | None = None, prepare: Callable[[], None] | None = None):
        super().__init__(parent)
        self._pool = pool or QThreadPool.globalInstance()
        self._progress_per_second, self._prepare = progress_per_second, prepare
        self._latest = 0
        self._cancel: stopping.StopRequest | None = None
        self._signals = JobSignals(self)
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
        self._cancel = stopping.StopRequest()
        self._start(JobRun(self._latest, job, self._signals, self._cancel, self._progress_per_second,
                           self._prepare))
        return self._latest

    def _start(self, run: JobRun) -> None:
        """Start ``run`` on the pool (at once; a subclass may wait)."""
        self._pool.start(run)

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
