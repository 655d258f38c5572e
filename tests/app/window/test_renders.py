"""Background jobs: the newest job wins, a cancelled one stops early, failures are reported."""

import math
import os
import threading
import time

from app.renders import PROGRESS_PER_SECOND, Renderer
from core.give_way import NICE


def _counting_job(value, release: threading.Event | None = None):
    def job(cancelled, progress):
        if release is not None:
            release.wait(10)
        for pct in (50, 100):
            if cancelled.is_set():
                return None
            progress(pct, value)
        return value

    return job


def test_a_job_reports_progress_then_its_result(qtbot):
    renderer = Renderer()
    seen = []
    renderer.progress.connect(lambda pct, partial: seen.append((pct, partial)))
    with qtbot.waitSignal(renderer.finished, timeout=10000) as blocker:
        renderer.submit(_counting_job("image"))
    assert blocker.args == ["image"]
    qtbot.waitUntil(lambda: len(seen) >= 1)
    assert seen[0] == (50, "image")  # the first partial result always arrives
    assert not renderer.busy


def test_a_burst_of_partial_results_is_thinned_to_what_a_screen_can_show(qtbot):
    renderer = Renderer()
    seen = []
    renderer.progress.connect(lambda pct, partial: seen.append(partial))
    took = []

    def chatty(cancelled, progress):
        start = time.perf_counter()
        for i in range(2000):
            progress(i * 100 // 2000, i)
        took.append(time.perf_counter() - start)
        return "done"

    with qtbot.waitSignal(renderer.finished, timeout=10000):
        renderer.submit(chatty)
    qtbot.waitUntil(lambda: len(seen) >= 1)
    assert seen[0] == 0
    # At most one partial per 1/PROGRESS_PER_SECOND s of the job's run, plus the first one.
    assert len(seen) <= 1 + math.ceil(took[0] * PROGRESS_PER_SECOND) < 2000


def test_only_the_newest_job_is_delivered(qtbot):
    renderer = Renderer()
    delivered = []
    renderer.finished.connect(delivered.append)
    release = threading.Event()
    renderer.submit(_counting_job("old", release))  # still waiting when superseded
    renderer.submit(_counting_job("new"))
    release.set()
    qtbot.waitUntil(lambda: not renderer.busy, timeout=10000)
    assert delivered == ["new"]


def test_renders_asked_for_in_one_turn_start_after_it_and_only_the_last(qtbot):
    # A lesson step changes the settings, the scene and the tab in one turn of the event loop,
    # each asking for a render.  None may start while the turn lasts (its thread would run Python
    # beside the GUI thread drawing the step), and only the last one ever starts.
    renderer = Renderer()
    started = {name: threading.Event() for name in ("settings", "scene", "tab")}

    def job(name):
        def run(cancelled, progress):
            started[name].set()
            return name
        return run

    for name in started:
        renderer.submit(job(name))
    assert renderer.busy
    assert not started["tab"].wait(0.2)  # the turn is not over: no thread has begun
    with qtbot.waitSignal(renderer.finished, timeout=10000) as blocker:
        pass
    assert blocker.args == ["tab"]
    assert [name for name, event in started.items() if event.is_set()] == ["tab"]


def test_a_failing_job_is_reported_not_lost(qtbot):
    renderer = Renderer()

    def broken(cancelled, progress):
        raise ValueError("scene has no camera")

    with qtbot.waitSignal(renderer.failed, timeout=10000) as blocker:
        renderer.submit(broken)
    assert blocker.args == ["ValueError: scene has no camera"]


def test_a_job_runs_at_a_lower_priority_than_the_window(qtbot):
    """Linux: a render thread is nicer than the GUI thread, so the window gets a core first."""
    renderer = Renderer()
    got = []
    renderer.finished.connect(got.append)
    renderer.submit(lambda cancelled, progress: os.getpriority(os.PRIO_PROCESS, threading.get_native_id()))
    qtbot.waitUntil(lambda: bool(got))
    window = os.getpriority(os.PRIO_PROCESS, threading.get_native_id())
    assert got[0] == max(window, NICE) > window
