"""``python -m app export``: pictures and animations written headless, bad arguments refused in one line."""

from __future__ import annotations

import subprocess
import sys
from dataclasses import replace

import imageio.v2 as iio2
import imageio.v3 as iio
import numpy as np
import pytest
from checkout import ROOT
from interrupts import ctrl_c_ignored, ctrl_c_reaches

from app.export.picture_sheet import MARGIN, TITLE_ROW
from core.files import scene_file
from core.presets import lecture_scene, zbuffer_three_polygons
from core.srgb import to_srgb8


def _run(*args):
    return subprocess.run([sys.executable, "-m", "app", "export", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


@pytest.fixture
def lecture(tmp_path):
    path = tmp_path / "lecture.json"
    scene = lecture_scene()
    scene_file.save(replace(scene, camera=scene.camera.replace(width=64, height=48)), path)
    return path


@pytest.fixture
def three_polygons(tmp_path):
    path = tmp_path / "three.json"
    scene_file.save(zbuffer_three_polygons(), path)
    return path


def _background8():
    return to_srgb8(np.asarray(lecture_scene().background)).astype(int)


@pytest.mark.parametrize("mode", ["raster", "raycast", "raytrace"])
def test_an_image_is_written_at_the_scene_size_and_shows_the_scene(tmp_path, lecture, mode):
    out = tmp_path / "image.png"
    result = _run(str(lecture), "--what", "image", "--mode", mode, "--out", str(out))
    assert result.returncode == 0, result.stderr
    pixels = iio.imread(out)
    assert pixels.shape == (48, 64, 3)
    # The ground fills the lower half; the sky above it is the background colour.
    assert (np.abs(pixels[0, 0].astype(int) - _background8()) <= 1).all()
    assert np.abs(pixels.astype(int) - _background8()).max(axis=2).mean() > 10
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 10


@pytest.mark.parametrize("what", ["zbuffer", "four-views", "compare"])
def test_sheets_hold_their_panels_and_are_not_blank(tmp_path, lecture, what):
    out = tmp_path / f"{what}.png"
    result = _run(str(lecture), "--what", what, "--out", str(out))
    assert result.returncode == 0, result.stderr
    pixels = iio.imread(out)
    columns = {"zbuffer": 1, "four-views": 2, "compare": 3}[what]
    assert pixels.shape[1] >= columns * 64 + (columns + 1) * MARGIN
    assert pixels.shape[0] >= 48 * (2 if what == "four-views" else 1)
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 20  # images, scale and text, not a blank sheet


def test_zbuffer_steps_gif_has_one_frame_per_polygon_plus_the_cleared_buffers(tmp_path, three_polygons):
    out = tmp_path / "steps.gif"
    result = _run(str(three_polygons), "--what", "zbuffer-steps", "--out", str(out))
    assert result.returncode == 0, result.stderr
    frames = iio.imread(out, index=None)
    scene = zbuffer_three_polygons()
    assert len(frames) == len(scene.objects) + 1  # three triangles facing the observer, then step 0
    w, h = scene.camera.width, scene.camera.height
    x, y = MARGIN, MARGIN + TITLE_ROW  # the image memory panel, top left of each frame

    def memory(frame):
        return frame[y:y + h, x:x + w, :3].astype(int)

    background = to_srgb8(np.asarray(scene.background)).astype(int)
    assert np.abs(memory(frames[0]) - background).max() <= 3  # GIF's palette may move a colour slightly
    for before, after in zip(frames[:-1], frames[1:], strict=True):
        assert np.abs(memory(after) - memory(before)).max() > 20  # each step draws (and tints) a polygon
    assert len({f.shape for f in frames}) == 1


def test_orbit_mp4_is_written_and_readable(tmp_path, lecture):
    out = tmp_path / "orbit.mp4"
    result = _run(str(lecture), "--what", "orbit", "--frames", "6", "--out", str(out))
    assert result.returncode == 0, result.stderr
    reader = iio2.get_reader(out)
    frames = [frame for frame in reader]
    reader.close()
    assert len(frames) == 6
    assert frames[0].shape == (48, 64, 3)
    # The observer walks around: the first and the middle frame show the scene from opposite sides.
    assert np.abs(frames[0].astype(int) - frames[3].astype(int)).mean() > 3
    assert "orbit" in result.stderr  # the progress bar


def test_orbit_gif_has_the_frames_asked_for(tmp_path, lecture):
    out = tmp_path / "orbit.gif"
    result = _run(str(lecture), "--what", "orbit", "--frames", "4", "--mode", "raycast", "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert len(iio.imread(out, index=None)) == 4


@pytest.mark.parametrize(("args", "fragment"), [
    (["--what", "image", "--out", "{tmp}/x.gif"], "--out"),
    (["--what", "orbit", "--out", "{tmp}/x.png"], "--out"),
    (["--what", "orbit", "--frames", "0", "--out", "{tmp}/x.gif"], "--frames"),
    (["--what", "image", "--frames", "3", "--out", "{tmp}/x.png"], "--frames"),
    (["--what", "compare", "--pair", "perspective,photo", "--out", "{tmp}/x.png"], "--pair"),
    (["--what", "orbit", "--fps", "0", "--out", "{tmp}/x.gif"], "--fps"),
    (["--what", "image", "--width", "0", "--out", "{tmp}/x.png"], "--width"),
    (["--what", "image", "--out", "{tmp}/no-such-folder/x.png"], "does not exist"),
    (["--what", "image", "--out", "{scene}"], "input"),
])
def test_bad_arguments_exit_2_with_one_line(tmp_path, lecture, args, fragment):
    args = [a.format(tmp=tmp_path, scene=lecture) for a in args]
    result = _run(str(lecture), *args)
    assert result.returncode == 2, result.stderr
    assert "Traceback" not in result.stderr
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert fragment in result.stderr
    assert not [p for p in tmp_path.iterdir() if p.suffix in (".png", ".gif", ".mp4")]


def test_a_missing_scene_file_exits_2_with_one_line(tmp_path):
    result = _run(str(tmp_path / "nothing.json"), "--what", "image", "--out", str(tmp_path / "x.png"))
    assert result.returncode == 2
    assert len(result.stderr.strip().splitlines()) == 1 and "nothing.json" in result.stderr


def test_zbuffer_grey_is_the_distance_between_near_and_far(tmp_path):
    # Looking straight down from height 5 at a ground plane: every covered pixel is 5 units away.
    from core.camera import Camera
    from core.scene import Scene
    from core.shapes import quad

    cam = Camera(eye=(0, 5, 0), target=(0, 0, 0), up=(0, 0, -1), near=1, far=20, width=40, height=30)
    scene = tmp_path / "ground.json"
    scene_file.save(Scene(camera=cam, objects=(quad((0, 0, 0), 100.0),)), scene)
    out = tmp_path / "z.png"
    result = _run(str(scene), "--what", "zbuffer", "--out", str(out))
    assert result.returncode == 0, result.stderr
    panel = iio.imread(out)[MARGIN + TITLE_ROW:MARGIN + TITLE_ROW + 30, MARGIN:MARGIN + 40]
    assert (np.abs(panel.astype(int) - round((5 - 1) / (20 - 1) * 255)) <= 1).all()


def test_dry_run_checks_and_writes_nothing(tmp_path, lecture):
    out = tmp_path / "orbit.mp4"
    result = _run(str(lecture), "--what", "orbit", "--dry-run", "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert "nothing rendered" in result.stdout
    assert not out.exists()


def _orbit_interrupted(tmp_path, lecture, frames: int, preexec_fn):
    """Start an orbit export, press Ctrl+C once its frames are being rendered; ``(status, stderr, out)``."""
    import signal

    out = tmp_path / "orbit.gif"
    proc = subprocess.Popen([sys.executable, "-m", "app", "export", str(lecture), "--what", "orbit",
                             "--frames", str(frames), "--out", str(out)], cwd=ROOT, stderr=subprocess.PIPE,
                            stdout=subprocess.PIPE, text=True, preexec_fn=preexec_fn)
    assert "orbit" in proc.stderr.read(40)  # the progress bar has started: frames are being rendered
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=120)
    return proc.returncode, err, out


def test_ctrl_c_during_an_animation_stops_cleanly_and_writes_nothing(tmp_path, lecture):
    status, err, _ = _orbit_interrupted(tmp_path, lecture, 1000, ctrl_c_reaches)
    assert status == 130
    assert "interrupted" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == [lecture]


def test_an_export_started_to_ignore_ctrl_c_ignores_it_and_finishes(tmp_path, lecture):
    # As under nohup, or started with "&" from a script: the user asked for Ctrl+C to be ignored.
    status, err, out = _orbit_interrupted(tmp_path, lecture, 120, ctrl_c_ignored)
    assert status == 0 and "Traceback" not in err
    assert len(iio.imread(out, index=None)) == 120


def test_zbuffer_steps_of_too_many_polygons_are_refused_before_rendering(tmp_path):
    from core.presets_trace import PRESETS_TRACE

    scene = tmp_path / "sphere.json"  # one analytic sphere: 3,968 triangles in object order
    scene_file.save(PRESETS_TRACE["lone_sphere"][1](), scene)
    out = tmp_path / "steps.gif"
    result = _run(str(scene), "--what", "zbuffer-steps", "--out", str(out))
    assert result.returncode == 2
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr  # no progress bar: nothing rendered
    assert "--what zbuffer-steps" in result.stderr and "fewer objects or triangles" in result.stderr
    assert not out.exists()


def test_a_zbuffer_steps_gif_over_the_memory_limit_is_refused_and_mp4_suggested(tmp_path, lecture):
    # 110 triangles at 64 x 48: up to 111 frames of 152 x 184 pixels, about 9 MB held by a GIF.
    out = tmp_path / "steps.gif"
    result = _run(str(lecture), "--what", "zbuffer-steps", "--memory-limit", "4M", "--out", str(out))
    assert result.returncode == 2
    assert len(result.stderr.strip().splitlines()) == 1, result.stderr
    assert "MP4" in result.stderr
    assert not out.exists()
    mp4 = _run(str(lecture), "--what", "zbuffer-steps", "--memory-limit", "4M", "--dry-run",
               "--out", str(tmp_path / "steps.mp4"))
    assert mp4.returncode == 0, mp4.stderr
