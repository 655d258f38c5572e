"""Work that would hold Python's lock runs in a helper process: what it returns or raises comes back
as from a call here, and a helper that dies, or a Ctrl+C, or the end of the window's process, loses
nothing and leaves nothing running."""

import math
import os
import signal
import subprocess
import sys
import threading

import pytest
from checkout import ROOT
from process_ends import ended

from core import give_way, helper_process


@pytest.fixture
def os_helper():
    """The helper of the ``os`` module (a call there tells which process ran it); forgotten afterwards."""
    yield helper_process.helper("os")
    helper_process._helpers.pop("os", None)


def test_a_call_runs_in_the_modules_helper_and_gives_back_what_it_returns(os_helper):
    pid = helper_process.call("os", "getpid")
    assert pid == os_helper.process.pid != os.getpid()
    assert helper_process.call("math", "fsum", [0.1] * 10) == 1.0  # exactly, as math.fsum here


def test_calls_from_several_threads_each_get_their_own_answer():
    answers = {}
    def ask(k):
        answers[k] = helper_process.call("math", "factorial", k)

    threads = [threading.Thread(target=ask, args=(k,)) for k in range(20)]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(60)
    assert answers == {k: math.factorial(k) for k in range(20)}


def test_what_the_call_raises_is_raised_here_and_the_helper_goes_on():
    with pytest.raises(ValueError, match="math domain error"):
        helper_process.call("math", "sqrt", -1.0)
    with pytest.raises(RuntimeError, match="pickle"):  # a result that cannot cross: said, not a hang
        helper_process.call("threading", "Lock")
    assert helper_process.call("math", "sqrt", 16.0) == 4.0


def test_ctrl_c_leaves_the_helper_to_the_window(os_helper):
    assert helper_process.call("os", "getpid") == os_helper.process.pid  # serving
    assert os.getsid(os_helper.process.pid) != os.getsid(0)  # out of the terminal's reach ...
    os.kill(os_helper.process.pid, signal.SIGINT)  # ... and an interrupt sent to it anyway is ignored
    assert helper_process.call("os", "getpid") == os_helper.process.pid
    assert os_helper.process.poll() is None


def test_the_helper_gives_way_to_the_window(os_helper):
    assert helper_process.call("os", "getpid") == os_helper.process.pid
    assert os.getpriority(os.PRIO_PROCESS, os_helper.process.pid) == (
        os.getpriority(os.PRIO_PROCESS, 0) + give_way.NICE)


def test_a_helper_that_died_is_replaced_by_running_the_call_here(os_helper):
    os_helper.process.kill()
    os_helper.process.wait(30)
    assert helper_process.call("os", "getpid") == os.getpid()
    assert helper_process.call("os", "getpid") == os.getpid()  # and from then on


WINDOW = """
import sys
from core import helper_process
print(helper_process.call("os", "getpid"), flush=True)
sys.stdin.read()  # until killed
"""


def test_the_helper_ends_with_the_window_process_however_that_ends():
    window = subprocess.Popen([sys.executable, "-c", WINDOW], cwd=ROOT, stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True)
    try:
        pid = int(window.stdout.readline())
        assert pid != window.pid and not ended(pid, 0.5)  # it lives while the window does
    finally:
        window.kill()  # no clean-up of its own at all
        window.wait(60)
    assert ended(pid)


ASKED_AND_KILLED = """
import pickle, sys
from core import helper_process
helper = helper_process.helper("time")
pickle.dump(("sleep", (1.0,), {}), helper.process.stdin)  # a call under way, as _Helper.ask makes it ...
helper.process.stdin.flush()
print(helper.process.pid, flush=True)
sys.stdin.read()  # ... when this process is killed
"""


def test_a_window_process_killed_during_a_call_leaves_the_helper_to_end_quietly():
    # The helper answered into the closed pipe: "BrokenPipeError" and its traceback on the terminal.
    window = subprocess.Popen([sys.executable, "-c", ASKED_AND_KILLED], cwd=ROOT, stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        pid = int(window.stdout.readline())
    finally:
        window.kill()
        window.wait(60)
    said = window.stderr.read()  # to its end: the helper, which shares it, has closed it too
    assert ended(pid)
    assert said == ""
