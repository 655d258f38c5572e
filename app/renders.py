"""The window's renders run off the GUI thread, with progress and cancel.

A render is a job of :mod:`views.jobs` (``job(cancelled, progress) -> result``).
:class:`Renderer` runs the jobs of one tab, the newest winning; its job's thread
gives way to the window (:mod:`core.give_way`), and partial results
reach the GUI thread at most :data:`PROGRESS_PER_SECOND` times a second.
:class:`RenderSchedule` decides when each tab renders.
"""

from __future__ import annotations

import time
from dataclasses import dataclass

from PySide6.QtCore import QObject, QThreadPool, QTimer, Signal

from app import render_budget
from core import give_way
from views.jobs import JobRun, JobRunner
from views.panels.pane_cover import cover, uncover

PROGRESS_PER_SECOND = 30


@dataclass(frozen=True)
class Waiting:
    """A job's partial result that says what it waits on (say, kernels compiling) in the progress bar,
    and why, with a partial result to show meanwhile (or None).  The bar counts the seconds of the
    wait (:meth:`said`): a bar at 0% for a minute would look like a window that hangs."""

    what: str
    why: str = ""
    partial: object = None

    def said(self, title: str, seconds: float) -> str:
        """The progress bar's text for tab ``title`` after ``seconds`` of the wait."""
        why = f" ({self.why})" if self.why else ""
        return f"{title}: {self.what}, {seconds:.0f} s so far{why}"


class Renderer(JobRunner):
    """Runs one render at a time for its owner; the newest wins (:class:`views.jobs.JobRunner`).

    Its jobs' threads give way to the window, and their partial results are thinned to
    :data:`PROGRESS_PER_SECOND` a second, what a screen can show.

    A job starts at the next turn of the event loop, and only if no newer one came meanwhile.  A
    lesson step changes the settings, the scene and the tab in one turn, and each change asks
    for a render: each one's thread began at once, and all but the last were cancelled, but
    meanwhile they ran Python beside the GUI thread, which waited for the lock while it drew
    the step (``bench gui``, the lesson steps' longest stall: 80-111 ms in four runs, 66-103 in five since).
    """

    def __init__(self, parent: QObject | None = None, pool: QThreadPool | None = None):
        super().__init__(parent, pool, progress_per_second=PROGRESS_PER_SECOND,
                         prepare=give_way.lower_this_thread)
        self._next: JobRun | None = None
        self._turn = QTimer(self)
        self._turn.setSingleShot(True)
        self._turn.setInterval(0)
        self._turn.timeout.connect(self._start_next)

    def _start(self, run: JobRun) -> None:
        self._next = run  # replaces one submitted earlier in this turn, which never starts
        self._turn.start()

    def _start_next(self) -> None:
        run, self._next = self._next, None
        if run is not None:  # cancelled since, it returns at once (JobRun.run)
            super()._start(run)


class RenderSchedule(QObject):
    """Decides when each of the window's tabs renders, and remembers what each one shows.

    - Only the visible tab (:meth:`show_tab`) renders; the others render when shown.
    - While the observer moves (camera changes less than :data:`REST_MS` apart)
      the visible tab gets previews, one at a time and each of the newest
      camera, never a queue; once the observer rests, the full render starts.
    - A newer camera supersedes a running full render at its next band, and a
      full result is shown only for the scene it was rendered from.
    - A job over the memory budget never starts (:mod:`app.render_budget`): the
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
        # title -> (tab, its job's Waiting, when the wait began): the tabs whose job said it waits
        self._waiting: dict[str, tuple[object, Waiting, float]] = {}
        self._wait_clock = QTimer(self)  # counts the waits' seconds in their tabs' status
        self._wait_clock.setInterval(1000)
        self._wait_clock.timeout.connect(self._count_waits)
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
        elif self._status[tab.title][1] == f"{tab.title}: not rendered yet":
            # Its full picture of this scene is shown; a render cancelled as another tab came to the
            # front had said otherwise.
            self._set_status(tab, 100, f"{tab.title}: done")

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
            # A newer job of the tab (the full render after a preview) waits on the same compile.
            began = self._waiting.get(tab.title, (None, None, time.monotonic()))[2]
            self._waiting[tab.title] = (tab, partial, began)
            self._set_status(tab, percent, partial.said(tab.title, time.monotonic() - began))
            self._wait_clock.start()
            partial = partial.partial
        elif not self._end_wait(tab, percent):
            self._set_status(tab, percent)
        if partial is not None and hasattr(tab, "show_progress"):
            tab.show_progress(partial)

    def _count_waits(self) -> None:
        for tab, waiting, began in self._waiting.values():
            self._set_status(tab, None, waiting.said(tab.title, time.monotonic() - began))

    def _stop_waiting(self, tab) -> bool:
        """The tab's job no longer waits; whether it did."""
        waited = self._waiting.pop(tab.title, None) is not None
        if not self._waiting:
            self._wait_clock.stop()
        return waited

    def _end_wait(self, tab, percent) -> bool:
        """If the tab's job last said what it waits on, the bar stops saying it; whether it did."""
        if not self._stop_waiting(tab):
            return False
        self._set_status(tab, percent, f"{tab.title}: rendering… %p%")
        return True

    def _finished(self, tab, result):
        scene, preview = self._jobs.pop(tab.title)
        if not preview and scene is not self.model.scene:
            self._stop_waiting(tab)
            return  # a full image of a superseded scene is never shown
        # A job whose progress after the wait was thinned away ends it before its image shows.
        self._end_wait(tab, None)
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
        self._stop_waiting(tab)
        self._jobs.pop(tab.title, None)
        self._set_status(tab, 0, f"{tab.title}: render failed", f"Render failed — {message}")
        cover(tab.widget, f"Render failed: what this tab shows is not of the current scene.\n\n{message}")
