"""The tests never read or write the user's own settings, not even from the programs they start."""

import os
import subprocess
import sys
from pathlib import Path

from checkout import ROOT


def test_a_program_a_test_starts_keeps_its_settings_in_the_tests_folder():
    ask = "from views.user_settings import user_settings; print(user_settings().fileName())"
    child = subprocess.run([sys.executable, "-c", ask], cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert child.returncode == 0, child.stderr
    where = Path(child.stdout.strip())
    assert where.is_relative_to(os.environ["XDG_CONFIG_HOME"])
    assert not where.is_relative_to(Path.home() / ".config")
