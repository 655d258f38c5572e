"""Jobs off the GUI thread (views/jobs.py): every report reaches the GUI thread unless thinned,
a cancelled or superseded job delivers nothing, a failure is told, reports carry their job's id."""

import threading

from PySide6.QtCore import QThreadPool

from core import stopping
from views.jobs import JobRun, JobRunner, JobSignals


def test_unthinned_every_partial_result_arrives_in_order(qtbot):
    # The Cost panel's sweep sends each measured setting as a partial result: none may be dropped.
    runner = JobRunner()
    seen = []
    runner.progress.connect(lambda percent, partial: seen.append((percent, partial)))

    def chatty(cancelled, progress):
        for i in range(500):
            progress(i // 5, i)
        return "done"

    with qtbot.waitSignal(runner.finished, timeout=10_000) as blocker:
        runner.submit(chatty)
    assert blocker.args == ["done"]
    assert seen == [(i // 5, i) for i in range(500)]
    assert not runner.busy


def test_a_cancelled_job_delivers_nothing_and_frees_the_runner(qtbot):
    runner = JobRunner()
    started, release = threading.Event(), threading.Event()

    def job(cancelled, progress):
        started.set()
        release.wait(10)
        progress(50, "late")
        return "late"

    with qtbot.assertNotEmitted(runner.finished, wait=200), qtbot.assertNotEmitted(runner.progress):
        runner.submit(job)
        qtbot.waitUntil(started.is_set, timeout=10_000)
        runner.cancel()
        assert not runner.busy
        release.set()


def test_a_job_stopped_inside_its_work_is_neither_a_result_nor_a_failure(qtbot):
    runner = JobRunner()
    started, ended = threading.Event(), threading.Event()

    def job(cancelled, progress):
        started.set()
        try:
            cancelled.wait(10)
            raise stopping.StoppedError("stopped in the kernel")
        finally:
            ended.set()

    with qtbot.assertNotEmitted(runner.failed, wait=200), qtbot.assertNotEmitted(runner.finished):
        runner.submit(job)
        qtbot.waitUntil(started.is_set, timeout=10_000)  # inside its work, not still waiting for a thread
        runner.cancel()
        qtbot.waitUntil(ended.is_set, timeout=10_000)


def test_prepare_runs_on_the_jobs_own_thread_before_the_job(qtbot):
    gui = threading.get_ident()
    order = []
    runner = JobRunner(prepare=lambda: order.append(("prepare", threading.get_ident())))
    with qtbot.waitSignal(runner.finished, timeout=10_000):
        runner.submit(lambda cancelled, progress: order.append(("job", threading.get_ident())) or "ok")
    (first, prepare_thread), (second, job_thread) = order
    assert (first, second) == ("prepare", "job")
    assert prepare_thread == job_thread != gui


def test_runs_report_under_their_own_ids(qtbot):
    # The Hard cases panel keeps several runs in flight and tells their results apart by id.
    pool = QThreadPool()
    pool.setMaxThreadCount(1)
    signals = JobSignals()
    results = {}
    signals.finished.connect(lambda job_id, result: results.__setitem__(job_id, result))
    signals.failed.connect(lambda job_id, message: results.__setitem__(job_id, message))
    pool.start(JobRun(-1, lambda c, p: "prefetched", signals))
    pool.start(JobRun(7, lambda c, p: 1 / 0, signals))
    pool.start(JobRun(8, lambda c, p: "asked for", signals))
    qtbot.waitUntil(lambda: len(results) == 3, timeout=10_000)
    assert results == {-1: "prefetched", 7: "ZeroDivisionError: division by zero", 8: "asked for"}
