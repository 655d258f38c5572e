"""``python -m app bench gui``: does the window stay responsive while the observer moves?

Opens the main window on the lecture scene under the current display, and
for each tab in turn moves the observer along a scripted path (an orbit
with a slow rise and fall) 25 times a second for ``--seconds`` seconds,
then lets it rest.  Per tab it prints:

- the longest and the 99th-percentile *stall* of the GUI thread: how late a
  timer that should fire every 5 ms actually fired (ms);
- how many camera changes the 3D pane actually drew per second;
- how many fresh images (preview or full) the tab's observer image showed
  per second while moving;
- the time from the last move to the full-resolution image of the last
  camera (ms).

Then the window's other work that a user waits on (``--actions``), each with the
GUI thread's longest and 99th-percentile stall: picking pixels of the traced
image (the ray tree and its worked math) and of the rasterized one (the pixel's
fragments, the z-buffer's verdict), a Cost sweep of every knob,
stepping through every step of every lesson (until its formulas are shown),
scene edits (move, colour, add, delete, then undo each), exports (a pane's
picture, the 3D pane, the z-buffer steps as a GIF written in the background),
entering and leaving presentation mode, and the text size ×1.5, ×2 and back.

With ``--cold`` the user's cache folder (``XDG_CACHE_HOME``: the formula cache,
matplotlib's font list) is an empty one, as on a first run, the compiled kernels
and Mesa's compiled shaders excepted: the actions run once so, then again with the formulas kept on disk
meanwhile (those in memory forgotten, as in a new process), and both tables are
printed.  The tabs' rows and the opening are of the first run.

With ``--why`` it also prints, per tab and action, what the GUI thread was doing
in its longest stall (:mod:`app.bench.stall_why`).

The numba kernels are compiled (or loaded from their cache) before the
window opens, so the figures are the window's, not the compiler's.

This is a benchmark, not a test; nothing here is asserted.  Run it under
``xvfb-run -a -s "-screen 0 1920x1080x24"`` on a machine without a display.
"""

from __future__ import annotations

import math
import time

MOVES_PER_SECOND = 25
TICK_MS = 5
ACTIONS = ("picks", "cost", "lessons", "edits", "export", "present", "text", "hard")
PICKS = 12
"""Pixels picked in the traced image, and as many in the rasterized one (their fragments' history), at
places drawn from a seeded generator."""
AFTER_S = 0.3
"""How long each action's stalls are still counted after it is done (the 3D pane's draws, repaints)."""


def add_arguments(parser) -> None:
    """Add the benchmark's options to ``parser`` (the ``bench gui`` subcommand)."""
    parser.add_argument("--seconds", type=float, default=6.0,
                        help="how long the observer moves on each tab (default 6)")
    parser.add_argument("--size", default="1600x900", help="window size WxH in pixels (default 1600x900)")
    parser.add_argument("--why", action="store_true",
                        help="per tab, the GUI thread's stack in its longest stall and where the time went")
    parser.add_argument("--actions", default=",".join(ACTIONS),
                        help=f"other work to time, comma-separated from {', '.join(ACTIONS)}, or none "
                             "(default: all)")
    parser.add_argument("--cold", action="store_true",
                        help="start with an empty formula cache (a first run), and time the actions "
                             "again once it is filled")


def _size(text: str) -> tuple[int, int]:
    from app.usage import UsageError

    try:
        w, h = (int(v) for v in text.lower().split("x"))
    except ValueError:
        raise UsageError(f"--size: expected WIDTHxHEIGHT such as 1600x900, got {text!r}") from None
    if not (200 <= w <= 10000 and 200 <= h <= 10000):
        raise UsageError(f"--size: width and height must be within 200..10000 pixels, got {text!r}")
    return w, h


