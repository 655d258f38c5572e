"""``python -m app export``: save what the window shows as a picture or an animation, headless.

``--what`` chooses the picture:

- ``image``: the image of one pipeline (``--mode``), pixel for pixel;
- ``zbuffer``: the z-buffer as grey levels (near black, the far plane white)
  with its scale in scene units;
- ``zbuffer-steps``: an animation, one frame per step of the z-buffer
  algorithm (step 0 the cleared buffers, then one step per polygon), image
  memory beside the z-buffer, the step's polygon tinted and a frame counter;
- ``four-views``: the front, side and top orthographic views and the
  observer's view in one picture;
- ``compare``: two outputs (``--pair``), their difference image with its colour
  scale and units, and the sentences that explain it: the sheet of the
  Compare tab's File → Export (:mod:`app.export.comparison_sheet`);
- ``orbit``: an animation of the observer walking once around the target in
  ``--frames`` steps, each frame the chosen pipeline's image.

Still pictures are PNG (or JPEG), animations GIF or MP4 (imageio, with
imageio-ffmpeg for MP4).  Scenes are loaded, checked and budgeted as
``render`` does, and the z-buffer steps refused before rendering when they
would make too long an animation; colours are written as sRGB
(:mod:`core.srgb`); every file is written atomically (:mod:`core.files.safe_files`).
The sheets and frames are those of the window's File → Export
(:mod:`app.export.picture_sheet`, :mod:`app.export.animation_frames`).  Imports neither Qt
nor VTK.
"""

from __future__ import annotations

import os
import sys

import numpy as np

from app.commands.render import ACCELS, MODES, budget_limit, judge_cost, prepare
from app.export.animation_frames import MAX_FRAMES, orbit_frames, steps_problem, zbuffer_steps
from app.export.picture_sheet import four_views, zbuffer_sheet
from app.process.kernel_loading import load_kernels
from app.usage import UsageError

WHATS = ("image", "zbuffer", "zbuffer-steps", "four-views", "compare", "orbit")
ANIMATIONS = ("zbuffer-steps", "orbit")


