"""Renders run off the GUI thread, band by band, with progress and cancel.

The GUI thread builds a :class:`RenderRequest` (everything the render needs,
frozen) with an increasing id and hands it to :class:`Renderer`.  A worker on
the thread pool renders the image in bands of rows, reports each band, and
stops as soon as a newer request supersedes it.  Results come back through
Qt signals, queued onto the GUI thread; results of superseded requests are
dropped there too.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass

import numpy as np
from PySide6.QtCore import QObject, QRunnable, QThreadPool, Signal

from core import raycast
from core.scene import Scene

BAND_ROWS = 32


@dataclass(frozen=True)
class RenderRequest:
    request_id: int
    scene: Scene


@dataclass(frozen=True)
class RenderResult:
    """A finished image with the time each stage took (seconds, summed over bands)."""

    request_id: int
    color: np.ndarray
    t: np.ndarray
    timings: dict[str, float]
    tests: int


class _Signals(QObject):
    progress = Signal(int, int, object)  # request id, percent done, partial colour image
    finished = Signal(object)  # RenderResult
    failed = Signal(int, str)  # request id, message


class _Job(QRunnable):
    def __init__(self, request: RenderRequest, signals: _Signals, cancelled: threading.Event):
        super().__init__()
        self.request, self.signals, self.cancelled = request, signals, cancelled

    def run(self):
        try:
            result = render(self.request, self.cancelled, self._progress)
        except Exception as exc:  # reported in the window, never lost silently
            self.signals.failed.emit(self.request.request_id, f"{type(exc).__name__}: {exc}")
            return
        if result is not None:
            self.signals.finished.emit(result)

    def _progress(self, percent, partial):
        self.signals.progress.emit(self.request.request_id, percent, partial)


def render(request: RenderRequest, cancelled=None, progress=None) -> RenderResult | None:
    """Render ``request`` band by band; ``None`` if ``cancelled`` got set."""
    cam = request.scene.camera
    color = np.empty((cam.height, cam.width, 3))
    color[:] = request.scene.background
    t = np.full((cam.height, cam.width), np.inf)
    timings: dict[str, float] = {}
    tests = 0
    for first in range(0, cam.height, BAND_ROWS):
        if cancelled is not None and cancelled.is_set():
            return None
        stop = min(first + BAND_ROWS, cam.height)
        band = raycast.cast(request.scene, rows=(first, stop))
        color[first:stop], t[first:stop] = band.color, band.t
        tests += band.tests
        for stage, seconds in band.timings.items():
            timings[stage] = timings.get(stage, 0.0) + seconds
        if progress is not None:
            progress(round(100 * stop / cam.height), color.copy())
    return RenderResult(request.request_id, color, t, timings, tests)


class Renderer(QObject):
    """Starts renders for the latest scene; older ones are cancelled and ignored.

    Signals
    -------
    progress(int percent, ndarray partial_image)
    finished(RenderResult)
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

    def request(self, scene: Scene) -> int:
        """Render ``scene`` in the background; returns the request id."""
        self.cancel()
        self._latest += 1
        self._cancel = threading.Event()
        self._pool.start(_Job(RenderRequest(self._latest, scene), self._signals, self._cancel))
        return self._latest

    def cancel(self) -> None:
        """Stop the running render, if any; its result will not be shown."""
        if self._cancel is not None:
            self._cancel.set()
            self._cancel = None

    def _on_progress(self, request_id, percent, partial):
        if request_id == self._latest and self._cancel is not None:
            self.progress.emit(percent, partial)

    def _on_finished(self, result: RenderResult):
        if result.request_id == self._latest:
            self._cancel = None
            self.finished.emit(result)

    def _on_failed(self, request_id, message):
        if request_id == self._latest:
            self._cancel = None
            self.failed.emit(message)
