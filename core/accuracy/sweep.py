"""What accuracy costs in time: sweep one knob at a time against the reference.

A *knob* is one accuracy setting of a pipeline.  A sweep renders each of its
values with everything else at its default, and for each one measures

- time: the median of ``runs`` (>= 3) renders after one warm-up render; the
  kernels are compiled before, so compiling is never counted;
- error against the reference (:mod:`core.accuracy.reference`): RMSE of
  linear RGB, mean FLIP, the fraction of pixels whose visible object differs,
  and the depth error (:mod:`core.accuracy.error_metrics`);
- memory, where the knob changes the size of a buffer: the z-buffer for the
  depth format, the colour and depth buffers for the resolution, the
  triangles for the tessellation.

The *knee* of a knob is its cheapest value whose FLIP is within the tolerance
of the best value's: past it you pay for what nobody sees.  The tolerance is
an absolute FLIP distance, so each row also reports its FLIP as a multiple of
the best (``flip_vs_best``): on a small image every error is small, and a knee
within 0.01 may still have several times the best error.  Acceleration
methods are compared with ``"none"`` instead of the reference: they must find
exactly the same hits, so their error is exactly 0 and they change time only.

The z-buffer's number format has a second axis, the far/near ratio of the
frustum (:data:`DEPTH_RATIOS`, the near plane moved, the far plane kept): each
format at each ratio is compared with float64 at the same ratio, so its
wrong-visible-object fraction is z-fighting and nothing else.  Its values are
written ``int16@1:1000``; what it saves is memory, not time, so its knee is
the format with the fewest bytes per pixel whose FLIP stays within the
tolerance at every ratio tried.

A sweep is a generator of events (:meth:`Sweep.events`): it yields after every
render, so a caller running it in the background can stop between renders,
and calling :meth:`Sweep.events` again resumes with the first setting not yet
done (finished references are kept).
"""

from __future__ import annotations

import statistics
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, fields, replace

import numpy as np

from core.accuracy import error_metrics, reference, resolution, supersampling, tessellation
from core.accuracy.visible_surface import VisibleSurface, rasterized_surface, traced_surface
from core.image_order.flat_layout import ACCEL_CODES
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tracing import ensure_compiled as compile_tracer
from core.image_order.ray_tracing import render_trace, sample_tracer
from core.object_order.depth_formats import BYTES_PER_PIXEL, DEPTH_FORMATS
from core.object_order.pipeline import SPHERE_RINGS, SPHERE_SEGMENTS, RasterSettings, render_raster
from core.object_order.pipeline import ensure_compiled as compile_raster
from core.scene import Scene

#: The FLIP distance from the best value within which a value counts as "as good".
DEFAULT_TOLERANCE = 0.01
#: Samples per axis in a pixel that adaptive supersampling refines.
ADAPTIVE_N = 4
TRACE_MODES = ("raytrace", "raycast")
#: Far/near ratios the depth formats are tried at (``1:1000`` is near = far / 1000).
DEPTH_RATIOS = (10, 100, 1000, 10000)


@dataclass(frozen=True)
class Knob:
    """One accuracy setting and the values a sweep tries.

    Attributes
    ----------
    name : the name the command line and the CSV use.
    title : what the knob is, for a legend.
    modes : the pipelines it belongs to; the first is used when the sweep's
        own mode is not one of them.
    values : the values tried, from the cheapest to the dearest.
    default : the pipeline's default value.
    time_only : the knob cannot change the image (compared with its first value).
    """

    name: str
    title: str
    modes: tuple[str, ...]
    values: tuple
    default: object
    time_only: bool = False

    def label(self, value) -> str:
        """A value as the CSV and the plot write it."""
        if self.name == "spp":
            return f"{value}x{value}"
        if self.name == "tessellation":
            return f"{value[0]}x{value[1]}"
        if self.name == "depth-format":
            return f"{value[0]}@1:{value[1]}"
        return str(value)

    def mode_for(self, mode: str) -> str:
        """The pipeline this knob is swept in when the sweep asks for ``mode``."""
        return mode if mode in self.modes else self.modes[0]


