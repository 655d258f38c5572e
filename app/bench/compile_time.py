"""``python -m app bench compile``: the time to compile every kernel from nothing, per kernel group.

Each group (:data:`core.compiling.warm_up.GROUPS`) compiles in a fresh process whose kernel
cache (``NUMBA_CACHE_DIR``) is an empty folder, one group after another, so each
figure is that group's alone: wall-clock seconds and the process's CPU seconds
(the CPU figure is the steadier one on a busy machine).  Then every group is
compiled from nothing again as ``python -m app compile`` does it, each in its own
process, as many at once as there are cores: that wall time is what a fresh
machine waits.  This is a benchmark, not a test; nothing here is asserted.
"""

from __future__ import annotations

import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

from app.commands.compile_kernels import compile_groups
from app.usage import UsageError
from core.compiling.warm_up import GROUPS

#: The goal of issue 30: every kernel from nothing, on this 2-core machine.
GOAL_S = 45.0

_ONE_GROUP = """
import resource, sys, time
start = time.perf_counter()
from core.compiling.warm_up import warm_up_of
warm_up_of(sys.argv[1])()
used = resource.getrusage(resource.RUSAGE_SELF)
print(time.perf_counter() - start, used.ru_utime + used.ru_stime)
"""


def add_arguments(parser) -> None:
    """Add the benchmark's options to ``parser`` (the ``bench compile`` subcommand)."""
    parser.add_argument("--runs", type=int, default=1, help="compiles of each group (default 1)")


def _compile_alone(group: str) -> tuple[float, float]:
    """Wall and CPU seconds to compile ``group`` from nothing in a fresh process."""
    with tempfile.TemporaryDirectory() as cache:
        env = {**os.environ, "NUMBA_CACHE_DIR": cache}
        done = subprocess.run([sys.executable, "-c", _ONE_GROUP, group], env=env, capture_output=True,
                              text=True)
    if done.returncode != 0:
        raise UsageError(f"bench compile: the {group} kernels did not compile: "
                         f"{(done.stderr.strip().splitlines() or ['no output'])[-1]}")
    wall, cpu = map(float, done.stdout.split()[-2:])
    return wall, cpu


def _compile_all() -> tuple[float, float]:
    """Wall and CPU seconds (of every process) to compile every group as ``python -m app compile`` does."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    with tempfile.TemporaryDirectory() as cache:
        start = time.perf_counter()
        if compile_groups(list(GROUPS), env={**os.environ, "NUMBA_CACHE_DIR": cache}) != 0:
            raise UsageError("bench compile: a kernel group did not compile (see above)")
        wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    return wall, (after.ru_utime + after.ru_stime) - (before.ru_utime + before.ru_stime)


def run(args) -> int:
    """Run the benchmark and print its figures; returns the exit status."""
    if args.runs < 1:
        raise UsageError(f"--runs must be at least 1, got {args.runs}")
    import numba

    print(f"bench compile: every kernel from nothing (an empty cache), numba {numba.__version__}, "
          f"{os.cpu_count()} cores; median of {args.runs} [lowest .. highest]")
    rows = {group: [] for group in GROUPS}
    rows["all (python -m app compile)"] = []
    for _ in range(args.runs):
        for group in GROUPS:
            rows[group].append(_compile_alone(group))
        rows["all (python -m app compile)"].append(_compile_all())
    print(f"  {'group':<28} {'wall s':>24} {'cpu s':>8}")
    for name, runs in rows.items():
        walls, cpus = [w for w, _ in runs], [c for _, c in runs]
        print(f"  {name:<28} {statistics.median(walls):7.1f} [{min(walls):6.1f} .. {max(walls):6.1f}] "
              f"{statistics.median(cpus):8.1f}")
    total = statistics.median(w for w, _ in rows["all (python -m app compile)"])
    print(f"goal: every kernel from nothing <= {GOAL_S:.0f} s: {'met' if total <= GOAL_S else 'missed'}")
    return 0
