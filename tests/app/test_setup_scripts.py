"""The README's two commands install what a fresh Debian machine lacks before they start.

Each script runs in a copy of ``.ci`` beside a copy of ``pyproject.toml``, with stand-ins for
``dpkg-query`` (nothing is installed), ``apt-get`` and ``sudo`` that record their calls, and a
stand-in ``.venv`` whose stamp says the packages are installed, so nothing is installed for
real and no window opens.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
XCB_CURSOR = "libxcb-cursor0"  # the library desktop installs most often lack for Qt 6


def _stand_in(path: Path, body: str) -> None:
    path.write_text("#!/usr/bin/env bash\n" + body + "\n")
    path.chmod(0o755)


def _checkout(tmp_path: Path) -> tuple[Path, Path, dict]:
    """A copy of the scripts with a stand-in venv; returns (root, log, environment)."""
    root = tmp_path / "clone"
    shutil.copytree(ROOT / ".ci", root / ".ci")
    shutil.copy(ROOT / "pyproject.toml", root / "pyproject.toml")
    log = tmp_path / "calls.log"
    venv_bin = root / ".venv" / "bin"
    venv_bin.mkdir(parents=True)
    stamp = hashlib.sha256((root / "pyproject.toml").read_bytes()).hexdigest()
    for extras in ("", "[test]"):
        (root / ".venv" / f".installed{extras}").write_text(stamp + "\n")
    _stand_in(venv_bin / "python", f'echo "python $*" >> {log}')
    _stand_in(venv_bin / "ruff", f'echo "ruff $*" >> {log}')
    tools = tmp_path / "tools"
    tools.mkdir()
    _stand_in(tools / "dpkg-query", "exit 1")  # nothing is installed
    _stand_in(tools / "apt-get", f'echo "apt-get $*" >> {log}')
    _stand_in(tools / "sudo", '"$@"')
    _stand_in(tools / "xvfb-run", f'echo "xvfb-run $*" >> {log}')
    env = {**os.environ, "PATH": f"{tools}:{os.environ['PATH']}"}
    return root, log, env


def _installed(log: Path) -> set[str]:
    words = set()
    for line in log.read_text().splitlines():
        if line.startswith("apt-get") and " install " in line:
            words.update(w for w in line.split() if not w.startswith("-"))
    return words - {"apt-get", "install"}


def test_command_1_installs_qts_xcb_libraries_then_starts_the_app(tmp_path):
    root, log, env = _checkout(tmp_path)
    done = subprocess.run(["bash", str(root / ".ci" / "app.sh"), "--help"], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    installed = _installed(log)
    assert XCB_CURSOR in installed and "libxkbcommon-x11-0" in installed
    assert "xvfb" not in installed  # a desktop has a display: the app needs no X server of its own
    assert log.read_text().splitlines()[-1] == "python -m app --help"


def test_command_2_installs_xvfb_and_the_libraries_then_runs_the_tests_under_it(tmp_path):
    root, log, env = _checkout(tmp_path)
    done = subprocess.run(["bash", str(root / ".ci" / "test.sh"), "-q"], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    assert {XCB_CURSOR, "xvfb", "xauth"} <= _installed(log)
    calls = log.read_text().splitlines()
    assert calls[-2] == "ruff check ."
    assert calls[-1].startswith("xvfb-run -a") and calls[-1].endswith("python -m pytest -q")
