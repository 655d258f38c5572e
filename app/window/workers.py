"""Long work runs off the GUI thread, with progress and cancel.

A *job* is a plain function ``job(cancelled, progress) -> result``: it checks
``cancelled`` (a :class:`threading.Event`) between pieces of work and returns
``None`` once it is set, and calls ``progress(percent, partial)`` after each
piece.  :class:`Renderer` runs jobs on the thread pool; a new job supersedes the
running one (it stops at its next piece, and a compiled kernel it is running
stops within a pixel or a triangle, :mod:`core.stopping`), and results of
superseded jobs are never delivered.  Partial results reach the GUI thread at most
:data:`PROGRESS_PER_SECOND` times a second; the ones in between are dropped
(the next one shows more anyway).  Signals are queued onto the GUI thread, so
receivers may touch widgets and VTK.
"""

from __future__ import annotations

import threading
import time
from collections.abc import Callable
from dataclasses import dataclass

from PySide6.QtCore import QObject, QRunnable, QThreadPool, QTimer, Signal

from app.process import render_priority
from app.window import render_budget
from core import stopping
from views.panels.stale_cover import cover, uncover

Job = Callable[[threading.Event, Callable[[int, object], None]], object]
PROGRESS_PER_SECOND = 30


@dataclass(frozen=True)
class Waiting:
    """A job's partial result that says what it waits on (say, kernels compiling) in the progress bar,
    with a partial result to show meanwhile (or None)."""

    what: str
    partial: object = None


class _Signals(QObject):
    progress = Signal(int, int, object)  # job id, percent done, partial result
    finished = Signal(int, object)  # job id, result
    failed = Signal(int, str)  # job id, message


class _Runnable(QRunnable):
    def __init__(self, job_id: int, job: Job, signals: _Signals, cancelled: stopping.StopRequest):
        super().__init__()
        self.job_id, self.job, self.signals, self.cancelled = job_id, job, signals, cancelled
        self._last_progress = -float("inf")

    def run(self):
        if self.cancelled.is_set():  # superseded while it waited for a thread: nothing to do
            return
        render_priority.give_way_to_the_window()
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
        self._cancel = stopping.StopRequest()
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


