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
  scale, and the sentences that explain it;
- ``orbit``: an animation of the observer walking once around the target in
  ``--frames`` steps, each frame the chosen pipeline's image.

Still pictures are PNG (or JPEG), animations GIF or MP4 (imageio, with
imageio-ffmpeg for MP4).  Scenes are loaded, checked and budgeted as
``render`` does; colours are written as sRGB (:mod:`core.srgb`); every file is
written atomically (:mod:`core.safe_files`).  Imports neither Qt nor VTK; text
is drawn with matplotlib's Agg canvas.
"""

from __future__ import annotations

import copy
import os
import sys
import tempfile
import textwrap
from dataclasses import dataclass, replace

import numpy as np

from app.render_command import ACCELS, MODES, prepare
from app.usage import UsageError

WHATS = ("image", "zbuffer", "zbuffer-steps", "four-views", "compare", "orbit")
ANIMATIONS = ("zbuffer-steps", "orbit")
ANIMATION_EXTENSIONS = (".gif", ".mp4")
MAX_FRAMES = 1000
#: Sheet layout, in pixels: the gap around panels, a panel title's row, a line of text.
MARGIN, TITLE_ROW, TEXT_ROW = 8, 20, 16
SHEET = (1.0, 1.0, 1.0)  # the sheet's background, linear RGB
PASSED_TINT, FAILED_TINT = (1.0, 0.1, 0.8), (0.0, 0.8, 1.0)


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
    from app.image_files import IMAGE_EXTENSIONS, Outputs

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
    prepared = prepare(args, _outputs, [_with_mode(args, mode) for mode in _modes(args)])
    if prepared is None:
        return 2
    scene, outputs, limit = prepared
    if args.dry_run:
        return 0
    path = outputs.paths["--out"]
    extension = os.path.splitext(path)[1].lower()
    if args.what in ANIMATIONS:
        frames = _steps_frames(scene) if args.what == "zbuffer-steps" else _orbit_frames(scene, args)
        data = encode_animation(frames, extension, args.fps, limit)
    else:
        from app.image_files import encode_image

        data = encode_image(_picture(scene, args), extension)

    from app.image_files import OutputError

    try:
        outputs.write({"--out": data})
    except OutputError as exc:
        print(f"python -m app export: error: {exc}", file=sys.stderr)
        return 1
    print(f"{args.what}: -> {args.out}")
    return 0


def _with_mode(args, mode: str):
    """A copy of the parsed arguments with ``--mode`` changed (for the cost check of each pipeline)."""
    other = copy.copy(args)
    other.mode = mode
    return other


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


def depth_grey(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Distances along the viewing axis (H, W) as grey (H, W, 3): near black, the far plane and +inf white.

    The grey is linear RGB that a file shows as the sRGB level ``(d - near) / (far - near)``.
    """
    from core.srgb import srgb_to_linear

    level = np.clip((np.asarray(depth, dtype=float) - near) / (far - near), 0.0, 1.0)
    return srgb_to_linear(np.repeat(level[..., None], 3, axis=2))


@dataclass
class Panel:
    """One image of a sheet, with its title and, optionally, a scale bar under it.

    Attributes
    ----------
    title : str, drawn above the image.
    image : (H, W, 3) float64, linear RGB.
    bar : (h, W, 3) float64 or None, a scale strip under the image (linear RGB).
    bar_labels : (left, right) labels under the bar's ends.
    """

    title: str
    image: np.ndarray
    bar: np.ndarray | None = None
    bar_labels: tuple[str, str] = ("", "")


def _panel_height(panel: Panel) -> int:
    h = TITLE_ROW + panel.image.shape[0]
    if panel.bar is not None:
        h += 4 + panel.bar.shape[0] + TEXT_ROW
    return h


def panel_origins(panels: list[Panel], columns: int) -> list[tuple[int, int]]:
    """The top-left pixel (column, row) of every panel's image on the sheet."""
    rows = [panels[i:i + columns] for i in range(0, len(panels), columns)]
    widths = [max(p.image.shape[1] for p in panels[c::columns]) for c in range(min(columns, len(panels)))]
    origins, top = [], MARGIN
    for row in rows:
        left = MARGIN
        for c in range(len(row)):
            origins.append((left, top + TITLE_ROW))
            left += widths[c] + MARGIN
        top += max(_panel_height(p) for p in row) + MARGIN
    return origins


