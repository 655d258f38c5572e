"""bench gui --why: the stack of a stall names the function that held the GUI thread up."""

import sys
import time

from app.bench.stall_why import LOOK_AFTER_S, StallWhy


def _hold_the_thread_up(seconds):
    end = time.perf_counter() + seconds
    while time.perf_counter() < end:
        pass


def test_a_stall_shows_its_cause_and_where_the_time_went():
    why = StallWhy()
    why.tick()
    _hold_the_thread_up(3 * LOOK_AFTER_S)  # the stall: no tick meanwhile
    why.tick()
    why.stop()
    lines = why.explain(0, 3000 * LOOK_AFTER_S, outer="_pytest/")
    frames = lines[1:] if sys.platform.startswith("linux") else lines
    names = [frame.split()[-1] for frame in frames]
    assert names[:2] == ["_hold_the_thread_up", "test_a_stall_shows_its_cause_and_where_the_time_went"]
    assert not any("_pytest" in frame for frame in frames)  # cut where the outer code begins
    if sys.platform.startswith("linux"):
        assert "the GUI thread worked" in lines[0] and "for a core" in lines[0]


def test_a_short_gap_has_no_stack():
    why = StallWhy()
    why.tick()
    why.tick()
    why.stop()
    assert "no stack" in why.explain(0, 1.0, outer="_pytest/")[-1]