class _Ticker:
    """Times the GUI thread: a timer that should fire every TICK_MS, and how late it fired."""

    def __init__(self, why: bool = False):
        from PySide6.QtCore import QTimer

        from app.bench.stall_why import StallWhy

        self.why = StallWhy() if why else None
        self.ticks: list[float] = []
        self._timer = QTimer()
        self._timer.setInterval(TICK_MS)
        self._timer.timeout.connect(self._tick)

    def _tick(self):
        self.ticks.append(time.perf_counter())
        if self.why is not None:
            self.why.tick()

    def start(self):
        self.ticks = []
        self._tick()
        self._timer.start()

    def stop(self):
        self._timer.stop()
        if self.why is not None:
            self.why.stop()

    def stalls_ms(self):
        import numpy as np

        gaps = np.diff(self.ticks) * 1000.0 - TICK_MS
        return (float(gaps.max()), float(np.percentile(gaps, 99))) if len(gaps) else (0.0, 0.0)

    def longest_stall_why(self) -> list[str]:
        """What the GUI thread did in the longest stall (``--why``), innermost frame first."""
        import numpy as np

        gaps = np.diff(self.ticks) * 1000.0
        if self.why is None or not len(gaps):
            return []
        i = int(np.argmax(gaps))
        return self.why.explain(i, float(gaps[i]), outer="app/bench/gui.py")


class _Probe(_Ticker):
    """Counts what the user would notice on one tab: stalls, 3D draws, fresh images."""

    def __init__(self, window, view, why: bool = False):
        super().__init__(why)
        self.window, self.view = window, view
        self.draws = 0
        self.images = 0
        self._last_drawn = None
        ren_win = window.scene_view.plotter.ren_win
        self._observer = ren_win.AddObserver("EndEvent", self._drawn)
        self._original = view.set_image
        view.set_image = self._image_set

    def _drawn(self, *_):
        import numpy as np

        corners = np.array(self.window.scene_view.frustum.points)
        if self._last_drawn is None or not np.array_equal(corners, self._last_drawn):
            self.draws += 1
        self._last_drawn = corners

    def _image_set(self, *args, **kwargs):
        self.images += 1
        return self._original(*args, **kwargs)

    def start(self):
        self.draws = self.images = 0
        super().start()

    def stop(self):
        super().stop()
        self.window.scene_view.plotter.ren_win.RemoveObserver(self._observer)
        del self.view.set_image


def _actions(text: str) -> list[str]:
    from app.usage import UsageError

    names = [] if text.strip() == "none" else [n.strip() for n in text.split(",") if n.strip()]
    unknown = [n for n in names if n not in ACTIONS]
    if unknown or not names and text.strip() != "none":
        raise UsageError(f"--actions: expected some of {', '.join(ACTIONS)} (comma-separated) or none, "
                         f"got {text!r}")
    return names


def _observer_image(window, title: str):
    """The image pane of ``title``'s tab that shows the observer's own view."""
    widget = window.tab(title).widget
    key = {"Four views": "observer", "Compare": "a"}.get(title)
    return widget.views[key] if key else widget.image


def _wait(app, done, timeout_s: float = 600.0) -> None:
    """Run the window's events until ``done()`` (or ``timeout_s``)."""
    from PySide6.QtCore import QEventLoop

    # Sleep until the next event, as the window's own event loop does: a loop that polls
    # would keep one of the cores busy and slow the renders and VTK it measures.
    end = time.perf_counter() + timeout_s
    while not done() and time.perf_counter() < end:
        app.processEvents(QEventLoop.ProcessEventsFlag.WaitForMoreEvents)


def _open(app, window, why: bool = False) -> dict:
    """Show the window and wait for its first full image and the 3D pane's first frame.

    Both come once per run, before any observer moves: VTK's first frame (its shaders
    compiled and the scene's buffers filled) is drawn on the GUI thread.  What the
    GUI thread's ticks saw meanwhile is returned, so the tabs' figures are of the moving
    observer alone and the opening's cost is still printed.
    """
    ticker = _Ticker(why)
    ticker.start()
    t0 = time.perf_counter()
    window.show()
    title = window.tab_titles()[0]
    pane = window.scene_view
    _wait(app, lambda: window.showing_full(title) and pane.view is not None
          and pane.view.plotter.picture is not None)
    ticker.stop()
    longest, _ = ticker.stalls_ms()
    return {"tab": "Opening", "longest": longest, "seconds": time.perf_counter() - t0,
            "why": ticker.longest_stall_why()}


