"""Jobs off the GUI thread (views/jobs.py): every report reaches the GUI thread unless thinned,
a cancelled or superseded job delivers nothing, a failure is told, reports carry their job's id, and
what a job held is let go of on the GUI thread."""

import functools
import threading

import shiboken6
from PySide6.QtCore import QThreadPool
from turns_in_a_process import ran_to_the_end

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


def test_what_a_job_held_is_let_go_on_the_gui_thread(qtbot):
    # A widget destroyed off the GUI thread crashes the process (the next test), and so may an object
    # whose signals the GUI thread receives.  Here the job's function (with what it holds) and its result
    # are each last held by the run: they must still go on the GUI thread.
    on_gui_thread = []

    class Witness:
        def __del__(self):
            on_gui_thread.append(threading.current_thread() is threading.main_thread())

    runner, gate = JobRunner(), threading.Event()

    def work(held, cancelled, progress):
        gate.wait(10)
        return Witness()

    job = functools.partial(work, Witness())  # the job's function holds a witness

    runner.finished.connect(lambda result: None)  # the result reaches the GUI thread and is dropped
    runner.submit(job)
    del job  # the run holds the only reference now
    with qtbot.waitSignal(runner.finished, timeout=10_000):
        gate.set()
    qtbot.waitUntil(lambda: len(on_gui_thread) == 2)
    assert on_gui_thread == [True, True]


JOBS = "from views.jobs import JobRunner"


def test_a_widget_a_job_held_last_does_not_crash_the_process(tmp_path):
    # It was destroyed on the pool's thread when the run ended: a segmentation fault within a few
    # hundred runs (a test worker died so once in about nine full runs, though which job it was is
    # not known).
    ran_to_the_end("""
    gate = threading.Event()

    def job(cancelled, progress, widget=QWidget()):  # a parentless widget: the job's to keep
        gate.wait(1)

    runner = JobRunner()
    runner.submit(job)
    del job, runner  # the run holds the only reference to the widget now
    gate.set()
""", tmp_path, JOBS)


def test_a_runner_deleted_while_its_job_reports_does_not_crash_the_process(tmp_path):
    # Its signals object, then a child of the runner, was destroyed while a pool's thread emitted
    # one of its signals: a segmentation fault within the first few runs, three times in three.
    ran_to_the_end("""
    started = threading.Event()

    def job(cancelled, progress):  # reports as fast as it can until it is stopped
        started.set()
        for i in range(200_000):
            if cancelled.is_set():
                return None
            progress(i % 100, i)
        return "done"

    runner = JobRunner()
    runner.progress.connect(lambda percent, partial: None)
    runner.submit(job)
    started.wait(5)
    shiboken6.delete(runner)  # its owner goes while the job reports
""", tmp_path, JOBS)


def test_a_job_whose_runner_is_deleted_stops_at_its_next_report(qtbot):
    runner = JobRunner()
    started, stopped = threading.Event(), threading.Event()

    def job(cancelled, progress):
        started.set()
        while not cancelled.wait(0.001):  # a piece of work, then its report
            progress(0, None)
        stopped.set()

    runner.submit(job)
    qtbot.waitUntil(started.is_set, timeout=10_000)
    shiboken6.delete(runner)
    qtbot.waitUntil(stopped.is_set, timeout=10_000)


def test_a_run_never_started_lets_go_of_its_job(qtbot):
    # A render superseded in the turn it was asked for never starts (app.renders): what its
    # job held must not be kept for it.
    freed = []

    class Witness:
        def __del__(self):
            freed.append(1)

    def work(held, cancelled, progress):
        return None

    runs = [JobRun(k, functools.partial(work, Witness()), JobSignals()) for k in range(20)]
    assert not freed
    del runs
    assert len(freed) == 20
