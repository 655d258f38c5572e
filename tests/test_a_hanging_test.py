"""A test that hangs fails after the suite's time limit, with the stack where it hung, and the
other tests still run: a hang never stops the whole test command in silence."""

import subprocess
import sys

from checkout import ROOT

HANGS = """
import threading

def test_waits_for_what_never_comes():
    threading.Event().wait()

def test_after_it():
    assert True
"""


def test_a_hanging_test_fails_with_its_stack_and_the_run_goes_on(tmp_path):
    (tmp_path / "test_hangs.py").write_text(HANGS)
    # The project's own pytest settings (its time limit's method included), with the limits cut to
    # 1 s for the stacks and 3 s for the failure; two worker processes as .ci/test.sh runs them, so the
    # hung one is replaced and the run finishes.
    command = [sys.executable, "-m", "pytest", "-c", str(ROOT / "pyproject.toml"),
               "--rootdir", str(tmp_path), "-p", "no:cacheprovider", "-p", "no:pytest-qt", "-n", "2",
               "-o", "faulthandler_timeout=1", "--timeout", "3",
               str(tmp_path / "test_hangs.py")]
    ran = subprocess.run(command, cwd=tmp_path, capture_output=True, text=True, timeout=300)
    out = ran.stdout + ran.stderr
    assert ran.returncode == 1, out[-3000:]
    assert "crashed while running 'test_hangs.py::test_waits_for_what_never_comes'" in out
    assert 'test_hangs.py", line 5 in test_waits_for_what_never_comes' in out  # where it hung
    assert "1 failed, 1 passed" in ran.stdout.strip().splitlines()[-1]
