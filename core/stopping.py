"""Stopping a long job at once: Ctrl+C on the command line, Cancel in the window.

Python notices Ctrl+C, or a job's cancel flag, only between its own
statements.  A compiled kernel (numba, without Python's lock) can run for
minutes, or hours with ``--accel none`` on a large image, without returning
to Python.  So a kernel that may run long reads a *stop flag*, one element of
an array it is given anyway, at least once per pixel or ray; the flag is
raised from another thread and the kernel returns within milliseconds, its
result incomplete.  The caller then raises :class:`StoppedError` instead of using
that result.

A :class:`StopRequest` is a :class:`threading.Event` that also raises the
flag of every kernel watching it (:func:`watching`).  A kernel watches
:data:`EVERY_JOB` (the command line's Ctrl+C) and the request of its own
thread, if one was set with :func:`stopped_by` (the window's Cancel).
"""

from __future__ import annotations

import contextlib
import threading

import numpy as np


class StoppedError(Exception):
    """A job was asked to stop (Ctrl+C or Cancel) before it finished; its result is incomplete."""


class StopRequest(threading.Event):
    """An event that, when set, raises the stop flag of every kernel watching it."""

    def __init__(self):
        super().__init__()
        self._lock = threading.Lock()
        self._flags: list[tuple[np.ndarray, int]] = []

    def set(self) -> None:
        with self._lock:
            super().set()
            for array, index in self._flags:
                array[index] = 1

    @contextlib.contextmanager
    def _watched(self, array: np.ndarray, index: int):
        entry = (array, index)
        with self._lock:
            self._flags.append(entry)
            if self.is_set():
                array[index] = 1
        try:
            yield
        finally:
            with self._lock:  # by identity: ``==`` on two entries would compare their arrays
                self._flags = [flag for flag in self._flags if flag is not entry]


EVERY_JOB = StopRequest()
"""Set by Ctrl+C on the command line (:mod:`app.process.ctrl_c`): every running kernel stops."""

_thread = threading.local()


@contextlib.contextmanager
def stopped_by(request: StopRequest):
    """Kernels run by this thread inside the ``with`` also watch ``request`` (a job's Cancel)."""
    previous = getattr(_thread, "request", None)
    _thread.request = request
    try:
        yield
    finally:
        _thread.request = previous


@contextlib.contextmanager
def watching(array: np.ndarray, index: int):
    """While the ``with`` runs, a stop request sets ``array[index]`` to 1; raises :class:`StoppedError`
    at the end if it was set.

    ``array[index]`` is the kernel's stop flag; it starts at 0.
    """
    array[index] = 0
    requests = [EVERY_JOB, *filter(None, [getattr(_thread, "request", None)])]
    with contextlib.ExitStack() as stack:
        for request in requests:
            stack.enter_context(request._watched(array, index))
        yield
    if array[index]:
        raise StoppedError("stopped before it finished")

