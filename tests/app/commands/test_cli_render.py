"""``python -m app render``: image, depth and statistics files, checked against the scene's geometry."""

import json
import subprocess
import sys

import numpy as np
import pytest
from checkout import ROOT
from PySide6.QtGui import QImage

from core.camera import Camera
from core.files import scene_file
from core.scene import Scene
from core.shapes import quad


def _run(*args):
    return subprocess.run([sys.executable, "-m", "app", "render", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


@pytest.fixture
def ground_scene(tmp_path):
    """A camera looking straight down at a big ground plane from height 5."""
    cam = Camera(eye=(0, 5, 0), target=(0, 0, 0), up=(0, 0, -1), fov_y_deg=60, near=1, far=20,
                 width=40, height=30)
    path = tmp_path / "ground.json"
    scene_file.save(Scene(camera=cam, objects=(quad((0, 0, 0), 6.0),)), path)
    return path


@pytest.mark.parametrize("mode", ["raster", "raycast", "raytrace"])
@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_render_writes_image_depth_and_stats(tmp_path, ground_scene, mode, projection):
    out, depth, stats = tmp_path / "out.png", tmp_path / "depth.npy", tmp_path / "stats.json"
    result = _run(str(ground_scene), "--mode", mode, "--projection", projection, "--out", str(out),
                  "--depth-out", str(depth), "--stats-out", str(stats))
    assert result.returncode == 0, result.stderr
    image = QImage(str(out))
    assert (image.width(), image.height()) == (40, 30)
    d = np.load(depth)
    assert d.shape == (30, 40)
    # Looking straight down from height 5, the ground is at distance 5 along the viewing axis.
    seen = np.isfinite(d)
    assert seen[15, 20] and np.allclose(d[seen], 5.0)
    if projection == "perspective":
        assert not seen[0, 0]  # the 6 x 6 plane does not reach the image corners: +inf there
    numbers = json.loads(stats.read_text())
    assert "times" in numbers
    # A fresh process loads its kernels before the render starts; the statistics still count it.
    assert numbers["compile_s"] > 0


def test_bad_size_is_refused_with_exit_2(tmp_path, ground_scene):
    result = _run(str(ground_scene), "--width", "0", "--out", str(tmp_path / "x.png"))
    assert result.returncode == 2
    assert "--width" in result.stderr and "Traceback" not in result.stderr