def compose(panels: list[Panel], columns: int, caption: list[str] = (),
            lines: int | None = None) -> np.ndarray:
    """Panels in a grid with their titles and scales, and caption lines under them.

    ``lines`` fixes the number of caption lines (cut or padded), so that the
    frames of an animation all have one size.

    Returns
    -------
    (H, W, 3) float64
        Linear RGB, to be written with :func:`app.image_files.encode_image`.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from core.srgb import srgb_to_linear, to_srgb8

    origins = panel_origins(panels, columns)
    right = max(x + p.image.shape[1] for (x, _), p in zip(origins, panels, strict=True)) + MARGIN
    bottom = max(y - TITLE_ROW + _panel_height(p) for (_, y), p in zip(origins, panels, strict=True))
    width = max(right, 2 * MARGIN + 40)
    chars = max(20, int((width - 2 * MARGIN) / 6.9))
    wrapped = [line for sentence in caption for line in textwrap.wrap(sentence, chars)]
    if lines is not None:
        wrapped = (wrapped + [""] * lines)[:lines]
    lines = wrapped
    height = bottom + MARGIN + TEXT_ROW * len(lines) + (MARGIN if lines else 0)
    sheet = np.empty((height, width, 3))
    sheet[:] = SHEET
    texts = []
    for (x, y), panel in zip(origins, panels, strict=True):
        h, w = panel.image.shape[:2]
        sheet[y:y + h, x:x + w] = panel.image
        texts.append((x, y - TITLE_ROW + 3, panel.title, 10, "left"))
        if panel.bar is not None:
            top = y + h + 4
            sheet[top:top + panel.bar.shape[0], x:x + panel.bar.shape[1]] = panel.bar
            below = top + panel.bar.shape[0] + 1
            texts.append((x, below, panel.bar_labels[0], 8.5, "left"))
            texts.append((x + panel.bar.shape[1], below, panel.bar_labels[1], 8.5, "right"))
    for i, line in enumerate(lines):
        texts.append((MARGIN, bottom + MARGIN + i * TEXT_ROW, line, 9, "left"))
    fig = Figure(figsize=(width / 100, height / 100), dpi=100)
    canvas = FigureCanvasAgg(fig)
    fig.figimage(to_srgb8(sheet), 0, 0, origin="upper", resize=False)
    for x, y, text, size, align in texts:
        fig.text(x / width, 1 - y / height, text, fontsize=size, ha=align, va="top", color="#202020")
    canvas.draw()
    pixels = np.asarray(canvas.buffer_rgba())[:height, :width, :3]
    return srgb_to_linear(pixels / 255.0)


def _picture(scene, args) -> np.ndarray:
    """The still picture ``args.what`` of ``scene`` (linear RGB)."""
    if args.what == "image":
        return render(scene, args)
    if args.what == "zbuffer":
        return _zbuffer_sheet(scene)
    if args.what == "four-views":
        return _four_views(scene, args)
    return _comparison(scene, args)


def _zbuffer_sheet(scene) -> np.ndarray:
    from core.object_order.pipeline import render_raster

    cam = scene.camera
    result = render_raster(scene)
    seen = result.depth[np.isfinite(result.depth)]
    span = (f"the surfaces seen lie between {seen.min():.3g} and {seen.max():.3g}" if seen.size
            else "no surface is seen")
    ramp = depth_grey(np.linspace(cam.near, cam.far, cam.width)[None].repeat(10, 0), cam.near, cam.far)
    panel = Panel("z-buffer", depth_grey(result.depth, cam.near, cam.far), ramp,
                  (f"near {cam.near:g}", f"far {cam.far:g}"))
    return compose([panel], 1, [f"Grey: distance along the viewing axis in scene units, from the near "
                                f"plane (black) to the far plane (white); {span}."])


def _four_views(scene, args) -> np.ndarray:
    from core.object_order.three_views import orthographic_views

    cam = scene.camera
    views = orthographic_views(scene, cam.width, cam.height)
    panels = [Panel(f"{name} view (orthographic)", render(replace(scene, camera=camera), args))
              for name, camera in views.items()]
    panels.append(Panel(f"observer's view ({cam.projection})", render(scene, args)))
    return compose(panels, 2, [f"Pipeline: {args.mode}."])


def _comparison(scene, args) -> np.ndarray:
    from core.compare import compare

    a, b = _pair(args)
    result = compare(scene, a, b, _trace_settings(args, "raytrace"))
    diff = result.difference
    panels = [Panel(result.a.title, result.a.color), Panel(result.b.title, result.b.color),
              Panel("difference |A - B| (linear RGB)", diff.colored,
                    diff.colorbar(diff.colored.shape[1], 10), ("0", f"{diff.scale:.3g}"))]
    return compose(panels, 3, list(result.explanation))


# --- animations ---------------------------------------------------------------------------------------


def _progress(total: int, what: str):
    from tqdm import tqdm

    return tqdm(total=total, desc=f"python -m app export: {what}", unit="frame", file=sys.stderr,
                leave=False)


def _tinted(image: np.ndarray, cols, rows, color) -> None:
    image[rows, cols] = 0.5 * image[rows, cols] + 0.5 * np.asarray(color)


def _steps_frames(scene):
    """One frame per step of the z-buffer algorithm: image memory and z-buffer after 0, 1, ... polygons."""
    from core.object_order import zbuffer
    from core.object_order.pipeline import RasterSettings, render_raster

    cam = scene.camera
    result = render_raster(scene, RasterSettings(record_steps=True))
    history = result.history
    n = history.n_steps
    if n + 1 > MAX_FRAMES:
        raise UsageError(f"--what zbuffer-steps: the scene draws {n:,} polygons, more than the "
                         f"{MAX_FRAMES - 1:,} an animation may show; use a scene with fewer polygons")
    names = [o.name for o in scene.objects]
    ortho = cam.projection == "orthographic"
    ramp = depth_grey(np.linspace(cam.near, cam.far, cam.width)[None].repeat(8, 0), cam.near, cam.far)
    with _progress(n + 1, "zbuffer-steps") as bar:
        for k in range(n + 1):
            color, zbuf = history.buffers(k)
            distance = zbuffer.distance_from_window_depth(zbuf, cam.near, cam.far, ortho)
            depth = depth_grey(np.where(zbuf < zbuffer.FAR_DEPTH, distance, np.inf), cam.near, cam.far)
            if k == 0:
                text = ("cleared buffers: image memory holds the background, the z-buffer the far plane")
            else:
                p = k - 1
                cols, rows, _, passed = history.polygon_fragments(p)
                for image in (color, depth):
                    _tinted(image, cols[passed], rows[passed], PASSED_TINT)
                    _tinted(image, cols[~passed], rows[~passed], FAILED_TINT)
                text = (f"polygon {p} of {names[history.object_index[p]]} (triangle "
                        f"{history.triangle_index[p]}): {int(passed.sum()):,} fragments passed the "
                        f"z-test (magenta), {int((~passed).sum()):,} failed (cyan)")
            panels = [Panel("image memory", color),
                      Panel("z-buffer", depth, ramp, (f"near {cam.near:g}", f"far {cam.far:g}"))]
            yield compose(panels, 2, [f"frame {k} / {n}, step {k}: {text}"], lines=4)
            bar.update(1)


def _orbit_frames(scene, args):
    """The observer walks once around the target; each frame the pipeline's image."""
    cam = scene.camera
    with _progress(args.frames, "orbit") as bar:
        for i in range(args.frames):
            moved = cam.orbit(cam.yaw_deg + 360.0 * i / args.frames, cam.pitch_deg)
            yield render(replace(scene, camera=moved), args)
            bar.update(1)


