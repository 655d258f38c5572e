"""Formulas are typeset in a process of their own, so that mathtext's Python never holds the window's
interpreter; the pictures are those this process would typeset, and a process that dies or cannot be
started costs only the window's speed."""

import os
import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from checkout import ROOT

from views.text import typesetting_process

QUADRATIC = r"$t = \frac{-b \pm \sqrt{b^2 - 4ac}}{2a}$"


@pytest.fixture
def typeset_here(monkeypatch):
    """The formulas this process typesets itself, from now on."""
    here, ink = [], typesetting_process.ink
    monkeypatch.setattr(typesetting_process, "ink", lambda *args: (here.append(args[0]), ink(*args))[1])
    return here


def _child() -> subprocess.Popen:
    typesetting_process.typeset("$x$", 10.0, "#000000", 96.0)  # started, if it was not
    child = typesetting_process._child[0]
    assert child is not None and child.process.poll() is None
    return child.process


def test_the_process_typesets_the_same_picture_this_process_would(typeset_here):
    args = (QUADRATIC, 14.0, "#1f77b4", 144.0)
    picture = typesetting_process.typeset(*args)
    assert typeset_here == []  # typeset elsewhere
    reference = typesetting_process.ink(*args)
    assert picture.dtype == np.uint8 and picture.shape == reference.shape and picture.shape[2] == 4
    assert np.array_equal(picture, reference)
    assert (picture[..., :3][picture[..., 3] > 0] == (31, 119, 180)).all()  # the colour asked for


def test_a_formula_that_is_not_mathtext_is_refused_with_where(typeset_here):
    with pytest.raises(ValueError, match=r"\\frac"):
        typesetting_process.typeset(r"$\frac{a$", 12.0, "#000000", 96.0)
    assert typeset_here == []
    assert typesetting_process.typeset("$a$", 12.0, "#000000", 96.0).shape[2] == 4  # and it goes on


def test_ctrl_c_at_the_terminal_leaves_the_typesetting_to_the_window():
    process = _child()
    os.kill(process.pid, signal.SIGINT)  # the terminal sends it to every process of the window
    assert typesetting_process.typeset(r"$\beta_{interrupted}$", 11.0, "#000000", 96.0).shape[2] == 4
    assert process.poll() is None


def test_a_typesetting_process_that_died_is_replaced_by_typesetting_here(typeset_here):
    process = _child()
    process.kill()
    process.wait(30)
    picture = typesetting_process.typeset(QUADRATIC, 12.5, "#000000", 96.0)
    assert typeset_here == [QUADRATIC]
    assert np.array_equal(picture, typesetting_process.ink(QUADRATIC, 12.5, "#000000", 96.0))
    typesetting_process._child.clear()  # the next test starts a process again


WINDOW = """
import sys
from views.text import typesetting_process
typesetting_process.typeset("$x$", 10.0, "#000000", 96.0)
print(typesetting_process._child[0].process.pid, flush=True)
sys.stdin.read()  # until killed
"""


def _ended(pid: int, timeout_s: float = 60.0) -> bool:
    """Whether process ``pid`` ends within ``timeout_s`` (a zombie waiting for its new parent has ended)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        try:
            with open(f"/proc/{pid}/stat") as stat:
                if stat.read().rsplit(")", 1)[1].split()[0] == "Z":
                    return True
        except FileNotFoundError:
            return True
        time.sleep(0.05)  # a process, not the GUI: nothing to wait on but its entry in /proc
    return False


def test_the_typesetting_process_ends_with_the_window_process_however_that_ends():
    window = subprocess.Popen([sys.executable, "-c", WINDOW], cwd=ROOT, stdin=subprocess.PIPE,
                              stdout=subprocess.PIPE, text=True)
    try:
        pid = int(window.stdout.readline())
        assert not _ended(pid, 0.5)  # it lives while the window does
    finally:
        window.kill()  # no clean-up of its own at all
        window.wait(60)
    assert _ended(pid)
