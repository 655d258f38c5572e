"""The README's two commands install what a fresh Debian machine lacks before they start.

Each script runs in a copy of ``.ci`` beside a copy of ``pyproject.toml``, with stand-ins for
``dpkg-query`` (nothing is installed), ``apt-get`` and ``sudo`` that record their calls, and a
stand-in ``.venv`` whose stamp says the packages are installed, so nothing is installed for
real and no window opens.
"""

from __future__ import annotations

import hashlib
import importlib.metadata
import os
import re
import shutil
import subprocess
from pathlib import Path

from checkout import ROOT

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
    for extras in ("", "[test]"):
        (root / ".venv" / f".installed{extras}").write_text(_stamp(root) + "\n")
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


def _stamp(root: Path) -> str:
    """What setup records once it has installed the packages of this pyproject and constraints."""
    both = (root / "pyproject.toml").read_bytes() + (root / ".ci" / "constraints.txt").read_bytes()
    return hashlib.sha256(both).hexdigest()


def _run(root: Path, env: dict, script: str, *args: str) -> subprocess.CompletedProcess:
    """Run one of the README's scripts in the copy; it must succeed."""
    done = subprocess.run(["bash", str(root / ".ci" / script), *args], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done


def _installed(log: Path) -> set[str]:
    words = set()
    for line in log.read_text().splitlines():
        if line.startswith("apt-get") and " install " in line:
            words.update(w for w in line.split() if not w.startswith("-"))
    return words - {"apt-get", "install"}


def test_command_1_installs_qts_xcb_libraries_then_starts_the_app(tmp_path):
    root, log, env = _checkout(tmp_path)
    _run(root, env, "app.sh", "--help")
    installed = _installed(log)
    assert XCB_CURSOR in installed and "libxkbcommon-x11-0" in installed
    assert "xvfb" not in installed  # a desktop has a display: the app needs no X server of its own
    assert log.read_text().splitlines()[-1] == "python -m app --help"


def test_command_2_installs_xvfb_and_the_libraries_compiles_then_runs_the_tests_under_it(tmp_path):
    root, log, env = _checkout(tmp_path)
    _run(root, env, "test.sh", "-q")
    assert {XCB_CURSOR, "xvfb", "xauth"} <= _installed(log)
    calls = log.read_text().splitlines()
    assert calls[-3] == "ruff check ."
    assert calls[-2] == "python -m app compile"  # the kernels compile before any test's time limit runs
    assert calls[-1].startswith("xvfb-run -a")
    assert calls[-1].endswith("python -m pytest -n 2 --dist worksteal -q")


def _fresh_venv(root: Path, log: Path, constrained_exit: int) -> None:
    """Forget the install, and make the stand-in pip fail with ``constrained_exit`` when asked for
    the tested versions (``-c``), as pip does where they have no wheel."""
    for stamp in (root / ".venv").glob(".installed*"):
        stamp.unlink()
    _stand_in(root / ".venv" / "bin" / "python",
              f'echo "python $*" >> {log}\ncase " $* " in *" -c "*) exit {constrained_exit};; esac')


def _pip_installs(log: Path) -> list[str]:
    return [line for line in log.read_text().splitlines() if line.startswith("python -m pip install -q ")
            and "--upgrade pip" not in line]


def test_a_fresh_install_takes_the_tested_versions_and_records_them(tmp_path):
    root, log, env = _checkout(tmp_path)
    _fresh_venv(root, log, constrained_exit=0)
    _run(root, env, "app.sh", "--help")
    assert _pip_installs(log) == [f"python -m pip install -q -c {root / '.ci' / 'constraints.txt'} -e ."]
    assert (root / ".venv" / ".installed").read_text().strip() == _stamp(root)
    assert log.read_text().splitlines()[-1] == "python -m app --help"


def test_where_the_tested_versions_do_not_install_it_says_so_and_installs_the_newest(tmp_path):
    root, log, env = _checkout(tmp_path)
    _fresh_venv(root, log, constrained_exit=1)
    done = _run(root, env, "test.sh", "-q")
    assert "constraints.txt do not install" in done.stderr
    constrained, plain = _pip_installs(log)
    assert " -c " in constrained and plain == "python -m pip install -q -e .[test]"
    assert log.read_text().splitlines()[-1].endswith("python -m pytest -n 2 --dist worksteal -q")


def _name(requirement: str) -> str:
    """The normalised distribution name of ``"PySide6>=6.6,<6.12  # why"`` (``pyside6``)."""
    return re.split(r"[<>=!~;\[ ]", requirement.strip(), maxsplit=1)[0].lower().replace("_", "-")


def test_every_package_the_project_asks_for_has_a_tested_version():
    # The installed project's own metadata: every requirement, those of the extras included.
    wanted = {_name(r) for r in importlib.metadata.requires("render-explorer")}
    assert {"numba", "pyside6", "pytest", "embreex"} <= wanted
    pinned = {}
    for line in (ROOT / ".ci" / "constraints.txt").read_text().splitlines():
        if line.strip() and not line.startswith("#"):
            name, _, version = line.partition("==")
            pinned[_name(name)] = version
    assert wanted - set(pinned) == set()
    assert all(re.fullmatch(r"[0-9][0-9A-Za-z.+!-]*", v) for v in pinned.values()), pinned