def encode_animation(frames, extension: str, fps: int, limit: int) -> bytes:
    """The bytes of a GIF or MP4 of ``frames`` (each (H, W, 3) linear RGB, written as sRGB).

    The file is encoded in a private temporary folder and returned as bytes,
    so the caller writes it into place atomically.  Refuses (``UsageError``)
    frames whose pixels alone would exceed ``limit`` bytes.
    """
    import imageio.v2 as iio2

    from core import budget
    from core.srgb import to_srgb8

    with tempfile.TemporaryDirectory(prefix="render-explorer-export-") as folder:
        path = os.path.join(folder, "animation" + extension)
        if extension == ".gif":
            pixels, held = [], 0
            for frame in frames:
                pixels.append(to_srgb8(frame))
                held += pixels[-1].nbytes
                if held > limit:
                    raise UsageError(f"the GIF's frames need more than {budget.format_bytes(limit)}; "
                                     "use a smaller image (--width/--height), fewer frames, or MP4")
            import imageio.v3 as iio

            iio.imwrite(path, pixels, extension=".gif", duration=1000 / fps, loop=0)
        else:
            with iio2.get_writer(path, format="FFMPEG", fps=fps, macro_block_size=2,
                                 ffmpeg_log_level="error") as writer:
                for frame in frames:
                    pixels = to_srgb8(frame)
                    h, w = pixels.shape[:2]
                    writer.append_data(np.pad(pixels, ((0, h % 2), (0, w % 2), (0, 0)), mode="edge"))
        with open(path, "rb") as f:
            return f.read()