def _bench_tab(app, window, title: str, seconds: float, why: bool = False) -> dict:
    from PySide6.QtCore import QEventLoop, QTimer

    WAIT = QEventLoop.ProcessEventsFlag.WaitForMoreEvents

    def wait_idle():
        """Until the tab shows the full image of the current camera."""
        _wait(app, lambda: window.showing_full(title))

    window.show_tab(title)
    wait_idle()
    probe = _Probe(window, _observer_image(window, title), why)
    start_cam = window.model.camera
    moves = int(seconds * MOVES_PER_SECOND)
    state = {"i": 0}

    def move():
        i = state["i"] = state["i"] + 1
        yaw = start_cam.yaw_deg + 1.5 * i
        pitch = max(-80.0, min(80.0, start_cam.pitch_deg + 10.0 * math.sin(i / 20)))
        window.model.set_camera(start_cam.orbit(yaw, pitch))
        if i >= moves:
            mover.stop()

    mover = QTimer()
    mover.setInterval(1000 // MOVES_PER_SECOND)
    mover.timeout.connect(move)
    probe.start()
    t0 = time.perf_counter()
    mover.start()
    while mover.isActive():
        app.processEvents(WAIT)
    moving = time.perf_counter() - t0
    draws, images = probe.draws, probe.images
    stopped = time.perf_counter()
    wait_idle()
    settle = time.perf_counter() - stopped
    longest, p99 = probe.stalls_ms()
    probe.stop()
    reasons = probe.longest_stall_why()
    window.model.set_camera(start_cam)
    wait_idle()
    return {"tab": title, "longest": longest, "p99": p99, "draws": draws / moving,
            "images": images / moving, "full": settle * 1000.0, "why": reasons}


def _bench_action(app, window, name: str, steps, why: bool) -> dict:
    """Time the GUI thread while each of ``steps`` (``(start, done)`` callables) is started and
    waited for, plus :data:`AFTER_S` each."""
    ticker = _Ticker(why)
    ticker.start()
    count = 0
    for start, done in steps:
        start()
        _wait(app, done)
        end = time.perf_counter() + AFTER_S
        _wait(app, lambda end=end: time.perf_counter() >= end)
        count += 1
    ticker.stop()
    longest, p99 = ticker.stalls_ms()
    return {"tab": name, "count": count, "longest": longest, "p99": p99, "why": ticker.longest_stall_why()}


def _picks(window):
    import random

    window.show_tab("image order")
    cam, rng = window.model.camera, random.Random(0)
    for _ in range(PICKS):
        x, y = rng.randrange(cam.width), rng.randrange(cam.height)
        yield (lambda x=x, y=y: window.pick_ray_tree(x, y),
               lambda x=x, y=y: window.ray_tree is not None and window.ray_tree[:2] == (x, y))
    window.show_tab("object order")
    panel = window.tab("object order").widget
    for _ in range(PICKS):
        x, y = rng.randrange(cam.width), rng.randrange(cam.height)
        yield (lambda x=x, y=y: panel.pick_pixel(x, y),
               lambda x=x, y=y: window.showing_full("object order") and window.model.buffer_pixel == (x, y))


def _cost_sweep(window):
    window.show_tab("cost")
    panel = window.tab("cost").widget
    panel.knob.setCurrentIndex(panel.knob.findData("all"))
    yield panel.run, lambda: panel.finished or not panel.running


def _lesson_steps(window):
    # The lessons the panel holds: reading the lesson files here (100 ms on the GUI thread, while the
    # clock ran) counted the bench's own work as the first step's stall.
    for i, lesson in enumerate(window.lesson_panel.lessons()):
        for k in range(len(lesson.steps)):
            yield (lambda i=i, k=k: window.lesson_panel.select(i, k),
                   lambda: window.showing_full(window.current.title)
                   and not window.lesson_panel.typesetting())


def _scene_edits(window):
    """Move the first object, colour it, add a sphere, delete it, then undo the four edits; each waits
    for the full image of the edited scene."""
    import numpy as np

    from core import checked_edits

    window.show_tab("image order")
    editor, model, first = window.editor, window.model, ("object", 0)
    shown = lambda: window.showing_full("image order")  # noqa: E731

    def move():
        editor.move(first, checked_edits.position_of(model.scene, first) + np.array([0.25, 0.0, 0.0]))

    def delete_last():
        model.set_selection(("object", len(model.scene.objects) - 1))
        editor.delete()

    yield move, shown
    yield lambda: editor.change_field(first, "material.color", [0.1, 0.9, 0.2]), shown
    yield lambda: editor.add_object("sphere"), shown
    yield delete_last, shown
    for _ in range(4):
        yield editor.stack.undo, shown


def _exports(window):
    """Export the traced image's pane as PNG and the 3D pane as PNG, then start writing the z-buffer
    steps as a GIF (in the background) and wait until it is written; into a folder removed after."""
    import os
    import tempfile

    from app.export.pane_pictures import tab_pictures

    window.show_tab("image order")
    folder = tempfile.TemporaryDirectory(prefix="bench-gui-")
    written = []
    window.exports.exported.connect(written.append)
    pane, shot, steps = (os.path.join(folder.name, name) for name in ("pane.png", "3d.png", "steps.gif"))
    picture = tab_pictures(window.tab("image order"))[0]
    yield lambda: window.exports.export_picture(picture, pane), lambda: pane in written
    yield lambda: window.exports.export_3d(shot), lambda: shot in written
    yield lambda: window.exports.export_steps(steps), lambda: steps in written
    window.exports.exported.disconnect(written.append)
    folder.cleanup()


def _presentation(window):
    """Enter presentation mode and leave it, twice."""
    presentation = window.presentation
    for on in (True, False, True, False):
        yield (lambda on=on: presentation.set_presenting(on),
               lambda on=on: presentation.presenting() == on and presentation.settled()
               and not window.lesson_panel.typesetting())


def _text_sizes(window):
    """The text size ×1.5, ×2 and back to ×1 (View → Text size), each until the formulas are typeset."""
    for scale in (1.5, 2.0, 1.0):
        yield (lambda scale=scale: window.presentation.set_scale(scale),
               lambda: not window.lesson_panel.typesetting())


def _hard_cases(window):
    """Choose each hard case in turn, then move its slider to both ends, each until its result is shown."""
    window.show_tab("hard cases")
    panel = window.tab("hard cases").widget
    shown = []
    panel.result_shown.connect(shown.append)

    def showing() -> bool:
        return bool(shown) and panel.result.name == panel.case_name and panel.status.text() != "computing…"

    for row in range(panel.cases.count()):
        if row != panel.cases.currentRow():
            yield lambda row=row: (shown.clear(), panel.cases.setCurrentRow(row)), showing
        for end in (panel.slider.minimum(), panel.slider.maximum()):
            if panel.slider.isVisibleTo(panel) and end != panel.slider.value():
                yield lambda end=end: (shown.clear(), panel.slider.setValue(end)), showing
    panel.result_shown.disconnect(shown.append)


_ACTION_STEPS = {"picks": ("picked pixels, 2 tabs", _picks), "cost": ("Cost sweep, all knobs", _cost_sweep),
                 "lessons": ("lesson steps", _lesson_steps), "edits": ("scene edits", _scene_edits),
                 "export": ("exports", _exports), "present": ("presentation on/off", _presentation),
                 "text": ("text size", _text_sizes), "hard": ("hard cases and sliders", _hard_cases)}


def _print_actions(done: list[dict], title: str = "") -> None:
    if title:
        print(f"\n{title}")
    print(f"{'' if title else chr(10)}{'action':<24}{'count':>6}{'longest stall':>15}{'p99 stall':>11}")
    for r in done:
        print(f"{r['tab']:<24}{r['count']:>6}{r['longest']:>12.0f} ms{r['p99']:>8.0f} ms")


def _forget_formulas() -> None:
    """Forget the formulas typeset in this process, as a new process would (those on disk stay)."""
    from views.text import math_view

    math_view._typeset.cache_clear()


def run(args) -> int:
    width, height = _size(args.size)
    actions = _actions(args.actions)
    from app.window.display_check import require_display

    require_display("bench gui")
    import os
    import tempfile

    cold = (tempfile.TemporaryDirectory(prefix="bench-gui-cache-", ignore_cleanup_errors=True)
            if args.cold else None)
    if cold is not None:  # an empty cache folder (formulas, matplotlib's fonts), as on a first run ...
        from core.compiling.kernel_cache import cache_root

        os.environ.setdefault("NUMBA_CACHE_DIR", str(cache_root()))  # ... but the kernels compiled,
        # and the 3D pane's shaders as Mesa compiled them (on an empty Mesa cache the first smooth
        # draw compiles them on the GUI thread: 167 ms, once per machine and graphics driver)
        os.environ.setdefault("MESA_SHADER_CACHE_DIR",
                              os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"))
        os.environ["XDG_CACHE_HOME"] = cold.name
    from PySide6.QtCore import QThreadPool
    from PySide6.QtWidgets import QApplication

    from app.process.lock_turns import hand_over_often
    from app.process.long_lived import set_aside_once_loaded
    from app.window.main_window import MainWindow
    from core import presets
    from core.image_order import ray_tracing
    from core.object_order import pipeline
    from views.text import math_view

    ray_tracing.ensure_compiled()  # compile (or load) the kernels first: this measures the window
    pipeline.ensure_compiled()
    app = QApplication.instance() or QApplication([])
    window = MainWindow(presets.lecture_scene())
    window.resize(width, height)
    set_aside_once_loaded(window)  # as python -m app does
    hand_over_often()
    opening = _open(app, window, args.why)
    # Tabs that draw what the observer sees; Hard cases and Cost do not follow the observer.
    following = [t for t in window.tab_titles()
                 if hasattr(window.tab(t).widget, "image") or hasattr(window.tab(t).widget, "views")]
    rows = [_bench_tab(app, window, title, args.seconds, args.why) for title in following]
    cam = window.model.camera
    done = [_bench_action(app, window, _ACTION_STEPS[a][0], _ACTION_STEPS[a][1](window), args.why)
            for a in actions]
    warm = []
    if cold is not None and actions:
        _forget_formulas()
        warm = [_bench_action(app, window, _ACTION_STEPS[a][0], _ACTION_STEPS[a][1](window), args.why)
                for a in actions]
    print(f"window {width} x {height}, lecture scene {cam.width} x {cam.height}, "
          f"observer moved {MOVES_PER_SECOND}x/s for {args.seconds:g} s per tab")
    print(f"{'tab':<14}{'longest stall':>15}{'p99 stall':>11}{'3D draws/s':>12}"
          f"{'images/s':>10}{'full image after stop':>23}")
    for r in rows:
        print(f"{r['tab']:<14}{r['longest']:>12.0f} ms{r['p99']:>8.0f} ms{r['draws']:>12.1f}"
              f"{r['images']:>10.1f}{r['full']:>20.0f} ms")
    print(f"Opening (once, before the observer moves): the first image and the 3D pane's first frame "
          f"after {opening['seconds']:.2f} s; the GUI thread's longest stall meanwhile "
          f"{opening['longest']:.0f} ms (VTK's first frame is drawn on it)")
    if done and cold is None:
        _print_actions(done)
    elif done:
        _print_actions(done, "first run (an empty formula cache):")
        _print_actions(warm, "warm (the formulas on disk):")
    for r in [opening, *rows, *done, *warm] if args.why else ():
        print(f"\n{r['tab']}, the longest stall: " + "\n".join(r["why"]))
    window.close()
    QThreadPool.globalInstance().waitForDone()
    # The formulas still queued are dropped, as when the window quits (typesetting them all took
    # half a minute with an empty cache), and the one being typeset is waited for.
    math_view.stop_typesetting(-1)
    if cold is not None:
        cold.cleanup()
    return 0
