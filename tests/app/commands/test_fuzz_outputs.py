"""Outputs under a file-size limit, and Ctrl+C at generated moments of long jobs (issue 35).

Every run is the real command in its own subprocess.  A write cut short (``ulimit -f``,
as on a full disk: ``RLIMIT_FSIZE`` with SIGXFSZ ignored, so a write fails with
``EFBIG`` rather than killing the process) must exit with status 1 and one line naming
the file, and leave the old file byte for byte and no temporary file.  Ctrl+C (SIGINT)
at a moment drawn by hypothesis must end a render, a cost sweep or an export that would
run for minutes with status 130 (or 0 or 2 if it was done or refused first): no signal
death, no traceback, no hang, the old file byte for byte.  Examples are few and seeded.
"""

from __future__ import annotations

import json
import os
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from checkout import ROOT
from hypothesis import given, settings
from hypothesis import strategies as st
from interrupts import ctrl_c_reaches

ENV = {**os.environ, "PYTHONDONTWRITEBYTECODE": "1"}
OLD = b"the old file, which must survive byte for byte\n"

SCENE = {"camera": {"eye": [3, 4, 6], "target": [0, 0, 0], "width": 48, "height": 36},
         "lights": [{"position": [5, 5, 5]}],
         "objects": [{"type": "box", "center": [0, 0, 0], "size": 1.5},
                     {"type": "sphere", "center": [1.5, 0.2, 0], "radius": 0.6,
                      "material": {"reflectivity": 0.5}}]}
#: 90,000 triangles traced without acceleration at 800 x 600: hours of work.
SLOW_SCENE = {"camera": {"eye": [0, 0, 6], "target": [0, 0, 0], "width": 800, "height": 600},
              "lights": [{"position": [5, 5, 5]}],
              "objects": [{"type": "uv_sphere", "center": [0, 0, 0], "radius": 1.5, "rings": 150,
                           "segments": 300}]}


def _leftovers(folder: Path) -> list[str]:
    return [p.name for p in folder.iterdir() if p.name.endswith((".part", ".tmp"))]


def _limited(limit_bytes: int):
    def start():
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit_bytes, limit_bytes))
    return start


# (command, arguments before the output, output option, file name, file-size limit in bytes): every
# format a command writes, each larger than the limit (measured without it: the PNG 481 bytes, the
# depth 13,952, the statistics 1,254, the GIF and MP4 several KB), the other outputs of the run
# smaller (the image beside the depth, 481 bytes, or beside the statistics at 8 x 6, 99 bytes).
FORMATS = [
    ("render", ["--mode", "raytrace"], "--out", "image.png", 100),
    ("render", ["--mode", "raster"], "--out", "image.jpg", 100),
    ("render", ["--mode", "raster", "--out", "{folder}/image.png"], "--depth-out", "depth.npy", 5000),
    ("render", ["--mode", "raster", "--width", "8", "--height", "6", "--out", "{folder}/image.png"],
     "--stats-out", "stats.json", 500),
    ("export", ["--what", "four-views"], "--out", "views.png", 100),
    ("export", ["--what", "orbit", "--frames", "6"], "--out", "orbit.gif", 100),
    ("export", ["--what", "orbit", "--frames", "6"], "--out", "orbit.mp4", 100),
]


@pytest.mark.parametrize("command, before, option, name, limit", FORMATS,
                         ids=[f"{c} {n.split('.')[-1]} ({o})" for c, _, o, n, _ in FORMATS])
def test_every_output_format_cut_short_exits_1_naming_it_and_keeps_the_old_files(tmp_path, command, before,
                                                                              option, name, limit):
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(SCENE))
    out, image = tmp_path / name, tmp_path / "image.png"
    for path in {out, image}:
        path.write_bytes(OLD)
    command = [sys.executable, "-m", "app", command, str(scene),
               *[a.replace("{folder}", str(tmp_path)) for a in before], option, str(out)]
    result = subprocess.run(command, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=300,
                            preexec_fn=_limited(limit))
    assert result.returncode == 1, result.stderr
    assert "Traceback" not in result.stderr
    last = result.stderr.strip().replace("\r", "\n").splitlines()[-1]  # after any progress bar
    assert str(out) in last and "error" in last
    assert out.read_bytes() == OLD and image.read_bytes() == OLD  # all of a run's files, or none
    assert _leftovers(tmp_path) == []


