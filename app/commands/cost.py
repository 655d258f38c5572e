"""``python -m app cost``: what accuracy costs in time, swept knob by knob against a reference.

Renders each setting of one knob (or of every knob) with everything else at
its default, times it (median of the runs after a warm-up), measures its
error against the reference, and writes ``DIR/cost.csv`` (one row per
setting, ``knee`` = 1 on each knob's knee), ``DIR/cost.png`` and
``DIR/cost.svg`` (error against time, log-log), and prints a short table.

The image is small by default (at most 160 pixels wide, the scene's aspect
kept), so that ``--knob all`` on the lecture scene takes a few minutes on a
two-core machine; the reference uses 16 x 16 samples per pixel unless
``--reference-spp`` asks for fewer.  Imports neither Qt nor VTK unless the
scene names a mesh file.
"""

from __future__ import annotations

import sys
from dataclasses import replace
from pathlib import Path

from app.usage import UsageError

KNOB_CHOICES = ("spp", "adaptive", "depth", "min-weight", "resolution", "tessellation", "accel",
                "depth-format", "all")
MODES = ("raycast", "raytrace", "raster")
DEFAULT_WIDTH = 160


def add_parser(sub) -> None:
    p = sub.add_parser("cost", help="sweep accuracy knobs against a reference: error vs time, CSV and plot",
                       description=__doc__.split("\n\n")[0])
    p.add_argument("scene", help="scene JSON file")
    p.add_argument("--knob", choices=KNOB_CHOICES, default="all", help="the knob to sweep (default all)")
    p.add_argument("--mode", choices=MODES, default="raytrace",
                   help="pipeline for knobs both have (spp, resolution); default raytrace")
    p.add_argument("--tolerance", type=float, default=0.01,
                   help="knee: the cheapest setting within this FLIP of the best (default 0.01)")
    p.add_argument("--width", type=int, help=f"image width (default: the scene's, at most {DEFAULT_WIDTH})")
    p.add_argument("--height", type=int, help="image height (default: the scene's aspect kept)")
    p.add_argument("--reference-spp", type=int, default=16,
                   help="samples per axis per pixel of the reference (default 16)")
    p.add_argument("--runs", type=int, default=3, help="timed renders per setting, after a warm-up (>= 3)")
    p.add_argument("--seed", type=int, default=0, help="seed of the sample patterns")
    p.add_argument("--budget", type=float,
                   help="equal time: also print each knob's most accurate setting within this many seconds")
    p.add_argument("--out", required=True, help="folder for cost.csv, cost.png and cost.svg")
    p.add_argument("--dry-run", action="store_true",
                   help="print the sweep's estimated memory and time, and stop before rendering")
    p.add_argument("--memory-limit", metavar="SIZE",
                   help="refuse a sweep estimated to need more memory, e.g. 8G or 512M "
                        "(default: half of the memory available)")
    p.set_defaults(run=run)


def _check(args) -> None:
    if not args.tolerance >= 0:  # also rejects nan
        raise UsageError(f"--tolerance: must be a number >= 0, got {args.tolerance}")
    for key in ("width", "height"):
        value = getattr(args, key)
        if value is not None and not 1 <= value <= 4096:
            raise UsageError(f"--{key}: must be a whole number of pixels in [1, 4096], got {value}")
    if args.budget is not None and not args.budget > 0:
        raise UsageError(f"--budget: must be a number of seconds > 0, got {args.budget}")
    if not 1 <= args.reference_spp <= 32:
        raise UsageError(f"--reference-spp: must be in [1, 32], got {args.reference_spp}")
    if not 3 <= args.runs <= 100:
        raise UsageError(f"--runs: must be in [3, 100], got {args.runs}")
    out = Path(args.out)
    if out.exists() and not out.is_dir():
        raise UsageError(f"--out: {out} exists and is not a folder")


def _size(camera, width, height) -> tuple[int, int]:
    if width is None and height is None:
        width = min(camera.width, DEFAULT_WIDTH)
    if width is None:
        width = max(1, round(height * camera.width / camera.height))
    if height is None:
        height = max(1, round(width * camera.height / camera.width))
    return width, height


def _table(rows, skipped) -> str:
    from core.accuracy.sweep import KNOBS

    v = max([9] + [len(r.value) for r in rows])
    lines = [f"{'knob':<13}{'value':>{v}}  {'mode':<9}{'seconds':>9}{'rmse':>9}{'flip':>8}{'x best':>8}"
             f"{'wrong':>8}  knee"]
    for r in rows:
        times = "" if r.flip_vs_best is None else f"{r.flip_vs_best:.2f}"
        lines.append(f"{r.knob:<13}{r.value:>{v}}  {r.mode:<9}{r.seconds:>9.4f}{r.rmse:>9.4f}{r.flip:>8.4f}"
                     f"{times:>8}{r.wrong_pixel_fraction:>8.4f}  {'<-- knee' if r.knee else ''}")
    for knob, reason in skipped.items():
        lines.append(f"{knob}: not swept: {reason}")
    if any(r.knob == "depth-format" for r in rows):
        lines.append("depth-format: each format compared with float64 at the same near/far ratio; "
                     "'wrong' is z-fighting")
    for knob in sorted({r.knob for r in rows if KNOBS[r.knob].time_only}):
        lines.append(f"{knob}: compared with '{next(r for r in rows if r.knob == knob).compared_with}': "
                     "changes time only")
    return "\n".join(lines)