KNOBS: dict[str, Knob] = {k.name: k for k in (
    Knob("spp", "supersampling, N x N per pixel", ("raytrace", "raycast", "raster"), (1, 2, 4, 8), 1),
    Knob("adaptive", f"adaptive supersampling (threshold; {ADAPTIVE_N}x{ADAPTIVE_N} where refined)",
         TRACE_MODES, (0.4, 0.2, 0.1, 0.05, 0.02), None),
    Knob("depth", "ray depth", ("raytrace",), (0, 1, 2, 3, 5, 10), 5),
    Knob("min-weight", "minimum ray weight", ("raytrace",), (0.3, 0.1, 0.03, 0.01, 0.001, 0.0), 0.01),
    Knob("resolution", "image resolution (scale)", ("raytrace", "raycast", "raster"), (0.25, 0.5, 1.0, 2.0),
         1.0),
    Knob("tessellation", "sphere tessellation (rings x segments)", ("raster",),
         ((4, 8), (8, 16), (16, 32), (32, 64), (64, 128)), (SPHERE_RINGS, SPHERE_SEGMENTS)),
    Knob("accel", "acceleration method", TRACE_MODES, ACCEL_CODES, "bvh", time_only=True),
    Knob("depth-format", "z-buffer number format @ near/far ratio", ("raster",),
         tuple((f, r) for f in DEPTH_FORMATS for r in DEPTH_RATIOS), "float64"),
)}
KNOB_NAMES = tuple(KNOBS)


def split_depth_label(text: str) -> tuple[str, int]:
    """A depth-format value as written (``"int16@1:1000"``) -> (format, far/near ratio).

    Examples
    --------
    >>> split_depth_label("float32-reversed@1:100")
    ('float32-reversed', 100)
    """
    name, ratio = text.split("@1:")
    return name, int(ratio)


def unavailable(name: str, scene: Scene) -> str | None:
    """Why knob ``name`` cannot be swept on ``scene``, or ``None`` when it can."""
    if name not in KNOBS:
        raise ValueError(f"knob must be one of {list(KNOB_NAMES)}, got {name!r}")
    if name == "tessellation" and not tessellation.has_spheres(scene):
        return "the scene has no analytic spheres to tessellate"
    return None


@dataclass(frozen=True)
class Setting:
    """One value of one knob, everything else at its default."""

    knob: str
    value: object
    mode: str

    @property
    def label(self) -> str:
        return KNOBS[self.knob].label(self.value)


@dataclass(frozen=True)
class Row:
    """What one setting cost and what it bought: a line of ``cost.csv``.

    Attributes
    ----------
    knob, value, mode : the setting (``value`` as text).
    seconds : median render time (s).
    rmse, flip, wrong_pixel_fraction, depth_error : error against ``compared_with``
        (``"reference"``, or ``"none"`` for acceleration methods); depth error in scene units.
    reference_flip : FLIP against the reference (the plot's error axis).
    samples_per_pixel : rays (or raster passes) per pixel.
    bytes : size of the buffers this knob changes, ``None`` where it changes none.
    knee : this is the knob's knee.
    flip_vs_best : ``flip`` divided by the knob's lowest ``flip`` (1 on the best row), once the
        knob is finished; ``None`` before, or when the best is exactly 0.
    """

    knob: str
    value: str
    mode: str
    seconds: float
    rmse: float
    flip: float
    wrong_pixel_fraction: float
    depth_error: float
    reference_flip: float
    samples_per_pixel: float
    bytes: int | None
    compared_with: str
    knee: bool = False
    flip_vs_best: float | None = None


CSV_COLUMNS = tuple(f.name for f in fields(Row))


@dataclass(frozen=True, eq=False)
class Point:
    """A finished setting: its row and its images (event of :meth:`Sweep.events`).

    Attributes
    ----------
    index : position of the setting in :attr:`Sweep.settings`.
    row : Row.
    color : (H, W, 3) float64, linear RGB at the reference's size.
    error_map : (H, W) float32, FLIP per pixel against ``compared_with``.
    samples : (H, W) int64, samples per pixel (adaptive supersampling), else ``None``.
    """

    index: int
    row: Row
    color: np.ndarray
    error_map: np.ndarray
    samples: np.ndarray | None


@dataclass(frozen=True)
class Progress:
    """Work done so far (event of :meth:`Sweep.events`), in renders; ``what`` names the current one."""

    done: float
    total: float
    what: str


@dataclass(frozen=True)
class Knee:
    """A knob is finished and its knee found (event of :meth:`Sweep.events`)."""

    knob: str
    index: int


@dataclass(frozen=True, eq=False)
class _Job:
    """One setting made ready: ``render()`` is timed, ``visible()`` is not."""

    render: Callable[[], tuple[np.ndarray, np.ndarray | None, float]]
    visible: Callable[[], VisibleSurface]
    bytes: int | None = None


