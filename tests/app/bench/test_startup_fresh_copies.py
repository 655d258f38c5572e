"""``bench startup --cold`` starts fresh copies of the code as a user would meet them: a second clone
finds the user's compiled kernels and typeset formulas and compiles only its own bytecode; a fresh
machine finds every cache empty.  Neither throws away the installed packages' bytecode (pip wrote it
at install), which made the second clone look 3 s slower than it is."""

import os
from pathlib import Path

import pytest

from app.bench import startup
from core.compiling.kernel_cache import cache_root


@pytest.mark.parametrize("fresh_machine", [False, True])
def test_a_fresh_copy_starts_without_its_own_bytecode_and_with_the_caches_a_user_would_have(
        monkeypatch, fresh_machine):
    seen = {}

    def watched(timeout_s, root, env):
        seen["root"], seen["env"] = Path(root), dict(env)
        seen["bytecode"] = sorted(Path(root).rglob("__pycache__"))
        seen["sources"] = (Path(root) / "core" / "camera.py").exists()
        return {"shown": startup.Moment(1.0, False), "image": startup.Moment(2.0, True)}

    monkeypatch.setattr(startup, "watched_start", watched)
    assert startup._start_fresh(60, fresh_machine) == (1.0, 2.0)
    assert seen["sources"] and seen["bytecode"] == []
    env = seen["env"]
    assert "PYTHONPYCACHEPREFIX" not in env  # the installed packages' bytecode is used
    if fresh_machine:
        assert Path(env["NUMBA_CACHE_DIR"]).parent == seen["root"].parent
        assert Path(env["XDG_CACHE_HOME"]).parent == seen["root"].parent
    else:
        assert env["NUMBA_CACHE_DIR"] == str(cache_root())
        assert "XDG_CACHE_HOME" not in env or env["XDG_CACHE_HOME"] == os.environ.get("XDG_CACHE_HOME")