def _check_cost(job, args) -> bool:
    """Refuse a sweep over the memory budget, announce a slow one; True when it should run."""
    from app.commands.render import budget_limit
    from core import budget
    from core.accuracy import sweep_cost

    cost = sweep_cost.estimate(job)
    cam = job.scene.camera
    what = f"a sweep of {len(job.settings)} settings at {cam.width} × {cam.height}"
    over = budget.refusal(what, cost, *budget_limit(args))
    if over:
        raise UsageError(f"{over}; use a smaller image (--width/--height), one --knob, a lower "
                         "--reference-spp, or --memory-limit")
    said = (f"{what}: about {budget.format_bytes(cost.bytes)} of memory and "
            f"{budget.format_seconds(cost.seconds)}")
    if args.dry_run:
        print(f"{said}; nothing rendered (--dry-run)")
    elif cost.seconds > budget.SLOW_SECONDS:
        print(f"python -m app cost: estimated {said}", file=sys.stderr, flush=True)
    return not args.dry_run


def run(args) -> int:
    _check(args)
    from app.commands.render import parse_memory_limit

    parse_memory_limit(args.memory_limit)
    from core.files import scene_file
    from core.files.mesh_files import read_mesh

    try:
        scene = scene_file.load(args.scene, read_mesh=read_mesh)
    except scene_file.SceneFileError as exc:
        where = f"scene file {exc.where}" if exc.where else "scene"
        raise UsageError(f"{where}: {'; '.join(exc.problems)}") from None
    width, height = _size(scene.camera, args.width, args.height)
    scene = replace(scene, camera=scene.camera.replace(width=width, height=height))

    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from tqdm import tqdm

    from core.accuracy import sweep
    from views.images import cost_files
    from views.images.cost_plot import draw_cost_plot, tidy_cost_plot

    knobs = sweep.KNOB_NAMES if args.knob == "all" else (args.knob,)
    job = sweep.Sweep(scene, knobs, args.mode, args.tolerance, args.runs, args.reference_spp, args.seed)
    if not job.settings:
        reasons = "; ".join(f"{k}: {why}" for k, why in job.skipped.items())
        raise UsageError(f"--knob {args.knob}: nothing to sweep on this scene ({reasons})")
    if not _check_cost(job, args):
        return 0
    out = Path(args.out)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise UsageError(f"--out: cannot create the folder {out}: {exc.strerror or exc}") from None
    with tqdm(total=1.0, file=sys.stderr, unit="render", dynamic_ncols=True,
              bar_format="{l_bar}{bar}| {elapsed} {postfix}") as bar:
        for event in job.events():
            if isinstance(event, sweep.Progress):
                bar.total = event.total
                bar.n = event.done
                bar.set_description(event.what[:40], refresh=False)
                bar.refresh()
    rows = job.rows()
    figure = Figure(figsize=(9, 6), layout="constrained")
    FigureCanvasAgg(figure)
    draw_cost_plot(figure, rows)
    figure.canvas.draw()
    tidy_cost_plot(figure)  # the legend under the axis label: laid out again, then the labels thinned
    figure.canvas.draw()
    figure.set_layout_engine("none")
    tidy_cost_plot(figure)
    from core.files.safe_files import OutputError, write_atomic_all

    try:
        write_atomic_all({out / "cost.csv": cost_files.csv_text(rows).encode("utf-8"),
                          out / "cost.png": cost_files.figure_bytes(figure, ".png"),
                          out / "cost.svg": cost_files.figure_bytes(figure, ".svg")})
    except OutputError as exc:
        print(f"python -m app cost: error: {exc}", file=sys.stderr)
        return 1
    print(_table(rows, job.skipped))
    if args.budget is not None:
        best = sweep.best_within(rows, args.budget)
        print(f"equal time, at most {args.budget:g} s: " + (", ".join(
            f"{k} {r.value} (FLIP {r.reference_flip:.4f}, {r.seconds:.3f} s)" for k, r in best.items())
            or "no setting is that fast"))
    spp = args.reference_spp
    print(f"{len(rows)} settings, {width}x{height} pixels, reference {spp}x{spp} per pixel"
          f" -> {out / 'cost.csv'}, cost.png, cost.svg")
    return 0
