"""``python -m app hardcases``: the lab on the command line, run as a real subprocess."""

import argparse
import json
import subprocess
import sys
from decimal import Decimal, localcontext

import pytest
from checkout import ROOT

from app.commands import hardcases as hardcases_command
from core import hard_cases
from core.hard_cases.result import CaseResult, Row

GUI_PACKAGES = ("PySide6", "pyvista", "pyvistaqt", "vtk", "vtkmodules")
KEYS = {"case", "naive_error", "robust_error", "tolerance", "passed"}


def run_app(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run(
        [sys.executable, "-m", "app", "hardcases", *args],
        cwd=ROOT, capture_output=True, text=True, encoding="utf-8", timeout=600,
    )


@pytest.fixture(scope="module")
def all_json():
    out = run_app("--json")
    assert out.returncode == 0, out.stderr
    return [json.loads(line) for line in out.stdout.splitlines()]


def test_json_has_one_object_per_case_and_every_robust_method_passes(all_json):
    assert [r["case"] for r in all_json] == list(hard_cases.CASES)
    for r in all_json:
        assert r.keys() >= KEYS
        assert r["passed"] is True and r["robust_error"] <= r["tolerance"], r
        # Each case is set up at a parameter where the textbook method visibly fails
        # (a NaN error, printed as null, fails too).
        assert r["naive_error"] is None or r["naive_error"] > r["tolerance"], r


def test_json_never_contains_nan(all_json):
    tir = next(r for r in all_json if r["case"] == "total_reflection")
    assert tir["naive_error"] is None and tir["naive_result"] == "NaN"
    assert tir["robust_result"] == "reflected (total)"


def test_lecture_exercise_roots_in_json(all_json):
    seg = next(r for r in all_json if r["case"] == "lecture_segment")
    assert seg["exact_result"] == "no crossing" and seg["robust_result"] == "no crossing"
    assert seg["naive_result"].startswith("crosses at t = -0.36")
    # a = 105, b = -126, c = -59: t = (126 ∓ √40656) / 210, both outside [0, 1].
    with localcontext() as ctx:
        ctx.prec = 50
        root = Decimal(40656).sqrt()
        t_near, t_far = float((126 - root) / 210), float((126 + root) / 210)
    rows = {row["label"]: row for row in seg["rows"]}
    assert rows["t_near"]["robust"] == pytest.approx(t_near, rel=1e-15)
    assert rows["t_far"]["robust"] == pytest.approx(t_far, rel=1e-15)
    assert rows["t_near"]["exact"] == pytest.approx(t_near, rel=1e-15)


def test_one_case_prints_a_table_line_and_a_summary():
    out = run_app("--case", "far_sphere")
    assert out.returncode == 0, out.stderr
    header, line, summary = out.stdout.splitlines()
    assert header.split()[:2] == ["case", "parameter"]
    assert line.startswith("far_sphere") and "distance=1e+08" in line and line.endswith("pass")
    assert summary == "1 of 1 robust methods pass"


def test_command_loads_no_gui_toolkit():
    code = ("import sys; from app.cli import main; main(['hardcases', '--case', 'tangent', '--json']);"
            f"print([m for m in {GUI_PACKAGES!r} if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines()[-1] == "[]"


@pytest.mark.parametrize(
    ("args", "option"),
    [
        (["--case", "nope"], "--case"),
        (["--case", ""], "--case"),
        (["--case"], "--case"),
        (["--bogus"], "--bogus"),
    ],
)
def test_bad_arguments_exit_2_with_one_line_naming_the_option(args, option):
    out = run_app(*args)
    assert out.returncode == 2
    assert out.stdout == "" and "Traceback" not in out.stderr
    error_lines = [line for line in out.stderr.splitlines() if "error:" in line]
    assert len(error_lines) == 1 and option in error_lines[0], out.stderr
    assert out.stderr.rstrip("\n").splitlines()[-1] == error_lines[0]


def test_unknown_case_message_lists_the_cases():
    out = run_app("--case", "acne")
    assert "shadow_acne" in out.stderr and "tangent" in out.stderr


def test_exit_status_is_1_when_a_robust_method_fails(monkeypatch, capsys):
    failing = CaseResult(
        name="broken", title="a robust method that misses its tolerance", parameter=None,
        naive_method="n", robust_method="r", reference_method="x", rows=(Row("value", 1.0, 2.0, 0.0),),
        naive_error=1.0, robust_error=2.0, error_unit="units", tolerance=0.5, tolerance_reason="test",
        explanation="",
    )
    monkeypatch.setitem(hard_cases.CASES, "broken", hard_cases.Case("broken", lambda: failing))
    status = hardcases_command.run(argparse.Namespace(case="broken", json=False))
    lines = capsys.readouterr().out.splitlines()
    assert status == 1
    assert lines[1].startswith("broken") and lines[1].endswith("FAIL")
    assert lines[2] == "0 of 1 robust methods pass; failing: broken"
