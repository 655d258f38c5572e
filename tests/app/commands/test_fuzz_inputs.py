"""Fuzzing the command line with generated scene files, mesh files and paths (issue 11), and the
lesson reader with generated lesson files (issue 35).

Every example runs ``python -m app render ... --dry-run`` in its own
subprocess, so a crash or a hang is a failure of that example, not a lost
test run: no signal deaths, no timeouts, no tracebacks, exit status 0 or 2,
and a refusal names the field that is wrong.  ``--dry-run`` loads and checks
everything (scene, mesh files, camera, output paths, memory budget) and stops
before the render; a few generated scenes that pass are then rendered for
real.  Examples are few but diverse and the runs are seeded (derandomized),
so the test is repeatable and stays within about a minute.
"""

from __future__ import annotations

import tempfile
from pathlib import Path

from hostile_inputs import (
    lesson_cases,
    lesson_verdict,
    mesh_cases,
    path_cases,
    run_case,
    run_lesson,
    scene_cases,
    verdict,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

FUZZ = settings(max_examples=40, derandomize=True, deadline=None, database=None,
                suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])


def _handled(case, *options):
    with tempfile.TemporaryDirectory() as folder:
        code, stderr, _ = run_case(case, Path(folder), *options)
    problem = verdict(code, stderr)
    assert problem is None, f"{case.kind}: {problem}\n{stderr[-2000:]}\n{case.files!r}"[:5000]
    return code


@FUZZ
@given(scene_cases())
def test_generated_scene_files_are_loaded_or_refused_cleanly(case):
    _handled(case, "--dry-run", "--mode", "raster")


@FUZZ
@given(mesh_cases())
def test_generated_mesh_files_are_read_or_refused_cleanly(case):
    _handled(case, "--dry-run", "--mode", "raycast")


@settings(max_examples=7, derandomize=True, deadline=None, database=None)
@given(path_cases())
def test_paths_that_never_end_are_refused(case):
    assert _handled(case, "--dry-run") == 2


@settings(max_examples=20, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(st.one_of(scene_cases(), mesh_cases()), st.sampled_from(["raster", "raycast", "raytrace"]))
def test_generated_inputs_that_pass_the_checks_also_render(case, mode):
    if _handled(case, "--dry-run", "--mode", mode) == 0:  # about one in six: render those
        assert _handled(case, "--mode", mode, "--width", "16", "--height", "12") == 0


@settings(max_examples=10, derandomize=True, deadline=None, database=None,
          suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large])
@given(lesson_cases())
def test_generated_lesson_files_are_loaded_or_refused_cleanly(case):
    # As File > Open lesson reads them: a FIFO, /dev/zero, 5000-digit numbers, 200,000 keys, a view
    # the 3D pane cannot look from, ... each loads or is refused in one message naming the field.
    with tempfile.TemporaryDirectory() as folder:
        code, stderr = run_lesson(case, Path(folder), timeout=60)
    problem = lesson_verdict(code, stderr)
    assert problem is None, f"{case.kind}: {problem}\n{stderr[-2000:]}"