def knee_index(rows: list[Row], tolerance: float = DEFAULT_TOLERANCE, by_time: bool = False) -> int:
    """Index of the cheapest row whose FLIP is within ``tolerance`` of the best row's.

    Cheapest is the first in the knob's own order (its values go from the
    cheapest to the dearest: fewer samples, fewer bounces, fewer pixels), not
    the measured time: a render of a few milliseconds on a shared machine can
    time a dearer setting faster than a cheaper one, and the knee must not
    follow that noise.  With ``by_time`` (acceleration methods, whose order is
    no order of cost) it is the shortest median time.  The depth formats (all
    rows of knob ``depth-format``) save memory, so there it is the format with the
    fewest bytes whose worst FLIP over the ratios is within ``tolerance`` of
    the best format's worst (ties: lower worst FLIP, then time), and the index
    is that format's row at the largest ratio.

    Examples
    --------
    >>> r = [Row("k", str(i), "raster", s, 0, f, 0, 0, f, 1, None, "reference")
    ...      for i, (s, f) in enumerate([(1, 0.2), (2, 0.05), (4, 0.045), (8, 0.04)])]
    >>> knee_index(r)
    1
    """
    if rows[0].knob == "depth-format":
        return _depth_format_knee(rows, tolerance)
    best = min(r.flip for r in rows)
    good = [i for i, r in enumerate(rows) if r.flip <= best + tolerance]
    return min(good, key=lambda i: rows[i].seconds) if by_time else good[0]


def _depth_format_knee(rows: list[Row], tolerance: float) -> int:
    by_format: dict[str, list[int]] = {}
    for i, r in enumerate(rows):
        by_format.setdefault(split_depth_label(r.value)[0], []).append(i)
    worst = {f: max(rows[i].flip for i in idx) for f, idx in by_format.items()}
    best = min(worst.values())
    good = [f for f in by_format if worst[f] <= best + tolerance]
    chosen = min(good, key=lambda f: (BYTES_PER_PIXEL[f], worst[f],
                                      sum(rows[i].seconds for i in by_format[f])))
    return max(by_format[chosen], key=lambda i: split_depth_label(rows[i].value)[1])


def marked_rows(points: dict[int, Point], knees: dict[str, int]) -> list[Row]:
    """The rows of ``points`` in setting order, knees marked and ``flip_vs_best`` filled in.

    Parameters
    ----------
    points : setting index -> Point.
    knees : knob name -> setting index of its knee (the finished knobs).
    """
    knee_at = set(knees.values())
    best: dict[str, float] = {}
    for p in points.values():
        if p.row.knob in knees:
            best[p.row.knob] = min(best.get(p.row.knob, np.inf), p.row.flip)
    rows = []
    for i, p in sorted(points.items()):
        lowest = best.get(p.row.knob, 0.0)
        ratio = p.row.flip / lowest if lowest > 0 else None
        rows.append(replace(p.row, knee=i in knee_at, flip_vs_best=ratio))
    return rows


def best_within(rows: list[Row], budget: float) -> dict[str, Row]:
    """Equal time: per knob, its most accurate row (lowest FLIP, then fastest) within ``budget`` seconds."""
    best: dict[str, Row] = {}
    for r in rows:
        if r.seconds <= budget and (r.knob not in best or (r.reference_flip, r.seconds)
                                    < (best[r.knob].reference_flip, best[r.knob].seconds)):
            best[r.knob] = r
    return best


