"""Opening a bad scene file from the command line: one clear message, exit status 2, no window."""

import json
import subprocess
import sys

from checkout import ROOT


def _run(*args):
    return subprocess.run([sys.executable, "-m", "app", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=60, env={"PATH": "", "QT_QPA_PLATFORM": "offscreen"})


def test_bad_scene_file_names_every_problem_and_exits_2(tmp_path):
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({
        "camera": {"near": 5, "far": 2},
        "objects": [{"type": "box", "center": [0, 0, 0], "size": 1},
                    {"type": "sphere", "center": [0, 0, 0], "radius": -1}],
    }))
    out = _run(str(bad))
    assert out.returncode == 2
    assert "camera.far" in out.stderr
    assert "objects[1].radius: must be > 0, got -1" in out.stderr
    assert "Traceback" not in out.stderr


def test_missing_scene_file_exits_2(tmp_path):
    out = _run(str(tmp_path / "nowhere.json"))
    assert out.returncode == 2
    assert "not found" in out.stderr
    assert "Traceback" not in out.stderr
