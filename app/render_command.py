"""``python -m app render``: render a scene file headless, in object order or image order.

Writes the image as PNG and, on request, the depth of the visible surface per
pixel (``.npy``: camera-space distance along the viewing axis, +inf where only
background is seen) and the render's statistics (JSON: counts and times per
stage).  Imports neither Qt nor VTK unless the scene names a mesh file.
"""

from __future__ import annotations

import json
import sys
from dataclasses import replace
from pathlib import Path

import numpy as np

MODES = ("raster", "raycast", "raytrace")
ACCELS = ("none", "spheres", "grid", "grid+spheres", "bvh")


def add_parser(sub) -> None:
    p = sub.add_parser("render", help="render a scene file to PNG (object order or image order)",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("scene", help="scene JSON file")
    p.add_argument("--mode", choices=MODES, default="raytrace",
                   help="raster: object order (z-buffer); raycast / raytrace: image order")
    p.add_argument("--projection", choices=("perspective", "orthographic"),
                   help="override the scene camera's projection")
    p.add_argument("--width", type=int, help="image width in pixels (overrides the scene)")
    p.add_argument("--height", type=int, help="image height in pixels (overrides the scene)")
    p.add_argument("--max-depth", type=int, default=5, help="ray tracing: deepest bounce (default 5)")
    p.add_argument("--accel", choices=ACCELS, default="bvh",
                   help="image order: how rays find objects (default bvh)")
    p.add_argument("--out", required=True, help="PNG file to write")
    p.add_argument("--depth-out", help="write the depth per pixel as .npy")
    p.add_argument("--stats-out", help="write counts and times per stage as JSON")
    p.set_defaults(run=run)


def _camera_overrides(args) -> dict:
    from app.usage import UsageError

    changes = {}
    for key in ("width", "height"):
        value = getattr(args, key)
        if value is not None:
            if not 1 <= value <= 16384:
                raise UsageError(f"--{key}: must be a whole number of pixels in [1, 16384], got {value}")
            changes[key] = value
    if args.projection:
        changes["projection"] = args.projection
    if args.max_depth < 0:
        raise UsageError(f"--max-depth: must be >= 0, got {args.max_depth}")
    return changes


def run(args) -> int:
    from app.mesh_files import read_mesh
    from core import scene_file

    changes = _camera_overrides(args)
    try:
        scene = scene_file.load(args.scene, read_mesh=read_mesh)
    except scene_file.SceneFileError as exc:
        print(f"python -m app render: error: {exc}", file=sys.stderr)
        return 2
    scene = replace(scene, camera=scene.camera.replace(**changes))
    if args.mode == "raster":
        from core.object_order.pipeline import RasterSettings, render_raster

        result = render_raster(scene, RasterSettings())
    else:
        from core.image_order.ray_tracing import TraceSettings, render_trace

        settings = TraceSettings(mode=args.mode, max_depth=args.max_depth, accel=args.accel)
        result = render_trace(scene, settings)
    try:
        from app.png import write_png

        write_png(args.out, result.color)
        if args.depth_out:
            np.save(args.depth_out, result.depth)
        if args.stats_out:
            Path(args.stats_out).write_text(json.dumps(result.stats, indent=2) + "\n")
    except OSError as exc:
        print(f"python -m app render: error: cannot write output: {exc}", file=sys.stderr)
        return 1
    h, w = result.depth.shape
    times = result.stats["times"]
    total = times["total"] if "total" in times else sum(times.values())
    print(f"{args.mode}: {w}x{h} pixels in {total * 1000:.1f} ms -> {args.out}")
    return 0
