"""OpenMP's waiting threads sleep in the program (:mod:`app.process.thread_waits`).

The setting only works if it is made before numba loads the OpenMP library, so
each case runs ``python -m app render`` in a fresh interpreter and reads what
``libgomp`` itself says it runs with (``OMP_DISPLAY_ENV``, printed when it is
loaded): a thread that waits spins 0 rounds (``GOMP_SPINCOUNT``) instead of
its default 300,000, and a policy the user set is kept.  (numba runs its
parallel loops on OpenMP here: the project installs no TBB.)
"""

from __future__ import annotations

import os
import subprocess
import sys
from dataclasses import replace

import pytest
from checkout import ROOT

from core import presets
from core.files import scene_file


@pytest.fixture
def small_scene(tmp_path):
    """The lecture's scene at 16 x 12 pixels, as a scene file."""
    scene = presets.lecture_scene()
    path = tmp_path / "lecture.json"
    scene_file.save(replace(scene, camera=scene.camera.replace(width=16, height=12)), path)
    return path


def _openmp_settings(scene, out, **env) -> str:
    """What OpenMP prints of its settings while ``python -m app render`` traces ``scene``."""
    environment = {k: v for k, v in os.environ.items() if k not in ("OMP_WAIT_POLICY", "GOMP_SPINCOUNT")}
    result = subprocess.run([sys.executable, "-m", "app", "render", str(scene), "--mode", "raytrace", "--out",
                             str(out)], cwd=ROOT, capture_output=True, text=True, timeout=300,
                            env={**environment, "OMP_DISPLAY_ENV": "VERBOSE", **env})
    assert result.returncode == 0, result.stderr
    assert out.exists()
    return result.stderr


def test_the_program_makes_openmps_waiting_threads_sleep(tmp_path, small_scene):
    settings = _openmp_settings(small_scene, tmp_path / "out.png")
    assert "OMP_WAIT_POLICY = 'PASSIVE'" in settings
    assert "GOMP_SPINCOUNT = '0'" in settings


def test_a_wait_policy_the_user_set_is_kept(tmp_path, small_scene):
    settings = _openmp_settings(small_scene, tmp_path / "out.png", OMP_WAIT_POLICY="ACTIVE")
    assert "OMP_WAIT_POLICY = 'ACTIVE'" in settings
    assert "GOMP_SPINCOUNT = '0'" not in settings
