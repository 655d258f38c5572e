"""A warm-up compiles once per machine: a second process waits for the first and loads what it compiled."""

import json
import subprocess
import sys

from checkout import ROOT

KERNELS = """
from pathlib import Path
from core.compiling.kernel_cache import share_cache
share_cache(Path(__file__).parent, [Path(__file__)], "tiny")
"""

PROCESS = f"""
import json, sys, time
sys.path[:0] = [sys.argv[1], {str(ROOT)!r}]
from core.compiling.warm_up import WarmUp

def warm_up():  # stands for a compile: it takes a while, and says when it ran
    start = time.time()
    time.sleep(1.0)
    print(json.dumps([start, time.time()]))

job = WarmUp(warm_up, "tinykernels", "tiny", "all")
ready = job.ready()
job()
print(json.dumps({{"ready before": ready, "ready after": job.ready()}}))
"""


def test_two_processes_never_compile_the_same_kernels_at_once(tmp_path):
    (tmp_path / "tinykernels").mkdir()
    (tmp_path / "tinykernels" / "__init__.py").write_text(KERNELS)
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "cache"), "PATH": "/usr/bin:/bin"}
    processes = [subprocess.Popen([sys.executable, "-c", PROCESS, str(tmp_path)], env=env, text=True,
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE) for _ in range(2)]
    outputs = [p.communicate(timeout=300) for p in processes]
    assert all(p.returncode == 0 for p in processes), [err for _, err in outputs]
    runs = sorted(json.loads(out.splitlines()[0]) for out, _ in outputs)
    assert runs[0][1] <= runs[1][0]  # the second began once the first had ended
    states = [json.loads(out.splitlines()[-1]) for out, _ in outputs]
    assert all(s["ready after"] for s in states)  # both say compiled now: the marker is on disk


def test_a_warm_up_is_ready_only_once_it_has_run_on_this_machine(tmp_path):
    (tmp_path / "tinykernels").mkdir()
    (tmp_path / "tinykernels" / "__init__.py").write_text(KERNELS)
    env = {"NUMBA_CACHE_DIR": str(tmp_path / "cache"), "PATH": "/usr/bin:/bin"}
    states = []
    for _ in range(2):
        done = subprocess.run([sys.executable, "-c", PROCESS, str(tmp_path)], env=env, text=True,
                              capture_output=True, timeout=300)
        assert done.returncode == 0, done.stderr
        states.append(json.loads(done.stdout.splitlines()[-1]))
    assert states == [{"ready before": False, "ready after": True},
                      {"ready before": True, "ready after": True}]