class RenderSchedule(QObject):
    """Decides when each of the window's tabs renders, and remembers what each one shows.

    - Only the visible tab (:meth:`show_tab`) renders; the others render when shown.
    - While the observer moves (camera changes less than :data:`REST_MS` apart)
      the visible tab gets previews, one at a time and each of the newest
      camera, never a queue; once the observer rests, the full render starts.
    - A newer camera supersedes a running full render at its next band, and a
      full result is shown only for the scene it was rendered from.
    - A job over the memory budget never starts (:mod:`app.window.render_budget`): the
      tab's status says why and what to reduce.

    Tabs are those of :mod:`app.window.tabs` (``title``, ``job(scene, preview)``,
    ``show(result)``, optional ``show_progress``, ``warning``, ``changes`` and ``cost``).

    Signals
    -------
    status_changed(object tab) : the tab's progress or status line changed (see :meth:`status`).
    image_shown(str title, bool preview) : a tab showed a new image (a preview or the full one).
    full_image_shown(str title) : a tab showed the full render of the current scene.
    warned(str) : a word before a very long render.
    refused(str) : a render was not started because it is over the memory budget; the message says why.
    rested() : the observer stopped moving.
    """

    REST_MS = 150

    status_changed = Signal(object)
    image_shown = Signal(str, bool)
    full_image_shown = Signal(str)
    warned = Signal(str)
    refused = Signal(str)
    rested = Signal()

    def __init__(self, model, parent: QObject | None = None):
        super().__init__(parent)
        self.model = model
        self.tabs: list = []
        self.current = None
        self.last_result = None
        self._jobs: dict[str, tuple[object, bool]] = {}  # title -> (scene, preview) of the running job
        self._full_shown: dict[str, object] = {}  # title -> the scene whose full image the tab shows
        self._preview_shown: dict[str, object] = {}
        self._status: dict[str, tuple[int, str, str]] = {}  # title -> percent, progress text, caption
        self._waiting: set[str] = set()  # titles whose job said it waits on something (Waiting)
        self._moving = False
        self._held = False
        self._rest = QTimer(self)
        self._rest.setSingleShot(True)
        self._rest.setInterval(self.REST_MS)
        self._rest.timeout.connect(self._rested)
        model.camera_changed.connect(self._camera_moved)
        model.scene_changed.connect(self._scene_replaced)

    def add(self, tab) -> None:
        """Render ``tab`` when it is visible; it gets its own :class:`Renderer` as ``tab.renderer``."""
        self.tabs.append(tab)
        tab.renderer = Renderer(self)
        tab.renderer.progress.connect(lambda pct, partial, t=tab: self._progress(t, pct, partial))
        tab.renderer.finished.connect(lambda result, t=tab: self._finished(t, result))
        tab.renderer.failed.connect(lambda message, t=tab: self._failed(t, message))
        self._status[tab.title] = (0, f"{tab.title}: not rendered yet", "")
        for signal in getattr(tab, "changes", ()):
            signal.connect(lambda *_, t=tab: self.settings_changed(t))

    def status(self, tab) -> tuple[int, str, str]:
        """``tab``'s progress in percent, its progress-bar text (``%p%`` for the percent) and caption."""
        return self._status[tab.title]

    def busy(self, tab) -> bool:
        return tab.title in self._jobs

    def showing_full(self, tab) -> bool:
        """Whether ``tab`` shows the full render of the current scene and settings."""
        return self._full_shown.get(tab.title) is self.model.scene

    def show_tab(self, tab) -> None:
        """``tab`` is now the visible one: the others stop, it renders what it lacks."""
        self.current = tab
        for other in self.tabs:
            if other is not tab and other.title in self._jobs:
                other.renderer.cancel()
                del self._jobs[other.title]
                self._set_status(other, 0, f"{other.title}: not rendered yet")
        self._update()

    def settings_changed(self, tab) -> None:
        """``tab``'s own settings changed: its image is out of date."""
        self._full_shown.pop(tab.title, None)
        if tab is self.current:
            self._update(force=True)

    def rerender(self) -> None:
        """Render the visible tab again in full."""
        self._full_shown.pop(self.current.title, None)
        self._update(force=True)

    def cancel(self) -> None:
        """Stop the visible tab's render; what was drawn so far stays on screen."""
        tab = self.current
        tab.renderer.cancel()
        self._jobs.pop(tab.title, None)
        self._set_status(tab, None, f"{tab.title}: cancelled at %p% (F5 renders again)")

    def hold(self) -> None:
        """Start no render until :meth:`release` (the window's first frame comes first: loading
        the kernels holds the GIL and would delay it by as much); refusals are still told at once."""
        self._held = True

    def release(self) -> None:
        self._held = False
        self._update()

    def stop(self) -> None:
        self._rest.stop()
        for tab in self.tabs:
            tab.renderer.cancel()

    # ------------------------------------------------------------ inside
    def _camera_moved(self, _camera) -> None:
        self._moving = True
        self._rest.start()
        self._update()

    def _rested(self) -> None:
        self._moving = False
        self._update()
        self.rested.emit()

    def _scene_replaced(self, _scene) -> None:
        self._moving = False
        self._rest.stop()
        self._update()

    def _update(self, force: bool = False) -> None:
        """Start what the visible tab needs next for the current scene, if anything."""
        tab, scene = self.current, self.model.scene
        if tab is None:
            return
        running = self._jobs.get(tab.title)
        if self._moving:
            if running is not None and running[1]:
                return  # a preview is on its way; when it ends, the next one starts from the newest camera
            if self._preview_shown.get(tab.title) is not scene or force:
                self._submit(tab, preview=True)
        elif running is not None and running[0] is scene and not force:
            return  # this scene's full render is under way, or its preview, after which the full one starts
        elif self._full_shown.get(tab.title) is not scene or force:
            self._submit(tab, preview=False)

    def _submit(self, tab, preview: bool) -> None:
        scene = self.model.scene
        refusal, slow = render_budget.check(tab, scene, preview, self.model.memory_limit)
        if refusal:
            tab.renderer.cancel()  # whatever it was rendering is out of date too
            self._jobs.pop(tab.title, None)
            self._set_status(tab, 0, f"{tab.title}: not rendered, over the memory budget", refusal)
            cover(tab.widget, f"Not rendered: what this tab shows is not of the current scene.\n\n{refusal}")
            self.refused.emit(refusal)
            return
        if self._held:
            return  # a refusal is told at once; a render waits for release()
        job = tab.job(scene, preview)
        if job is None:
            self._full_shown[tab.title] = scene  # nothing to render: what it shows is current
            self._set_status(tab, 0, tab.idle)
            return
        self._jobs[tab.title] = (scene, preview)
        tab.renderer.submit(job)
        warning = None if preview else getattr(tab, "warning", lambda _: None)(scene) or slow
        what = "preview while the observer moves" if preview else "rendering"
        self._set_status(tab, 0, f"{tab.title}: {what}… %p%", warning)
        if warning:
            self.warned.emit(warning)

    def _set_status(self, tab, percent: int | None = None, text: str | None = None,
                    caption: str | None = None) -> None:
        old = self._status[tab.title]
        self._status[tab.title] = (old[0] if percent is None else percent, old[1] if text is None else text,
                                   old[2] if caption is None else caption)
        self.status_changed.emit(tab)

    def _progress(self, tab, percent, partial):
        if isinstance(partial, Waiting):  # said until the job's next progress
            self._waiting.add(tab.title)
            self._set_status(tab, percent, f"{tab.title}: {partial.what}… %p%")
            partial = partial.partial
        elif tab.title in self._waiting:
            self._waiting.discard(tab.title)
            self._set_status(tab, percent, f"{tab.title}: rendering… %p%")
        else:
            self._set_status(tab, percent)
        if partial is not None and hasattr(tab, "show_progress"):
            tab.show_progress(partial)

    def _finished(self, tab, result):
        self._waiting.discard(tab.title)
        scene, preview = self._jobs.pop(tab.title)
        if not preview and scene is not self.model.scene:
            return  # a full image of a superseded scene is never shown
        self.last_result = result
        caption = tab.show(result)
        uncover(tab.widget)
        if preview:
            self._preview_shown[tab.title] = scene
            self._set_status(tab, 100, f"{tab.title}: preview (observer moving)", caption)
        else:
            self._full_shown[tab.title] = scene
            self._set_status(tab, 100, f"{tab.title}: done", caption)
        self.image_shown.emit(tab.title, preview)
        if not preview:
            self.full_image_shown.emit(tab.title)
        if tab is self.current:
            self._update()

    def _failed(self, tab, message: str):
        self._waiting.discard(tab.title)
        self._jobs.pop(tab.title, None)
        self._set_status(tab, 0, f"{tab.title}: render failed", f"Render failed — {message}")
        cover(tab.widget, f"Render failed: what this tab shows is not of the current scene.\n\n{message}")
