"""The command line: ``python -m app [SCENE.json]`` opens the window; subcommands answer headless.

Each subcommand imports only what it needs, so ``intersect`` answers without
loading Qt or VTK.
"""

from __future__ import annotations

import argparse
import sys


class UsageError(Exception):
    """A bad command-line argument; the message names the argument."""


def build_parser() -> argparse.ArgumentParser:
    from app import intersect_command

    parser = argparse.ArgumentParser(
        prog="python -m app",
        description="Render Explorer: see how a 3D scene becomes pixels.",
    )
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    gui = sub.add_parser("gui", help="open the window (the default when no command is given)")
    gui.add_argument("scene", nargs="?", help="a scene JSON file (default: the lecture scene)")
    intersect_command.add_parser(sub)
    return parser


def main(argv: list[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] not in {"gui", "intersect", "-h", "--help"}:
        argv.insert(0, "gui")
    parser = build_parser()
    args = parser.parse_args(argv)
    try:
        if args.command == "gui":
            from app.main_window import run

            return run(args.scene)
        return args.run(args)
    except UsageError as exc:
        print(f"{parser.prog}: error: {exc}", file=sys.stderr)
        return 2
