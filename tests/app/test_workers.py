"""Background jobs: the newest job wins, a cancelled one stops early, failures are reported."""

import threading

from app.workers import Renderer


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
    qtbot.waitUntil(lambda: len(seen) == 2)
    assert seen == [(50, "image"), (100, "image")]
    assert not renderer.busy


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


def test_a_failing_job_is_reported_not_lost(qtbot):
    renderer = Renderer()

    def broken(cancelled, progress):
        raise ValueError("scene has no camera")

    with qtbot.waitSignal(renderer.failed, timeout=10000) as blocker:
        renderer.submit(broken)
    assert blocker.args == ["ValueError: scene has no camera"]
