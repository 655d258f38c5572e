"""``python -m app render --heat-out``: what each pixel cost, adding up to the statistics' totals."""

import json
import subprocess
import sys

import numpy as np
import pytest
import verdict_scenes as vs
from checkout import ROOT

from core.files import scene_file


def _render(tmp_path, scene, *args):
    path = tmp_path / "scene.json"
    scene_file.save(scene, path)
    return subprocess.run([sys.executable, "-m", "app", "render", str(path), *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


@pytest.mark.parametrize("accel", ["none", "grid", "bvh"])
def test_traced_heat_adds_up_to_the_stats_and_leaves_the_image_alone(tmp_path, accel):
    heat, stats, out, plain = (tmp_path / n for n in ("heat.npy", "stats.json", "out.png", "plain.png"))
    result = _render(tmp_path, vs.glass_ball(), "--accel", accel, "--out", str(out), "--heat-out", str(heat),
                     "--stats-out", str(stats))
    assert result.returncode == 0, result.stderr
    tests = np.load(heat)
    assert tests.shape == (31, 41, 2) and tests.dtype == np.int64
    numbers = json.loads(stats.read_text())["accel"]
    assert tests[..., 0].sum() == numbers["prim_tests"] > 0
    assert tests[..., 1].sum() == numbers["bounds_tests"] + numbers["cells_visited"]  # cells: grid's boxes
    assert _render(tmp_path, vs.glass_ball(), "--accel", accel, "--out", str(plain)).returncode == 0
    assert plain.read_bytes() == out.read_bytes()


def test_raster_heat_is_the_fragments_per_pixel(tmp_path):
    heat, stats = tmp_path / "heat.npy", tmp_path / "stats.json"
    result = _render(tmp_path, vs.two_quads(), "--mode", "raster", "--out", str(tmp_path / "out.png"),
                     "--heat-out", str(heat), "--stats-out", str(stats))
    assert result.returncode == 0, result.stderr
    fragments = np.load(heat)
    assert fragments.shape == (30, 40)
    assert fragments.sum() == json.loads(stats.read_text())["fragments_generated"]
    x, y = vs.PIXEL
    assert fragments[y, x] == 2  # both quads cover it (see verdict_scenes.two_quads)


def test_a_heat_file_of_another_kind_is_refused_before_rendering(tmp_path):
    result = _render(tmp_path, vs.two_quads(), "--out", str(tmp_path / "out.png"), "--heat-out",
                     str(tmp_path / "heat.txt"))
    assert result.returncode == 2
    assert "--heat-out" in result.stderr and "Traceback" not in result.stderr
    assert not (tmp_path / "out.png").exists()
