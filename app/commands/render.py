"""``python -m app render``: render a scene file headless, in object order or image order.

Writes the image as sRGB PNG (or JPEG for ``.jpg``/``.jpeg``) and, on request,
the depth of the visible surface per pixel (``.npy``: camera-space distance
along the viewing axis, +inf where only background is seen), what each pixel
cost (``--heat-out``, ``.npy``: its intersection tests, or in object order its
fragments) and the render's statistics (JSON: counts and times per stage).  Imports neither Qt nor VTK.

Before any work it checks every output path, loads the scene, and estimates
the render's memory (:mod:`core.budget`): a render over the budget (half of
the available memory unless ``--memory-limit`` says otherwise) is refused,
and one estimated to take long says so before starting.  Every output is
written atomically, after the render (:mod:`app.export.image_files`).
"""

from __future__ import annotations

import io
import json
import os
import sys
from dataclasses import replace

import numpy as np

from app.process.kernel_loading import load_kernels
from app.usage import UsageError

MODES = ("raster", "raycast", "raytrace")
ACCELS = ("none", "spheres", "grid", "grid+spheres", "bvh")
MAX_DEPTH = 64


def add_parser(sub) -> None:
    p = sub.add_parser("render", help="render a scene file to PNG (object order or image order)",
                       description=__doc__.split("\n\n")[0])
    add_scene_arguments(p)
    p.add_argument("--accel", choices=ACCELS, default="bvh",
                   help="image order: how rays find objects (default bvh)")
    p.add_argument("--out", required=True, help="image file to write: .png, or .jpg/.jpeg (JPEG)")
    p.add_argument("--depth-out", help="write the depth per pixel as .npy")
    p.add_argument("--stats-out", help="write counts and times per stage as JSON")
    p.add_argument("--heat-out", metavar="TESTS.npy",
                   help="write what each pixel cost as .npy: image order, (H, W, 2) int64, the primitive "
                        "tests and the box and sphere tests (bounding spheres, BVH boxes, grid cells "
                        "walked) of all its rays; raster, (H, W) int64, the fragments that reached it; "
                        "they add up to --stats-out's totals")
    p.add_argument("--dry-run", action="store_true",
                   help="check the scene and the output paths, print the estimated cost, "
                        "and stop before rendering")
    p.add_argument("--memory-limit", metavar="SIZE",
                   help="refuse a render estimated to need more memory, e.g. 8G or 512M "
                        "(default: half of the memory available)")
    p.set_defaults(run=run)


def add_scene_arguments(p) -> None:
    """The scene file, the pipeline and the camera's overrides, as ``render`` and ``pixel`` take them."""
    p.add_argument("scene", help="scene JSON file")
    p.add_argument("--mode", choices=MODES, default="raytrace",
                   help="raster: object order (z-buffer); raycast / raytrace: image order")
    p.add_argument("--projection", choices=("perspective", "orthographic"),
                   help="override the scene camera's projection")
    p.add_argument("--width", type=int, help="image width in pixels (overrides the scene)")
    p.add_argument("--height", type=int, help="image height in pixels (overrides the scene)")
    p.add_argument("--max-depth", type=int, default=5, help="ray tracing: deepest bounce (default 5)")


def camera_overrides(args) -> dict:
    changes = {}
    for key in ("width", "height"):
        value = getattr(args, key)
        if value is not None:
            if not 1 <= value <= 16384:
                raise UsageError(f"--{key}: must be a whole number of pixels in [1, 16384], got {value}")
            changes[key] = value
    if args.projection:
        changes["projection"] = args.projection
    if not 0 <= args.max_depth <= MAX_DEPTH:
        raise UsageError(f"--max-depth: must be a whole number in [0, {MAX_DEPTH}], "
                         f"got {args.max_depth}")
    return changes


def _outputs(args):
    from app.export.image_files import IMAGE_EXTENSIONS, Outputs

    outputs = Outputs(inputs=[args.scene])
    try:
        outputs.add("--out", args.out, tuple(IMAGE_EXTENSIONS))
        if args.depth_out:
            outputs.add("--depth-out", args.depth_out, (".npy",))
        if args.stats_out:
            outputs.add("--stats-out", args.stats_out, (".json",))
        if args.heat_out:
            outputs.add("--heat-out", args.heat_out, (".npy",))
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    return outputs


def parse_memory_limit(text: str | None) -> int | None:
    """``--memory-limit``'s value in bytes (None when not given); a bad one raises :class:`UsageError`."""
    from core import budget

    try:
        return None if text is None else budget.parse_size(text)
    except ValueError as exc:
        raise UsageError(f"--memory-limit: {exc}") from None


def budget_limit(args) -> tuple[int, str]:
    from core import budget

    return budget.memory_limit(parse_memory_limit(args.memory_limit))


def check_cost(scene, args, limit: int, limit_source: str) -> None:
    """Refuse a render over the memory budget; say so when it will be slow (or asked to)."""
    from core import budget
    from core.in_words import counted

    cost = budget.estimate(scene, args.mode, args.accel, args.max_depth)
    cam = scene.camera
    objects = counted(len(scene.objects), "object")
    judge_cost(args, cost, limit, limit_source,
               what=f"{cam.width} × {cam.height} {args.mode} of {objects}",
               summary=f"{args.mode}: {cam.width}x{cam.height} pixels, {objects}",
               reduce="use a smaller image (--width/--height), fewer objects or triangles, or --memory-limit")


