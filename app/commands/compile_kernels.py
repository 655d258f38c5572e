"""``python -m app compile``: compile every renderer's kernels now, on every core, once per machine.

Examples::

    python -m app compile            # what is not compiled yet, each kernel group in its own process
    python -m app compile --quiet    # say nothing when everything is compiled already

The kernels are kept in the user's cache folder (:mod:`core.compiling.kernel_cache`), so
this is done once per machine and version of the code; afterwards every render,
test and window loads them in a second or two.  Each kernel group
(:data:`core.compiling.warm_up.GROUPS`) compiles in a process of its own, as many at once as
there are cores.  Exit status 0 when every group is compiled, 1 when one failed
(its error is printed), 130 on Ctrl+C.
"""

from __future__ import annotations

import argparse
import os
import subprocess
import sys
import time
from pathlib import Path

from core import give_way
from core.compiling.warm_up import GROUPS, warm_up_of

#: The folder that holds the ``app`` package: on the path of every process this command starts.
_ROOT = str(Path(__file__).resolve().parents[2])


def child_env(env: dict | None = None) -> dict:
    """``env`` (default: this process's) for a ``python -m app`` child, which finds this very code."""
    env = dict(os.environ if env is None else env)
    env["PYTHONPATH"] = os.pathsep.join(filter(None, [_ROOT, env.get("PYTHONPATH")]))
    return env


def add_parser(sub) -> argparse.ArgumentParser:
    """Add the ``compile`` command to ``sub``."""
    parser = sub.add_parser(
        "compile",
        help="compile the renderers' kernels now (once per machine; renders then start at once)",
        description="Compile every kernel group that is not compiled on this machine yet, each in a "
                    "process of its own, on every core.",
    )
    parser.add_argument("--quiet", action="store_true", help="print nothing when all is compiled already")
    parser.add_argument("--group", choices=sorted(GROUPS), action="append",
                        help="compile only this group (may be repeated)")
    parser.add_argument("--in-process", action="store_true", help=argparse.SUPPRESS)
    parser.add_argument("--give-way", action="store_true",
                        help="run at a lower priority, beside a window that should stay smooth")
    parser.set_defaults(run=run)
    return parser


def run(args) -> int:
    groups = args.group or list(GROUPS)
    if args.give_way:  # the processes it starts for each group inherit it
        give_way.lower_this_process()
    if args.in_process:  # one group, in the process the parent started for it
        for group in groups:
            print(f"{warm_up_of(group)():.1f}", flush=True)
        return 0
    missing = [g for g in groups if not warm_up_of(g).ready()]
    from core.compiling.kernel_cache import cache_root

    if not missing:
        if not args.quiet:
            print(f"python -m app compile: every kernel group is compiled already (in {cache_root()})")
        return 0
    cores = min(len(missing), os.cpu_count() or 1)
    print(f"python -m app compile: compiling the renderers' kernels ({', '.join(missing)}) on "
          f"{cores} core{'s' if cores > 1 else ''}; this happens once per machine and version of "
          f"the code, and they are kept in {cache_root()}", flush=True)
    return compile_groups(missing)


def compile_groups(groups: list[str], env: dict | None = None) -> int:
    """Compile ``groups`` in processes of their own, as many at once as there are cores; print each
    group's time as it ends.  Returns 0, or 1 if a group failed."""
    env = child_env(env)
    waiting, running, failed = list(groups), {}, False
    start = time.perf_counter()
    try:
        while waiting or running:
            while waiting and len(running) < (os.cpu_count() or 1):
                group = waiting.pop(0)
                running[group] = subprocess.Popen(
                    [sys.executable, "-m", "app", "compile", "--in-process", "--group", group],
                    env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            group, done = _next_to_end(running)
            out, err = done.communicate()
            del running[group]
            if done.returncode == 0:
                print(f"  {group}: compiled in {time.perf_counter() - start:.0f} s", flush=True)
            else:
                failed = True
                last = (err.strip().splitlines() or ["(no message)"])[-1]
                print(f"python -m app compile: the {group} kernels did not compile: {last}", file=sys.stderr)
    finally:
        for process in running.values():
            process.kill()
    return 1 if failed else 0


def _next_to_end(running: dict) -> tuple[str, subprocess.Popen]:
    """Wait until one of ``running``'s processes ends; its group and process."""
    while True:
        for group, process in running.items():
            if process.poll() is not None:
                return group, process
        time.sleep(0.2)
