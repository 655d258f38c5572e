"""Work that would hold Python's lock for long runs in a process of its own.

Only one thread of a process runs Python at a time, and some work keeps that lock for all of a long
call: matplotlib's mathtext typesets formulas in pure Python, and ``flip_evaluator`` holds the lock
for the whole of its C++ (a 640×480 FLIP takes 277 ms, and meanwhile a 1 ms sleep of another thread
took 187-270 ms).  Run on a worker thread of the window's process, either kept the window's thread
waiting: after a new text size the thread typesetting formulas ran 230 ms of a 330 ms stall.

:func:`call` runs a function of a module in a helper process for that module instead: one process per
module (``python -m core.helper_process MODULE``), started at the module's first call, which reads
requests on its standard input and answers each in turn on its standard output.  It ends when its
input closes, as when the window's process ends, however that ends, and quietly when that happens
during a call.  It runs in a session of its own,
so that Ctrl+C at the terminal reaches the window's process alone, which decides how to end, and it
ignores an interrupt sent to it anyway.  It runs at a lower priority (:mod:`core.give_way`, as the
renders' threads do), so that the window's thread gets a core first.  If a
helper cannot be started, or dies, the call runs in this process, as it would without one (the
same result, a slower window).

Arguments and results cross as pickles: arrays of a few megabytes take a few milliseconds.
"""

from __future__ import annotations

import importlib
import os
import pickle
import subprocess
import sys
import threading
from pathlib import Path

from core import give_way


class _Helper:
    """The helper process of one module, asked one call at a time."""

    def __init__(self, module: str):
        root = str(Path(__file__).resolve().parents[1])  # where the core package is, installed or not
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")])))
        # A session of its own: Ctrl+C at the terminal goes to the window's process alone.
        self.process = subprocess.Popen([sys.executable, "-m", "core.helper_process", module],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env,
                                        start_new_session=True)
        self.lock = threading.Lock()

    def ask(self, function: str, args: tuple, kwargs: dict):
        pickle.dump((function, args, kwargs), self.process.stdin)
        self.process.stdin.flush()
        ok, answer = pickle.load(self.process.stdout)  # EOFError if the helper died
        if not ok:
            raise answer
        return answer


_helpers: dict[str, _Helper | None] = {}  # by module; None once its helper could not start or died
_starting = threading.Lock()


def helper(module: str) -> _Helper | None:
    """The helper process of ``module``, started if it is not yet (``None``: calls run here)."""
    with _starting:
        if module not in _helpers:
            try:
                _helpers[module] = _Helper(module)
            except OSError:
                _helpers[module] = None
        return _helpers[module]


def call(module: str, function: str, *args, **kwargs):
    """``module.function(*args, **kwargs)``, run in ``module``'s helper process; what it returns, or
    raises."""
    runner = helper(module)
    if runner is not None:
        with runner.lock:
            try:
                return runner.ask(function, args, kwargs)
            except (OSError, EOFError, pickle.UnpicklingError):  # the helper is gone: run it here
                _helpers[module] = None
    return getattr(importlib.import_module(module), function)(*args, **kwargs)


def _serve(module: str, requests, answers) -> None:
    """The helper's loop: run each request, answer ``(True, result)`` or ``(False, exception)``."""
    functions = importlib.import_module(module)
    while True:
        try:
            function, args, kwargs = pickle.load(requests)
        except EOFError:  # the window's process closed its end: it has ended
            return
        try:
            answer = (True, getattr(functions, function)(*args, **kwargs))
        except Exception as exc:  # raised again by the caller
            answer = (False, exc)
        try:
            data = pickle.dumps(answer)
        except Exception as why:  # a result or exception that does not pickle: its message does
            shown = why if answer[0] else answer[1]
            data = pickle.dumps((False, RuntimeError(f"{type(shown).__name__}: {shown}")))
        try:
            answers.write(data)
            answers.flush()
        except BrokenPipeError:  # the window's process ended while this call ran: no one to answer
            # What is left in the buffer goes nowhere at exit, not into a second error (Python's
            # documentation on SIGPIPE does the same).
            os.dup2(os.open(os.devnull, os.O_WRONLY), answers.fileno())
            return


if __name__ == "__main__":
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    give_way.lower_this_process()
    answers = os.fdopen(os.dup(1), "wb")  # the answers' own copy of standard output ...
    os.dup2(2, 1)  # ... and whatever a library prints goes to standard error, not among them
    sys.stdout = sys.stderr
    _serve(sys.argv[1], sys.stdin.buffer, answers)
