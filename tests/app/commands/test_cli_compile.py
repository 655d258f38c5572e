"""``python -m app compile`` on a machine whose kernels are compiled: one line, at once."""

import subprocess
import sys

from checkout import ROOT


def test_it_says_in_one_line_where_the_compiled_kernels_are():
    # .ci/test.sh compiled every kernel group before the tests ran.
    done = subprocess.run([sys.executable, "-m", "app", "compile"], cwd=ROOT, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    assert done.stdout.splitlines() == [
        f"python -m app compile: every kernel group is compiled already (in {_cache_root()})"]
    quiet = subprocess.run([sys.executable, "-m", "app", "compile", "--quiet"], cwd=ROOT, capture_output=True,
                           text=True, timeout=120)
    assert quiet.returncode == 0 and quiet.stdout == ""


def _cache_root() -> str:
    import os

    return os.environ["NUMBA_CACHE_DIR"]  # set by tests/conftest.py to the user's kernel cache


GIVE_WAY = """
import os, sys
from app import cli
from app.window.background_compile import BackgroundCompile

assert "--give-way" in BackgroundCompile.COMMAND  # the window's background compile asks for it
before = os.getpriority(os.PRIO_PROCESS, 0)
code = cli.main(["compile", "--quiet", "--give-way"])
print(before, os.getpriority(os.PRIO_PROCESS, 0), code)
"""


def test_the_windows_background_compile_runs_at_a_lower_priority_than_the_window():
    # It was lowered by a hook run between fork and exec (subprocess's preexec_fn), which Python
    # warns may deadlock the child of a process with threads, as the window's is; now the compile
    # lowers its own, and the processes it starts per kernel group inherit it.
    from core.give_way import NICE

    done = subprocess.run([sys.executable, "-c", GIVE_WAY], cwd=ROOT, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    before, after, code = (int(v) for v in done.stdout.split())
    assert code == 0 and after == min(before + NICE, 19)