def test_cost_files_cut_short_exit_1_and_keep_all_three_old_files(tmp_path):
    scene = tmp_path / "scene.json"
    scene.write_text(json.dumps(SCENE))
    out = tmp_path / "cost"
    out.mkdir()
    for name in ("cost.csv", "cost.png", "cost.svg"):
        (out / name).write_bytes(OLD)
    command = [sys.executable, "-m", "app", "cost", str(scene), "--knob", "depth", "--width", "8",
               "--reference-spp", "1", "--out", str(out)]
    result = subprocess.run(command, cwd=ROOT, env=ENV, capture_output=True, text=True, timeout=300,
                            preexec_fn=_limited(100))
    assert result.returncode == 1, result.stderr
    assert "Traceback" not in result.stderr
    assert str(out) in result.stderr.strip().replace("\r", "\n").splitlines()[-1]
    assert all((out / name).read_bytes() == OLD for name in ("cost.csv", "cost.png", "cost.svg"))
    assert _leftovers(out) == []


# --- Ctrl+C at generated moments ------------------------------------------------------------

LONG_JOBS = {
    # every one would run for minutes to hours without Ctrl+C
    "render raytrace, no acceleration": ["render", "{slow}", "--mode", "raytrace", "--accel", "none",
                                         "--out", "{out}.png"],
    "export raster orbit": ["export", "{slow}", "--what", "orbit", "--mode", "raster", "--frames", "1000",
                            "--width", "4096", "--height", "4096", "--out", "{out}.mp4"],
    "cost sweep": ["cost", "{slow}", "--knob", "accel", "--width", "200", "--out", "{out}"],
    "export orbit": ["export", "{slow}", "--what", "orbit", "--mode", "raycast", "--accel", "none",
                     "--frames", "50", "--out", "{out}.mp4"],
}


@settings(max_examples=5, derandomize=True, deadline=None, database=None)
@given(job=st.sampled_from(sorted(LONG_JOBS)), delay=st.floats(0.3, 4.0))
def test_ctrl_c_at_any_moment_of_a_long_job_stops_it_and_keeps_the_old_file(tmp_path_factory, job, delay):
    folder = tmp_path_factory.mktemp("interrupted")
    slow = folder / "slow.json"
    slow.write_text(json.dumps(SLOW_SCENE))
    args = [a.format(slow=slow, out=folder / "out") for a in LONG_JOBS[job]]
    old = folder / "cost" / "cost.csv" if job == "cost sweep" else Path(args[-1])
    if job == "cost sweep":
        args[-1] = str(old.parent)
    old.parent.mkdir(exist_ok=True)
    old.write_bytes(OLD)
    proc = subprocess.Popen([sys.executable, "-m", "app", *args], cwd=ROOT, env=ENV,
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            preexec_fn=ctrl_c_reaches)
    # A moment of the job: loading, checking, rendering, encoding.  (Not the first few milliseconds:
    # before Python has set up its Ctrl+C handler, SIGINT ends any program at once.)
    time.sleep(delay)
    proc.send_signal(signal.SIGINT)
    try:
        _, err = proc.communicate(timeout=60)  # a guard against a hang; the job itself takes hours
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.communicate()
        pytest.fail(f"{job}: still running 60 s after Ctrl+C at {delay:.2f} s")
    assert proc.returncode == 130, f"{job} at {delay:.2f} s: {err[-2000:]}"
    assert "Traceback" not in err
    assert "interrupted" in err.strip().replace("\r", "\n").splitlines()[-1]
    assert old.read_bytes() == OLD
    assert _leftovers(old.parent) == []