class Sweep:
    """Sweeps of several knobs of one scene, resumable.

    Parameters
    ----------
    scene : the scene, with its camera at the size to compare at.
    knobs : knob names, or ``("all",)``.
    mode : ``"raytrace"``, ``"raycast"`` or ``"raster"``: the pipeline for
        knobs that belong to several (a knob of one pipeline only uses that one).
    tolerance : FLIP distance for the knee.
    runs : timed renders per setting (>= 3), after one warm-up render.
    reference_spp : samples per axis of the reference.
    seed : seed of every random sample pattern.

    Attributes
    ----------
    settings : list of Setting, in the order they are rendered.
    skipped : dict, knob name -> why it is not swept.
    points : dict, setting index -> Point, the settings done so far.
    references : dict, mode -> Reference, those rendered so far.
    """

    def __init__(self, scene: Scene, knobs=("all",), mode: str = "raytrace",
                 tolerance: float = DEFAULT_TOLERANCE, runs: int = 3,
                 reference_spp: int = reference.REFERENCE_SPP, seed: int = 0):
        if mode not in reference.MODES:
            raise ValueError(f"mode must be one of {list(reference.MODES)}, got {mode!r}")
        if not (isinstance(runs, int) and runs >= 3):
            raise ValueError(f"runs must be a whole number >= 3, got {runs!r}")
        if not tolerance >= 0:
            raise ValueError(f"tolerance must be >= 0, got {tolerance!r}")
        names = KNOB_NAMES if "all" in knobs else tuple(knobs)
        self.scene, self.mode, self.tolerance, self.runs = scene, mode, tolerance, runs
        self.reference_spp, self.seed = reference_spp, seed
        self.skipped: dict[str, str] = {}
        self.settings: list[Setting] = []
        for name in names:
            reason = unavailable(name, scene)
            if reason:
                self.skipped[name] = reason
                continue
            knob = KNOBS[name]
            self.settings += [Setting(name, v, knob.mode_for(mode)) for v in knob.values]
        self.points: dict[int, Point] = {}
        self.references: dict[str, reference.Reference] = {}
        self._knees: dict[str, int] = {}
        self._visible: dict[int, VisibleSurface] = {}

    # -- what has been found ------------------------------------------------

    @property
    def finished(self) -> bool:
        return len(self.points) == len(self.settings)

    def rows(self) -> list[Row]:
        """The rows done so far, in setting order, with the knees marked."""
        return marked_rows(self.points, self._knees)

    def knee_indices(self) -> dict[str, int]:
        """Knob name -> setting index of its knee, for the knobs finished so far."""
        return dict(self._knees)

    def _units(self) -> float:
        """Total work in renders: each setting warm-up + runs (+1 for its visible surface); references 10."""
        modes = {s.mode for s in self.settings}
        return len(self.settings) * (self.runs + 2) + 10 * len(modes)

    # -- the work -------------------------------------------------------------

    def events(self) -> Iterator[Progress | Point | Knee]:
        """Run the settings not done yet, yielding after every render (see the module docstring)."""
        total = self._units()
        done = float(10 * len(self.references) + len(self.points) * (self.runs + 2))
        compile_tracer()
        compile_raster()
        for index, setting in enumerate(self.settings):
            if index in self.points:
                continue
            if setting.mode not in self.references:
                yield Progress(done, total, f"reference ({setting.mode}, {self.reference_spp}x"
                                            f"{self.reference_spp} per pixel)")
                steps = reference.reference_steps(self.scene, setting.mode, self.reference_spp, self.seed)
                start = done
                while True:
                    try:
                        fraction = next(steps)
                    except StopIteration as end:
                        self.references[setting.mode] = end.value
                        break
                    done = start + 10 * fraction
                    yield Progress(done, total, f"reference ({setting.mode})")
                done = start + 10
            job = self._job(setting)
            what = f"{setting.knob} = {setting.label} ({setting.mode})"
            times = []
            for run in range(self.runs + 1):  # run 0 is the warm-up
                start_s = time.perf_counter()
                color, samples, spp = job.render()
                if run:
                    times.append(time.perf_counter() - start_s)
                done += 1
                yield Progress(done, total, what)
            visible = job.visible()
            done += 1
            point = self._point(index, setting, statistics.median(times), color, samples, spp, visible,
                                job.bytes)
            self.points[index] = point
            yield point
            yield Progress(done, total, what)
            knob_indices = [i for i, s in enumerate(self.settings) if s.knob == setting.knob]
            if all(i in self.points for i in knob_indices):
                rows = [self.points[i].row for i in knob_indices]
                self._knees[setting.knob] = knob_indices[knee_index(rows, self.tolerance,
                                                                        KNOBS[setting.knob].time_only)]
                yield Knee(setting.knob, self._knees[setting.knob])

    def run(self) -> list[Row]:
        """Run every setting not done yet, synchronously; return the rows."""
        for _ in self.events():
            pass
        return self.rows()

    def _point(self, index, setting, seconds, color, samples, spp, visible, nbytes) -> Point:
        ref = self.references[setting.mode]
        ref_flip, ref_map = error_metrics.flip(ref.color, color)
        baseline = self._baseline(index)
        if baseline is not None:
            base = self.points.get(baseline)
            base_color = color if base is None else base.color
            base_visible = visible if base is None else self._visible[baseline]
            compared_with = self.settings[baseline].label
        else:
            base_color, compared_with = ref.color, "reference"
            base_visible = ref.exact if setting.knob == "tessellation" else ref.visible
        flip_value, error_map = (ref_flip, ref_map) if compared_with == "reference" else \
            error_metrics.flip(base_color, color)
        self._visible[index] = visible
        row = Row(setting.knob, setting.label, setting.mode, seconds,
                  error_metrics.rmse(base_color, color), flip_value,
                  error_metrics.wrong_pixel_fraction(base_visible.object_index, visible.object_index),
                  error_metrics.depth_error(base_visible.depth, visible.depth, base_visible.object_index,
                                            visible.object_index),
                  ref_flip, float(spp), nbytes, compared_with)
        return Point(index, row, color, error_map, samples)

    def _baseline(self, index: int) -> int | None:
        """The setting that ``index`` is compared with instead of the reference, if any.

        Acceleration methods: the first method (``none``).  Depth formats:
        float64 at the same far/near ratio.  Other knobs: ``None``.
        """
        setting = self.settings[index]
        if KNOBS[setting.knob].time_only:
            return next(i for i, s in enumerate(self.settings) if s.knob == setting.knob)
        if setting.knob == "depth-format":
            same = ("float64", setting.value[1])
            return next(i for i, s in enumerate(self.settings) if s.knob == setting.knob and s.value == same)
        return None

    def _job(self, setting: Setting) -> _Job:
        """The timed render and the visible surface of one setting."""
        scene, mode, value, seed = self.scene, setting.mode, setting.value, self.seed
        cam = scene.camera
        tracer = mode in TRACE_MODES
        trace_default = TraceSettings(mode=mode) if tracer else None
        if setting.knob == "spp":
            if tracer:
                trace = sample_tracer(scene, trace_default)
                return _Job(lambda: (supersampling.trace_supersampled(
                    scene, trace_default, value, np.random.default_rng(seed), trace), None, value * value),
                    lambda: traced_surface(scene, trace_default))
            return _Job(lambda: (supersampling.raster_supersampled(
                scene, RasterSettings(), value, np.random.default_rng(seed)), None, value * value),
                lambda: rasterized_surface(scene))
        if setting.knob == "adaptive":
            trace = sample_tracer(scene, trace_default)

            def adaptive():
                image = supersampling.trace_adaptive(scene, trace_default, value, ADAPTIVE_N,
                                                     np.random.default_rng(seed), trace)
                return image.color, image.samples, image.samples_per_pixel

            return _Job(adaptive, lambda: traced_surface(scene, trace_default))
        if setting.knob in ("depth", "min-weight", "accel"):
            field = {"depth": "max_depth", "min-weight": "min_weight", "accel": "accel"}[setting.knob]
            settings = replace(trace_default, **{field: value})
            return _Job(lambda: (render_trace(scene, settings).color, None, 1.0),
                        lambda: traced_surface(scene, settings))
        if setting.knob == "resolution":
            w, h = resolution.scaled_size(cam.width, cam.height, value)
            small = replace(scene, camera=cam.replace(width=w, height=h))
            nbytes = w * h * (3 * 8 + 8)  # colour (3 float64) and depth (float64) per pixel
            spp = w * h / (cam.width * cam.height)

            def render():
                image = render_trace(small, trace_default).color if tracer else render_raster(small).color
                return resolution.to_size(image, cam.width, cam.height), None, spp

            def visible():
                v = traced_surface(small, trace_default) if tracer else rasterized_surface(small)
                return VisibleSurface(resolution.to_size(v.object_index, cam.width, cam.height),
                                      resolution.to_size(v.depth, cam.width, cam.height))

            return _Job(render, visible, nbytes)
        if setting.knob == "tessellation":
            rings, segments = value
            nbytes = tessellation.mesh_bytes(tessellation.tessellated(scene, rings, segments)) \
                - tessellation.mesh_bytes(scene)
            return _Job(lambda: (render_raster(tessellation.tessellated(scene, rings, segments)).color, None,
                                 1.0),
                        lambda: rasterized_surface(tessellation.tessellated(scene, rings, segments)), nbytes)
        # depth-format: a number format at a far/near ratio, the near plane moved
        name, ratio = value
        moved = replace(scene, camera=cam.replace(near=cam.far / ratio))
        settings = RasterSettings(depth_format=name)
        return _Job(lambda: (render_raster(moved, settings).color, None, 1.0),
                    lambda: rasterized_surface(moved, settings),
                    cam.width * cam.height * BYTES_PER_PIXEL[name])
