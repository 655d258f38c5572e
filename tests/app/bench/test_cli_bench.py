"""Bad options to the benchmarks: one line naming the option, exit status 2, no traceback.

Each runs in a subprocess, as a user would type it; all are refused before
anything is imported or timed.
"""

from __future__ import annotations

import os
import subprocess
import sys

import pytest
from checkout import ROOT
from unserved_display import unserved_display


def _run(*argv, env=None):
    return subprocess.run([sys.executable, "-m", "app", *argv], cwd=ROOT, capture_output=True, text=True,
                          env=env, timeout=120)


@pytest.mark.parametrize(("argv", "named"), [
    (["bench", "raster", "--triangles", "10k"], "--triangles: '10k' is not a whole number"),
    (["bench", "raster", "--triangles", "10000,5"], "--triangles: 5 is outside"),
    (["bench", "raster", "--runs", "0"], "--runs must be at least 1"),
    (["bench", "raster", "--width", "-3"], "--width must be at least 16"),
    (["bench", "startup", "--runs", "0"], "--runs must be at least 1"),
    (["bench", "trace", "--repeats", "0"], "--repeats must be at least 1, got 0"),
    (["bench", "trace", "--height", "2"], "--height must be at least 16, got 2"),
    (["bench", "gui", "--actions", "picks,dance"], "--actions: expected some of picks, cost, lessons"),
    (["bench", "gui", "--actions", ""], "--actions: expected some of picks, cost, lessons"),
])
def test_bad_benchmark_options_are_one_line_and_exit_2(argv, named):
    out = _run(*argv)
    assert out.returncode == 2
    lines = out.stderr.strip().splitlines()
    assert len(lines) == 1 and named in lines[0], out.stderr
    assert "Traceback" not in out.stderr and out.stdout == ""


@pytest.mark.parametrize("bench", ["startup", "gui"])
@pytest.mark.parametrize("display", ["not set", "nobody answers"])
def test_the_benchmarks_that_open_the_window_say_when_there_is_no_screen_and_how_to_run_them(bench, display):
    """Without a screen Qt aborted `bench gui` (status 134, a core dump); `bench startup` knew of
    DISPLAY unset only, and with a display nobody serves timed its windows' aborts."""
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY", "QT_QPA_PLATFORM")}
    if display == "nobody answers":
        env["DISPLAY"] = unserved_display()
        why = f"no X server answers on display '{env['DISPLAY']}' (DISPLAY)"
    else:
        why = "DISPLAY is not set"
    out = _run("bench", bench, "--runs" if bench == "startup" else "--seconds", "1", env=env)
    assert out.returncode == 2
    said = f"python -m app: error: bench {bench} needs a screen to open the window on: {why}"
    assert out.stderr.strip() == f"{said}; run it under xvfb-run -a"
    assert out.stdout == ""


@pytest.mark.gui
def test_bench_gui_prints_a_row_per_tab_that_follows_the_observer_and_the_opening_apart():
    out = _run("bench", "gui", "--seconds", "0.2", "--size", "800x600", "--actions", "picks")
    assert out.returncode == 0, out.stderr
    lines = out.stdout.splitlines()
    blank = lines.index("")
    rows = {line.split("  ")[0]: line.split() for line in lines[2:blank] if not line.startswith("Opening")}
    assert set(rows) == {"Image order", "Object order", "Four views", "Compare"}
    for words in rows.values():  # longest and p99 stall, draws/s, images/s, full image after stop
        numbers = [float(w) for w in words if w.replace(".", "").isdigit()]
        assert len(numbers) == 5 and numbers[0] >= numbers[1] >= 0 and numbers[4] > 0
    opening = next(line for line in lines if line.startswith("Opening"))
    assert "the 3D pane's first frame after" in opening and "longest stall meanwhile" in opening
    assert lines[blank + 1].split() == ["action", "count", "longest", "stall", "p99", "stall"]
    picks = lines[blank + 2].split()
    assert picks[:4] == ["picked", "pixels,", "2", "tabs"] and picks[4] == "24" and picks[6] == "ms"
    assert len(lines) == blank + 3
