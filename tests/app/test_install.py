"""The package as a user installs it: a wheel in a new virtual environment, run from another folder."""

import json
import subprocess
import sys
import sysconfig
from pathlib import Path

import numpy as np
from checkout import ROOT
from imageio.v3 import imread

from core import presets
from core.files import scene_file


def _run(args, **kwargs):
    done = subprocess.run(args, capture_output=True, text=True, timeout=600, **kwargs)
    assert done.returncode == 0, f"{args}: {done.stderr[-3000:]}"
    return done


def _files(site: Path) -> list[Path]:
    """Every file of the installed project's packages (the bytecode pip compiled at install included)."""
    return sorted(p for name in ("app", "core", "views") for p in (site / name).rglob("*"))


def test_the_wheel_runs_from_another_folder_and_writes_nothing_into_its_package(tmp_path):
    # Build the wheel as pip would, and install it into a new virtual environment. The environment
    # borrows this one's third-party packages (numpy, numba, Qt...) through a .pth file, so nothing is
    # downloaded; the project itself comes from the wheel only.
    wheels = tmp_path / "wheels"
    _run([sys.executable, "-m", "pip", "wheel", "--no-deps", "--no-build-isolation", "-q", "-w", str(wheels),
          str(ROOT)])
    (wheel,) = wheels.glob("render_explorer-*.whl")
    venv = tmp_path / "venv"
    _run([sys.executable, "-m", "venv", str(venv)])
    python = venv / "bin" / "python"
    site = Path(_run([str(python), "-c", "import sysconfig; print(sysconfig.get_paths()['purelib'])"])
                .stdout.strip())
    (site / "borrowed.pth").write_text(sysconfig.get_paths()["purelib"] + "\n")
    _run([str(python), "-m", "pip", "install", "--no-deps", "--no-index", "-q", str(wheel)])

    elsewhere = tmp_path / "somewhere else"
    elsewhere.mkdir()
    scene = elsewhere / "lecture.json"
    scene_file.save(presets.lecture_scene(), scene)
    installed = Path(_run([str(python), "-c", "import core, os; print(os.path.dirname(core.__file__))"],
                          cwd=elsewhere).stdout.strip())
    assert installed.is_relative_to(venv)  # the installed copy, not this checkout
    package_files = _files(installed.parent)

    command = venv / "bin" / "render-explorer"
    _run([str(command), "render", str(scene), "--mode", "raytrace", "--width", "64", "--height", "48",
          "--out", "traced.png", "--stats-out", "stats.json"], cwd=elsewhere)
    image = imread(elsewhere / "traced.png")
    assert image.shape[:2] == (48, 64) and np.ptp(image) > 0  # the scene, not a blank picture
    assert json.loads((elsewhere / "stats.json").read_text())["rays"]["total"] > 64 * 48
    count = "from core.lessons.lesson_file import shipped_lessons; print(len(shipped_lessons()))"
    lessons = _run([str(python), "-c", count], cwd=elsewhere).stdout.split()
    assert int(lessons[-1]) >= 10  # the lesson files travel as package data

    assert _files(installed.parent) == package_files  # nothing written into it (it may be read-only)
