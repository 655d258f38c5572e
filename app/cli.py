"""The command line: ``python -m app [SCENE.json]`` opens the window; subcommands answer headless.

Each subcommand imports only what it needs, so ``intersect`` answers without
loading Qt or VTK.
"""

from __future__ import annotations

import argparse
import importlib
import os
import signal
import sys

from app.process import ctrl_c
from app.usage import UsageError
from core.stopping import StoppedError

SUBCOMMANDS = {"intersect": "intersect", "render": "render", "pixel": "pixel", "hardcases": "hardcases",
               "cost": "cost", "export": "export", "compile": "compile_kernels", "lesson": "lesson"}
"""Each subcommand's module in :mod:`app.commands`."""
BENCHMARKS = {"raster": "raster", "trace": "trace", "gui": "gui", "startup": "startup",
              "compile": "compile_time"}
"""Each ``bench`` kind's module in :mod:`app.bench`."""


def build_parser(command: str | None = None) -> argparse.ArgumentParser:
    """The command line's parser; with ``command``, only that subcommand's module is imported and
    parsed (a run names one), else every subcommand's (``--help`` lists them all)."""
    parser = argparse.ArgumentParser(
        prog="python -m app",
        description="Render Explorer: see how a 3D scene becomes pixels.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    window = sub.add_parser("gui", help="open the window (the default when no command is given)")
    window.add_argument("scene", nargs="?", help="a scene JSON file (default: the lecture scene)")
    window.add_argument("--memory-limit", metavar="SIZE",
                        help="refuse renders estimated to need more memory, e.g. 8G or 512M "
                           "(default: half of the memory available)")
    for name, module in SUBCOMMANDS.items():
        if command in (None, name):
            importlib.import_module(f"app.commands.{module}").add_parser(sub)
    if command in (None, "bench"):
        bench_parser = sub.add_parser(
            "bench", help="time our pipelines against VTK / Embree (a benchmark, not a test)")
        kinds = bench_parser.add_subparsers(dest="bench", metavar="KIND", required=True)
        for name, module in BENCHMARKS.items():
            bench = importlib.import_module(f"app.bench.{module}")
            p = kinds.add_parser(name, help=bench.__doc__.split("\n")[0].split(": ", 1)[-1])
            bench.add_arguments(p)
            p.set_defaults(run=bench.run)
    return parser


#: The first words the command line understands; anything else opens the window on it.
COMMANDS = {"gui", "bench", *SUBCOMMANDS, "-h", "--help"}


INTERRUPTED = "python -m app: interrupted; no output file was written or changed"


def interrupted() -> None:
    """Say so and end the process with status 130 at once, without the interpreter's shutdown.

    After a stopped render, tearing down numba's worker threads and freeing the render's arrays
    took about a second on a busy machine; and a second Ctrl+C meanwhile is ignored, so that it
    cannot end the process by the signal (status -2) instead.
    """
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    print(INTERRUPTED, file=sys.stderr)
    sys.stdout.flush()
    sys.stderr.flush()
    os._exit(130)


def _pressed_ctrl_c(exc: BaseException) -> bool:
    """Whether a ``KeyboardInterrupt`` is among the causes of ``exc`` (raised from it, or while
    handling it)."""
    seen = set()
    while exc is not None and id(exc) not in seen:
        if isinstance(exc, KeyboardInterrupt):
            return True
        seen.add(id(exc))
        exc = exc.__cause__ or exc.__context__
    return False


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] not in COMMANDS:
        argv.insert(0, "gui")
    if hasattr(signal, "SIGXFSZ"):  # over a file-size limit a write fails; the process lives
        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    parser = build_parser(None if argv[0] in ("-h", "--help") else argv[0])
    args = parser.parse_args(argv)
    try:
        if args.command == "gui":
            from app.window.display_check import why_no_display

            if (problem := why_no_display()) is not None:
                print(f"{parser.prog}: error: {problem}", file=sys.stderr)
                return 2
            from app.commands.render import parse_memory_limit
            from app.window.main_window import run

            return run(args.scene, parse_memory_limit(args.memory_limit))
        ctrl_c.stop_kernels_on_ctrl_c()
        return args.run(args)
    except UsageError as exc:
        print(f"{parser.prog}: error: {exc}", file=sys.stderr)
        return 2
    except (KeyboardInterrupt, StoppedError):
        if args.command != "gui":  # every file is closed and every temporary file gone by now
            interrupted()
        print(INTERRUPTED, file=sys.stderr)
        return 130
    except MemoryError:
        print(f"{parser.prog}: error: out of memory; use a smaller image (--width/--height), "
              "fewer objects, or a lower --memory-limit", file=sys.stderr)
        return 2
    except Exception as exc:
        # Ctrl+C that reaches the main thread inside a compiled kernel can come out of numba's
        # dispatcher as "SystemError: ... returned a result with an exception set"; inside the
        # initialisation of an extension module a command imports when it needs it (matplotlib's
        # ft2font, in the Cost sweep's first 0.3 s) as "ImportError: initialization failed"; inside a
        # class being made as a module loads (matplotlib's Axis) as "RuntimeError: Error calling
        # __set_name__": the interrupt is among their causes.
        if not _pressed_ctrl_c(exc):
            raise
        interrupted()