def add_parser(sub) -> None:
    p = sub.add_parser("export", help="save an image, the z-buffer, its steps, four views, a comparison "
                                      "or an orbit as PNG, GIF or MP4",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("scene", help="scene JSON file")
    p.add_argument("--what", choices=WHATS, required=True, help="what to export")
    p.add_argument("--mode", choices=MODES, default="raster",
                   help="the pipeline of image, four-views and orbit (default raster)")
    p.add_argument("--pair", default="perspective,raytrace", metavar="A,B",
                   help="compare: two of orthographic, perspective, raycast, raytrace "
                        "(default perspective,raytrace)")
    p.add_argument("--frames", type=int, help="orbit: number of frames (default 36)")
    p.add_argument("--fps", type=int, default=10, help="animations: frames per second (default 10)")
    p.add_argument("--projection", choices=("perspective", "orthographic"),
                   help="override the scene camera's projection")
    p.add_argument("--width", type=int, help="image width in pixels (overrides the scene)")
    p.add_argument("--height", type=int, help="image height in pixels (overrides the scene)")
    p.add_argument("--max-depth", type=int, default=5, help="ray tracing: deepest bounce (default 5)")
    p.add_argument("--accel", choices=ACCELS, default="bvh", help="image order: how rays find objects")
    p.add_argument("--out", required=True,
                   help="file to write: .png (or .jpg) for pictures, .gif or .mp4 for animations")
    p.add_argument("--dry-run", action="store_true",
                   help="check the scene and the output path, print the estimated cost, and stop")
    p.add_argument("--memory-limit", metavar="SIZE",
                   help="refuse an export estimated to need more memory, e.g. 8G or 512M")
    p.set_defaults(run=run)


def _pair(args) -> tuple[str, str]:
    from core.compare import OUTPUTS

    parts = [p.strip() for p in args.pair.split(",")]
    if len(parts) != 2 or any(p not in OUTPUTS for p in parts):
        raise UsageError(f"--pair: must be two of {', '.join(OUTPUTS)} separated by a comma, "
                         f"got {args.pair!r}")
    return parts[0], parts[1]


def _check_arguments(args) -> None:
    if args.frames is not None and args.what != "orbit":
        raise UsageError(f"--frames: applies to --what orbit only (zbuffer-steps has one frame per "
                         f"polygon), not to --what {args.what}")
    frames = 36 if args.frames is None else args.frames
    if not 1 <= frames <= MAX_FRAMES:
        raise UsageError(f"--frames: must be a whole number in [1, {MAX_FRAMES}], got {frames}")
    args.frames = frames
    if not 1 <= args.fps <= 60:
        raise UsageError(f"--fps: must be a whole number in [1, 60], got {args.fps}")
    if args.what == "compare":
        _pair(args)


def _outputs(args):
    from app.export.image_files import ANIMATION_EXTENSIONS, IMAGE_EXTENSIONS, Outputs

    extensions = ANIMATION_EXTENSIONS if args.what in ANIMATIONS else tuple(IMAGE_EXTENSIONS)
    outputs = Outputs(inputs=[args.scene])
    try:
        outputs.add("--out", args.out, extensions)
    except ValueError as exc:
        raise UsageError(f"{exc} for --what {args.what}") from None
    return outputs


def _modes(args) -> list[str]:
    """The pipelines the export runs, for the cost check."""
    if args.what in ("zbuffer", "zbuffer-steps"):
        return ["raster"]
    if args.what == "compare":
        return sorted({"raster" if p in ("orthographic", "perspective") else p for p in _pair(args)})
    return [args.mode]


def run(args) -> int:
    _check_arguments(args)
    prepared = prepare(args, _outputs, [])
    if prepared is None:
        return 2
    scene, outputs, limit = prepared
    extension = os.path.splitext(outputs.paths["--out"])[1].lower()
    if args.what == "zbuffer-steps":
        problem = steps_problem(scene, extension, limit)
        if problem:
            raise UsageError(f"--what zbuffer-steps: {problem}")
    from core.in_words import counted

    cam = scene.camera
    judge_cost(args, export_cost(scene, args, extension), limit, budget_limit(args)[1],
               what=f"--what {args.what} at {cam.width} × {cam.height}",
               summary=f"{args.what}: {cam.width}x{cam.height} pixels, "
                       f"{counted(len(scene.objects), 'object')}",
               reduce="use a smaller image (--width/--height), fewer frames or objects, MP4 rather "
                      "than GIF, or --memory-limit")
    if args.dry_run:
        return 0
    for mode in {*_modes(args), *(["raster"] if args.what == "four-views" else [])}:
        load_kernels(mode, args.accel)
    from app.export.image_files import OutputError, encode_animation, encode_image

    try:
        if args.what in ANIMATIONS:
            data = encode_animation(_animation(scene, args), extension, args.fps, limit)
        else:
            data = encode_image(_picture(scene, args), extension)
    except OSError as exc:  # the encoder failed (OutputError), or its temporary folder cannot be made
        print(f"python -m app export: error: cannot write {args.out}: {exc}; any previous file there "
              "is unchanged", file=sys.stderr)
        return 1
    try:
        outputs.write({"--out": data})
    except OutputError as exc:
        print(f"python -m app export: error: {exc}", file=sys.stderr)
        return 1
    print(f"{args.what}: -> {args.out}")
    return 0


def export_cost(scene, args, extension: str):
    """The export's estimated peak memory and time (:class:`core.budget.Estimate`).

    Its renders run one after another, so the time is theirs added up and the
    memory the largest one's (:func:`core.budget.combined`): one per pipeline
    for ``image``, ``zbuffer`` and ``compare``; the three orthographic views by
    the z-buffer and the observer's by ``--mode`` for ``four-views``; one per
    frame for ``orbit``; one recording every step for ``zbuffer-steps``
    (:func:`app.export.animation_frames.steps_problem` checks its frames).  A GIF
    holds every frame, 3 bytes a pixel, until it is written; an MP4 one.
    """
    from core import budget

    def cost(mode):
        return budget.estimate(scene, mode, args.accel, args.max_depth)

    if args.what == "four-views":
        runs = [cost("raster")] * 3 + [cost(args.mode)]
    elif args.what == "orbit":
        runs = [cost(args.mode)] * args.frames
    else:
        runs = [cost(mode) for mode in _modes(args)]
    total = budget.combined(runs)
    if args.what == "orbit" and extension == ".gif":
        cam = scene.camera
        frames = args.frames * cam.width * cam.height * 3
        total = budget.Estimate(total.bytes + frames, {**total.parts, "GIF frames": frames}, total.seconds,
                                total.slow_because)
    return total


# --- rendering --------------------------------------------------------------------------------------------


def render(scene, args) -> np.ndarray:
    """The image (H, W, 3, linear RGB) of ``scene`` by the pipeline ``args.mode``."""
    if args.mode == "raster":
        from core.object_order.pipeline import render_raster

        return render_raster(scene).color
    from core.image_order.ray_tracing import render_trace

    return render_trace(scene, _trace_settings(args, args.mode)).color


def _trace_settings(args, mode):
    from core.image_order.ray_tracing import TraceSettings

    return TraceSettings(mode=mode, max_depth=args.max_depth, accel=args.accel)


def _picture(scene, args) -> np.ndarray:
    """The still picture ``args.what`` of ``scene`` (linear RGB)."""
    if args.what == "image":
        return render(scene, args)
    if args.what == "zbuffer":
        from core.object_order.pipeline import render_raster

        cam = scene.camera
        return zbuffer_sheet(render_raster(scene).depth, cam.near, cam.far)
    if args.what == "four-views":
        traced = None if args.mode == "raster" else lambda view: render(view, args)
        return four_views(scene, args.mode, traced)
    return _comparison(scene, args)


def _comparison(scene, args) -> np.ndarray:
    from app.export.comparison_sheet import comparison_sheet
    from core.compare import compare

    a, b = _pair(args)
    return comparison_sheet(compare(scene, a, b, _trace_settings(args, "raytrace")))


# --- animations ---------------------------------------------------------------------------------------


def _animation(scene, args):
    """The frames of ``args.what``, with a progress bar on the terminal."""
    from tqdm import tqdm

    if args.what == "zbuffer-steps":
        from core.object_order.pipeline import RasterSettings

        count, frames = zbuffer_steps(scene, RasterSettings())
    else:
        count, frames = args.frames, orbit_frames(scene, args.frames, lambda view: render(view, args))
    with tqdm(total=count, desc=f"python -m app export: {args.what}", unit="frame", file=sys.stderr,
              leave=False) as bar:
        for frame in frames:
            yield frame
            bar.update(1)
