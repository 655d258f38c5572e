"""``python -m app pixel``: why one pixel of a scene looks as it does, in one sentence and its evidence.

Examples::

    python -m app pixel scene.json --at 160,120
    python -m app pixel scene.json --at 160,120 --mode raster --json

In object order (``--mode raster``) the scene is rendered with its step
history and the pixel's fragments are read (:func:`core.pixel_verdict.raster_verdict`);
in image order only the pixel's ray tree is traced (:func:`core.pixel_verdict.trace_verdict`).
Without ``--json`` it prints the sentence, then the fragments or the lights and
rays; with ``--json`` one JSON object (``null``, never NaN).  Imports neither Qt nor VTK.
"""

from __future__ import annotations

import json
import re

from app.commands import render as render_command
from app.process.kernel_loading import load_kernels
from app.usage import UsageError


def add_parser(sub) -> None:
    p = sub.add_parser("pixel", help="say in one sentence what decided one pixel, and the evidence",
                       description="Say in one sentence what decided one pixel of a scene, then the "
                                   "fragments (object order) or the lights and rays (image order) behind it.")
    render_command.add_scene_arguments(p)
    p.add_argument("--at", required=True, metavar="X,Y",
                   help="the pixel: column X and row Y from the top-left, whole numbers")
    p.add_argument("--json", action="store_true", help="print one JSON object")
    p.set_defaults(run=run, accel="bvh", dry_run=False, memory_limit=None)
    p._negative_number_matcher = re.compile(r"^-\.?\d")  # "--at -1,3" is a value, refused in words


def parse_pixel(text: str, width: int, height: int) -> tuple[int, int]:
    """``"X,Y"`` to a pixel of a ``width x height`` image; a :class:`UsageError` naming ``--at`` otherwise."""
    parts = text.split(",")
    try:
        x, y = (int(p) for p in parts)
    except ValueError:
        raise UsageError(f"--at: expected two whole numbers X,Y, got {text!r}") from None
    if not (0 <= x < width and 0 <= y < height):
        raise UsageError(f"--at: pixel ({x}, {y}) is outside the {width} x {height} image "
                         f"(X in 0..{width - 1}, Y in 0..{height - 1})")
    return x, y


def _lines(verdict) -> list[str]:
    lines = [verdict.sentence]
    if verdict.fragments:
        lines.append("fragments (drawn in order, then dropped before drawing, nearest first):")
        for f in verdict.fragments:
            step = "    -" if f.step is None else f"{f.step:5d}"
            plane = f" ({f.plane} plane)" if f.plane else ""
            lines.append(f"  step {step}  {f.object}, {f.polygon}  depth {f.depth:.4g}  {f.fate}{plane}")
    if verdict.lights:
        lines.append("lights:")
        for light in verdict.lights:
            blocked = f", blocked by {light.blocked_by}" if light.blocked_by else ""
            lines.append(f"  {light.name}: {'lit' if light.lit else 'not lit'} ({light.status}){blocked}")
    if verdict.rays:
        lines.append("rays: " + ", ".join(f"{n} {kind}" for kind, n in verdict.rays.items()))
    return lines


def run(args) -> int:
    prepared = render_command.prepare(args, _inputs, [args])
    if prepared is None:
        return 2
    scene, _, _ = prepared
    cam = scene.camera
    x, y = parse_pixel(args.at, cam.width, cam.height)
    load_kernels(args.mode, args.accel)
    from core import pixel_verdict

    if args.mode == "raster":
        from core.object_order.pipeline import RasterSettings, render_raster

        verdict = pixel_verdict.raster_verdict(render_raster(scene, RasterSettings(record_steps=True)), x, y)
    else:
        from core.image_order.flat_scene import TraceSettings
        from core.image_order.ray_tree import trace_pixel

        settings = TraceSettings(mode=args.mode, max_depth=args.max_depth, accel=args.accel)
        verdict = pixel_verdict.trace_verdict(trace_pixel(scene, x, y, settings), scene, args.mode, x, y)
    if args.json:
        print(json.dumps(verdict.to_dict(), allow_nan=False))
    else:
        print("\n".join(_lines(verdict)))
    return 0


def _inputs(args):
    from app.export.image_files import Outputs

    return Outputs(inputs=[args.scene])  # nothing is written: the scene is only read
