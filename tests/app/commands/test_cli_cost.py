"""``python -m app cost``: the CSV, the plot files and the one-line errors, run as a user would."""

import csv
import subprocess
import sys

import imageio.v3 as iio
import numpy as np
import pytest
from checkout import ROOT

from core.accuracy.sweep import CSV_COLUMNS, KNOBS, unavailable
from core.files import scene_file
from core.presets_trace import mirror_and_glass


def _run(*args):
    return subprocess.run([sys.executable, "-m", "app", "cost", *args], cwd=ROOT, capture_output=True,
                          text=True, timeout=600)


@pytest.fixture(scope="module")
def mirror_scene(tmp_path_factory):
    path = tmp_path_factory.mktemp("scene") / "mirror.json"
    scene_file.save(mirror_and_glass(), path)
    return path


def _rows(folder):
    with open(folder / "cost.csv", newline="") as f:
        return list(csv.DictReader(f))


def test_all_knobs_give_one_row_per_setting_a_knee_each_and_a_plot(tmp_path, mirror_scene):
    out = tmp_path / "out"
    result = _run(str(mirror_scene), "--knob", "all", "--width", "32", "--reference-spp", "2",
                  "--out", str(out))
    assert result.returncode == 0, result.stderr
    rows = _rows(out)
    assert tuple(rows[0]) == CSV_COLUMNS
    offered = [k for k in KNOBS if unavailable(k, mirror_and_glass()) is None]
    assert [(r["knob"], r["value"]) for r in rows] == [
        (k, KNOBS[k].label(v)) for k in offered for v in KNOBS[k].values]
    for knob in offered:
        assert sum(int(r["knee"]) for r in rows if r["knob"] == knob) == 1
    for r in rows:
        if r["knob"] == "accel":
            assert float(r["rmse"]) == 0.0 and float(r["wrong_pixel_fraction"]) == 0.0
    assert "changes time only" in result.stdout and "<-- knee" in result.stdout
    image = iio.imread(out / "cost.png")
    assert image.ndim == 3 and image.shape[0] > 200 and image[..., :3].std() > 10  # not blank
    assert (out / "cost.svg").read_text().lstrip().startswith("<?xml")
    assert not list(out.glob(".*.tmp"))  # temporary files were renamed into place
    assert "%" in result.stderr  # the progress bar


def test_one_knob_on_the_tracer(tmp_path, mirror_scene):
    out = tmp_path / "depth"
    result = _run(str(mirror_scene), "--knob", "depth", "--mode", "raycast", "--width", "24",
                  "--reference-spp", "2", "--tolerance", "0.5", "--out", str(out))
    assert result.returncode == 0, result.stderr
    rows = _rows(out)
    assert {r["mode"] for r in rows} == {"raytrace"}  # ray depth belongs to ray tracing
    # with a huge tolerance every setting is "as good", so the knee is the cheapest in the knob's
    # order (depth 0), whatever the noisy timings say
    assert [r["value"] for r in rows if r["knee"] == "1"] == [str(KNOBS["depth"].values[0])]
    assert np.isfinite([float(r["flip"]) for r in rows]).all()


@pytest.mark.parametrize(("args", "names"), [
    (["missing.json"], "missing.json"),
    (["{scene}", "--tolerance", "-1"], "--tolerance"),
    (["{scene}", "--tolerance", "nan"], "--tolerance"),
    (["{scene}", "--width", "0"], "--width"),
    (["{scene}", "--runs", "2"], "--runs"),
    (["{scene}", "--reference-spp", "0"], "--reference-spp"),
    (["{lecture}", "--knob", "tessellation"], "no analytic spheres"),
    (["{bad}"], "bad.json"),
    (["{scene}", "--out-is-a-file"], "--out"),
])
def test_bad_arguments_exit_2_with_one_line(tmp_path, mirror_scene, args, names):
    from core.presets import lecture_scene

    lecture = tmp_path / "lecture.json"
    scene_file.save(lecture_scene(), lecture)
    bad = tmp_path / "bad.json"
    bad.write_text('{"objects": [{"type": "sphere", "radius": -1}]')
    a_file = tmp_path / "a_file"
    a_file.write_text("x")
    argv = [a.format(scene=mirror_scene, lecture=lecture, bad=bad) for a in args]
    out = str(a_file) if "--out-is-a-file" in argv else str(tmp_path / "out")
    argv = [a for a in argv if a != "--out-is-a-file"]
    result = _run(*argv, "--out", out)
    assert result.returncode == 2
    lines = result.stderr.strip().splitlines()
    assert len(lines) == 1, result.stderr
    assert names in lines[0] and "Traceback" not in result.stderr


def test_unknown_knob_is_refused_by_name(tmp_path, mirror_scene):
    result = _run(str(mirror_scene), "--knob", "fastness", "--out", str(tmp_path))
    assert result.returncode == 2
    assert "--knob" in result.stderr and "Traceback" not in result.stderr


def test_depth_format_rows_name_format_and_ratio(tmp_path, mirror_scene):
    from core.accuracy.sweep import DEPTH_RATIOS
    from core.object_order.depth_formats import BYTES_PER_PIXEL, DEPTH_FORMATS

    out = tmp_path / "formats"
    result = _run(str(mirror_scene), "--knob", "depth-format", "--mode", "raster", "--width", "24",
                  "--reference-spp", "1", "--out", str(out))
    assert result.returncode == 0, result.stderr
    rows = _rows(out)
    assert [r["value"] for r in rows] == [f"{f}@1:{n}" for f in DEPTH_FORMATS for n in DEPTH_RATIOS]
    height = round(24 * mirror_and_glass().camera.height / mirror_and_glass().camera.width)
    for r in rows:
        fmt, ratio = r["value"].split("@")
        assert r["mode"] == "raster" and r["compared_with"] == f"float64@{ratio}"
        assert int(r["bytes"]) == 24 * height * BYTES_PER_PIXEL[fmt]
        if fmt == "float64":
            assert float(r["wrong_pixel_fraction"]) == 0.0 and float(r["rmse"]) == 0.0
    assert sum(int(r["knee"]) for r in rows) == 1
    assert "z-fighting" in result.stdout and "changes time only" not in result.stdout
    assert iio.imread(out / "cost.png")[..., :3].std() > 10


def test_a_sweep_over_the_memory_budget_is_refused_before_anything_renders(tmp_path, mirror_scene):
    # Every finished setting keeps at least its colour image: 4096 x 4096 x 3 float64 is 400 MB
    # each, so a sweep of several settings cannot fit in 1 GB.
    out = tmp_path / "out"
    result = _run(str(mirror_scene), "--knob", "depth", "--width", "4096", "--height", "4096",
                  "--memory-limit", "1G", "--out", str(out))
    assert result.returncode == 2
    message = result.stderr.strip()
    assert "4096 × 4096" in message and "the budget is 1 GB (--memory-limit)" in message
    assert "Traceback" not in result.stderr and not out.exists()


def test_a_dry_run_prints_the_estimate_and_renders_nothing(tmp_path, mirror_scene):
    out = tmp_path / "out"
    result = _run(str(mirror_scene), "--knob", "depth", "--width", "32", "--dry-run", "--out", str(out))
    assert result.returncode == 0, result.stderr
    assert "of memory and" in result.stdout and "nothing rendered (--dry-run)" in result.stdout
    assert not out.exists()


def test_a_bad_memory_limit_is_named(tmp_path, mirror_scene):
    result = _run(str(mirror_scene), "--memory-limit", "lots", "--out", str(tmp_path / "out"))
    assert result.returncode == 2 and "--memory-limit" in result.stderr and "Traceback" not in result.stderr
