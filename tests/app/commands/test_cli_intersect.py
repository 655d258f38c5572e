"""``python -m app intersect``: run as a real subprocess, as a user would."""

import json
import subprocess
import sys
from decimal import Decimal, localcontext

import pytest
from checkout import ROOT

GUI_PACKAGES = ("PySide6", "pyvista", "pyvistaqt", "vtk", "vtkmodules")
LECTURE = ["sphere", "--origin", "2,1,2", "--end", "10,6,6", "--center", "6,4,6", "--radius", "10"]


def run_app(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "app", "intersect", *args],
        cwd=ROOT, capture_output=True, text=True, encoding="utf-8", timeout=60,
    )


def test_lecture_exercise_json():
    out = run_app(*LECTURE, "--json")
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout)
    assert result["hit"] is False and result["t"] is None and result["point"] is None
    assert result["origin_inside"] is True
    assert result["classification"] == "crosses"
    # a = 105, b = -126, c = -59, Δ = 126² + 4·105·59 = 40656, t = (126 ∓ √40656) / 210
    assert (result["a"], result["b"], result["c"]) == (105, -126, -59)
    assert result["discriminant"] == pytest.approx(40656, rel=1e-13)
    with localcontext() as ctx:
        ctx.prec = 50
        root = Decimal(40656).sqrt()
        t_near, t_far = float((126 - root) / 210), float((126 + root) / 210)
    assert result["roots"] == pytest.approx([t_near, t_far], rel=1e-14)
    assert result["ray"]["hit"] is True
    assert result["ray"]["t"] == pytest.approx(t_far, rel=1e-14)


def test_tangent_ray_json_with_a_negative_coordinate():
    out = run_app("sphere", "--origin", "-5,1,0", "--direction", "1,0,0", "--center", "0,0,0",
                  "--radius", "1", "--json")
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout)
    assert result["classification"] == "tangent" and result["hit"] is True
    assert result["t"] == 5 and result["point"] == [0, 1, 0] and result["normal"] == [0, 1, 0]


def test_miss_has_nulls_not_nan():
    out = run_app("sphere", "--origin", "0,2,5", "--direction", "0,0,-1", "--center", "0,0,0",
                  "--radius", "1", "--json")
    assert out.returncode == 0, out.stderr
    assert "NaN" not in out.stdout
    result = json.loads(out.stdout)
    assert result["classification"] == "misses" and result["roots"] is None
    assert result["t"] is None and result["normal"] is None and result["ray"]["t"] is None


def test_triangle_hit_json():
    # Straight down onto z = 0 at (0.5, 0.25): P = 0.25 A + 0.5 B + 0.25 C, t = 1.
    out = run_app("triangle", "--origin", "0.5,0.25,1", "--direction", "0,0,-1",
                  "--a", "0,0,0", "--b", "1,0,0", "--c", "0,1,0", "--json")
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout)
    assert result["hit"] is True
    assert (result["alpha"], result["beta"], result["gamma"], result["t"]) == (0.25, 0.5, 0.25, 1)
    assert result["point"] == [0.5, 0.25, 0]


def test_parallel_triangle_json():
    out = run_app("triangle", "--origin", "0,0,1", "--direction", "1,0,0",
                  "--a", "0,0,0", "--b", "1,0,0", "--c", "0,1,0", "--json")
    assert out.returncode == 0, out.stderr
    result = json.loads(out.stdout)
    assert result["hit"] is False and "parallel" in result["reason"]
    assert result["alpha"] is None and result["t"] is None


def test_text_mode_shows_the_worked_solution():
    out = run_app(*LECTURE)
    assert out.returncode == 0, out.stderr
    assert "Δ = b² - 4ac = 40656" in out.stdout
    assert "Δ > 0: two real roots" in out.stdout
    assert "both ends of the segment are inside the sphere" in out.stdout
    assert "t_far = 1.56016" in out.stdout
    out = run_app("triangle", "--origin", "0,0,0", "--direction", "1,1,1",
                  "--a", "3,0,0", "--b", "0,3,0", "--c", "0,0,3")
    assert out.returncode == 0, out.stderr
    assert "det M = det[A - C, B - C, -d] = -27" in out.stdout
    assert "Cramer" in out.stdout and "Hit:" in out.stdout


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["sphere", "--origin", "0,0,0", "--direction", "1,0,0", "--center", "5,0,0",
          "--radius", "-1"], "--radius"),
        (["sphere", "--origin", "1,2", "--direction", "1,0,0", "--center", "5,0,0",
          "--radius", "1"], "--origin"),
        (["sphere", "--origin", "0,0,0", "--direction", "1,0,0", "--radius", "1"], "--center"),
        (["sphere", "--origin", "0,0,0", "--direction", "0,0,0", "--center", "5,0,0",
          "--radius", "1"], "--direction"),
        (["sphere", "--origin", "0,0,0", "--end", "1,nan,0", "--center", "5,0,0",
          "--radius", "1"], "--end"),
        (["triangle", "--origin", "0,0,0", "--direction", "0,0,1", "--a", "0,0,1",
          "--b", "1,0,1", "--c", "0,1,1,1"], "--c"),
    ],
)
def test_bad_arguments_exit_2_with_one_line_naming_the_option(args, option):
    out = run_app(*args)
    assert out.returncode == 2
    assert out.stdout == ""
    assert "Traceback" not in out.stderr
    error_lines = [line for line in out.stderr.splitlines() if "error:" in line]
    assert len(error_lines) == 1 and option in error_lines[0], out.stderr
    assert out.stderr.rstrip("\n").splitlines()[-1] == error_lines[0]


def test_intersect_loads_no_qt_or_vtk():
    code = (
        "import sys\n"
        "from app.cli import main\n"
        f"status = main(['intersect', *{LECTURE!r}, '--json'])\n"
        "assert status == 0, status\n"
        f"print(sorted(m for m in sys.modules if m.split('.')[0] in {GUI_PACKAGES!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                         timeout=60)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip().splitlines()[-1] == "[]"


def test_a_ray_starting_on_the_sphere_and_heading_out_leaves_at_its_start():
    # From (1, 0, 0) outwards on the unit sphere: c = |o - centre|² - r² = 0 exactly, so the
    # roots are t = -2 and t = 0; the start is on the surface, not inside it.
    out = subprocess.run([sys.executable, "-m", "app", "intersect", "sphere", "--origin", "1,0,0",
                          "--direction", "1,0,0", "--center", "0,0,0", "--radius", "1", "--json"],
                         capture_output=True, text=True, cwd=ROOT)
    answer = json.loads(out.stdout)
    assert answer["origin_inside"] is False
    assert answer["t"] == 0.0 and str(answer["t"]) == "0.0"
    assert "inside" not in answer["reason"] and "on the sphere" in answer["reason"]