def judge_cost(args, cost, limit: int, limit_source: str, *, what: str, summary: str, reduce: str) -> None:
    """Refuse work whose estimated ``cost`` is over the memory budget (:class:`UsageError`, naming
    ``what`` and how to ``reduce`` it); print the estimate after ``summary`` for ``--dry-run``, or
    announce it on stderr when it will be slow."""
    from core import budget

    over = budget.refusal(what, cost, limit, limit_source)
    if over:
        raise UsageError(f"{over}; {reduce}")
    if args.dry_run:
        print(f"{summary}: about {budget.format_bytes(cost.bytes)} of memory and "
              f"{budget.format_seconds(cost.seconds)}; nothing rendered (--dry-run)")
    elif cost.seconds > budget.SLOW_SECONDS:
        why = f": {cost.slow_because}" if cost.slow_because else ""
        print(f"python -m app {args.command}: {what}: estimated time about "
              f"{budget.format_seconds(cost.seconds)} and {budget.format_bytes(cost.bytes)} of memory{why}",
              file=sys.stderr, flush=True)


def load_scene(args, outputs, changes: dict):
    """The scene of ``args.scene`` with the camera ``changes``, checked against ``outputs``.

    Raises
    ------
    core.files.scene_file.SceneFileError
        For a scene file that cannot be read or is invalid.
    UsageError
        For an output that names one of the scene's mesh files, or options
        that make the camera invalid.
    """
    from core.camera import camera_problems
    from core.files import scene_file
    from core.files.mesh_files import read_mesh

    scene = scene_file.load(args.scene, read_mesh=read_mesh)
    meshes = [o.source["resolved_path"] for o in scene.objects
              if getattr(o, "source", None) and "resolved_path" in o.source]
    try:
        for option, path in outputs.paths.items():
            outputs.check_inputs(option, path, meshes)
    except ValueError as exc:
        raise UsageError(str(exc)) from None
    scene = replace(scene, camera=scene.camera.replace(**changes))
    problems = camera_problems(scene.camera)
    if problems:
        key, message = problems[0]
        raise UsageError(f"{args.scene}: with the options given, camera.{key}: {message}")
    return scene


def prepare(args, make_outputs, runs) -> tuple | None:
    """What ``render`` and ``export`` do before any work, in this order.

    Read the camera options, the memory budget and the output paths
    (``make_outputs(args)``), load and check the scene, then check the cost of
    each of ``runs`` (argument sets, one per pipeline the command will run).
    Returns ``(scene, outputs, limit)``, or ``None`` after printing why the scene
    file was refused (exit status 2); bad options raise :class:`UsageError`.
    """
    from core.files import scene_file

    changes = camera_overrides(args)
    limit, limit_source = budget_limit(args)
    outputs = make_outputs(args)
    try:
        scene = load_scene(args, outputs, changes)
    except scene_file.SceneFileError as exc:
        print(f"python -m app {args.command}: error: {exc}", file=sys.stderr)
        return None
    for run_args in runs:
        check_cost(scene, run_args, limit, limit_source)
    return scene, outputs, limit


def run(args) -> int:
    prepared = prepare(args, _outputs, [args])
    if prepared is None:
        return 2
    scene, outputs, _ = prepared
    if args.dry_run:
        return 0

    compile_s = load_kernels(args.mode, args.accel)
    if args.mode == "raster":
        from core.object_order.pipeline import RasterSettings, render_raster

        result = render_raster(scene, RasterSettings(record_steps=bool(args.heat_out)))
        heat = result.history.fragments_per_pixel() if args.heat_out else None
    else:
        from core.image_order.ray_tracing import TraceSettings, render_trace

        settings = TraceSettings(mode=args.mode, max_depth=args.max_depth, accel=args.accel)
        result = render_trace(scene, settings, heat=bool(args.heat_out))
        heat = result.heat

    result.stats["compile_s"] += compile_s  # the kernels were loaded just before the render

    from app.export.image_files import OutputError, encode_image

    contents = {"--out": encode_image(result.color, os.path.splitext(outputs.paths["--out"])[1])}
    for option, array in (("--depth-out", result.depth), ("--heat-out", heat)):
        if getattr(args, option[2:].replace("-", "_")):
            buffer = io.BytesIO()
            np.save(buffer, array)
            contents[option] = buffer.getvalue()
    if args.stats_out:
        contents["--stats-out"] = (json.dumps(result.stats, indent=2) + "\n").encode()
    try:
        outputs.write(contents)
    except OutputError as exc:
        print(f"python -m app render: error: {exc}", file=sys.stderr)
        return 1
    h, w = result.depth.shape
    times = result.stats["times"]
    total = times["total"] if "total" in times else sum(times.values())
    print(f"{args.mode}: {w}x{h} pixels in {total * 1000:.1f} ms -> {args.out}")
    return 0

