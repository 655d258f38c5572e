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
