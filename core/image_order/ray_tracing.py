"""Ray casting and Whitted ray tracing in image order: render a scene, count every ray.

The lecture's image order: for each pixel a *primary ray* from the eye (or,
in parallel projection, from the screen plane) through the pixel
(:mod:`core.image_order.ray_casting`); its first hit gives the pixel its colour.

- **Ray casting** (``mode="raycast"``): from the hit point one *shadow ray*
  towards each point light; a light contributes (Lambert + Phong,
  :mod:`core.image_order.shading`) only if its shadow ray reaches it unblocked.
- **Ray tracing** (``mode="raytrace"``, Whitted): in addition, at a reflective
  surface a *reflected ray* (angle of reflection = angle of incidence), at a
  transparent surface a *refracted ray* (Snell's law), the light split
  between them by the Fresnel equations, and total internal reflection when
  Snell's law has no solution (:mod:`core.image_order.optics`).  The rays form a tree per
  pixel; its colour is combined from the last hits back to the first
  (:mod:`core.image_order.ray_tree` shows one tree number by number).

A ray is not traced when it would be deeper than ``max_depth`` generations
(the primary ray is generation 0), or when its weight in the pixel (the
product of the coefficients along its path) falls below ``min_weight``
(default 0.01: a ray that could change the pixel by less than 1% of full
brightness is dropped).

Primary rays see only what lies between the near and the far plane, as the
object-order pipeline does after clipping; ``depth`` is therefore comparable
with the depth buffer.

Acceleration (``accel``): ``"none"`` tests every primitive; ``"spheres"``
puts bounding spheres around meshes; ``"grid"`` walks a uniform grid;
``"grid+spheres"`` combines both, as the lecture suggests; ``"bvh"`` uses a
bounding volume hierarchy.  All find exactly the same hits; only the work
differs, and the statistics count it.
"""

from __future__ import annotations

import dataclasses
import functools
import threading
import time
from dataclasses import dataclass

import numpy as np

from core import stopping
from core.compiling.warm_up import WarmUp
from core.image_order import flat_layout
from core.image_order.bvh import Bvh
from core.image_order.effects_plan import EffectsPlan, effects_plan
from core.image_order.flat_scene import KernelInputs, TraceSettings, kernel_inputs, trace_scene
from core.image_order.grid_of_cuboids import UniformGrid
from core.image_order.ray_tree import trace_pixel
from core.presets_trace import warm_up_scene
from core.scene import Scene

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).


@dataclass(frozen=True, eq=False)
class TraceResult:
    """An image rendered in image order, with what it took.

    Attributes
    ----------
    color : (H, W, 3) float64, RGB in [0, 1]; ``H = stop - first`` rows of the image.
    depth : (H, W) float64, camera-space distance along the viewing axis of the
        primary ray's hit (positive), ``+inf`` where it hits nothing.
    object_index : (H, W) int64, index into ``scene.objects`` of the first hit, -1 for none.
    stats : dict, JSON-serialisable: ``rays`` (counts by kind), ``plan``
        (:meth:`EffectsPlan.to_dict`), ``accel`` (method, work per ray, build
        time), ``times`` (seconds per kind of work), ``compile_s`` (compiling
        or loading the kernels, not part of ``times``), ``settings``.
    rows : (first, stop), the band of image rows rendered.
    step : int, one ray per ``step x step`` block of pixels.
    plan : EffectsPlan.
    heat : (H, W, 2) int64 or None, what each pixel cost (with ``heat=True``):
        the primitive tests (``[..., HEAT_PRIM_TESTS]``) and the box and sphere tests
        (``[..., HEAT_BOUNDS_TESTS]``, :mod:`core.image_order.flat_layout`: bounding
        spheres, BVH boxes, and the grid's cells walked, each a cuboid the ray enters) of all
        its rays; they add up to ``stats["accel"]["prim_tests"]`` and ``["bounds_tests"]
        + ["cells_visited"]``.
    """

    color: np.ndarray
    depth: np.ndarray
    object_index: np.ndarray
    stats: dict
    rows: tuple[int, int]
    step: int
    plan: EffectsPlan
    heat: np.ndarray | None = None


def render_trace(scene: Scene, settings: TraceSettings = TraceSettings(),
                 rows: tuple[int, int] | None = None, step: int = 1, heat: bool = False) -> TraceResult:
    """Render ``scene`` from its camera by ray casting or ray tracing.

    Parameters
    ----------
    scene : Scene
    settings : TraceSettings
    rows : (first, stop), optional
        Render only image rows ``first .. stop - 1`` (the window fills the
        image band by band); default all rows.
    step : int >= 1
        Trace one ray per ``step x step`` block (through the block's top-left
        pixel) and repeat its colour over the block: a coarse image, fast.
    heat : bool
        Keep what each pixel cost, its intersection tests (``TraceResult.heat``);
        only with ``step = 1``.

    Returns
    -------
    TraceResult
    """
    cam = scene.camera
    first, stop = rows if rows is not None else (0, cam.height)
    if not (0 <= first < stop <= cam.height):
        raise ValueError(f"rows must satisfy 0 <= first < stop <= {cam.height}, got {rows!r}")
    if not (isinstance(step, int) and step >= 1):
        raise ValueError(f"step must be a whole number >= 1, got {step!r}")
    if heat and step != 1:
        raise ValueError(f"a heat map counts every pixel: step must be 1, got {step}")
    warm_up = _compiled_for.get(settings.accel)  # an unknown method is refused below
    compile_s = warm_up() if warm_up else 0.0
    times = {}
    start = time.perf_counter()
    flat = trace_scene(scene)
    geometry = flat.geometry
    times["flatten"] = time.perf_counter() - start
    structure, build_s, cached = geometry.accel(settings.accel)
    times["build"] = 0.0 if cached else build_s
    plan = effects_plan(scene, settings.mode)
    xs = np.arange(0, cam.width, step, dtype=np.float64)
    ys = np.arange(first, stop, step, dtype=np.float64)
    inputs = kernel_inputs(scene, settings, plan, flat, structure)
    tests = np.zeros((len(ys), len(xs), flat_layout.HEAT_SIZE), np.int64) if heat else None
    color, depth, object_index, counters = _run_passes(xs, ys, inputs, times, tests)
    if step > 1:
        h, w = stop - first, cam.width
        color, depth, object_index = (np.repeat(np.repeat(a, step, 0), step, 1)[:h, :w]
                                      for a in (color, depth, object_index))
    times["total"] = sum(times.values())
    stats = _stats(settings, plan, structure, build_s, cached, counters, times, compile_s,
                   (first, stop), step, len(xs) * len(ys), geometry.n_prims, cam)
    return TraceResult(np.ascontiguousarray(color), np.ascontiguousarray(depth),
                       np.ascontiguousarray(object_index), stats, (first, stop), step, plan, tests)


#: The most a thread keeps of the working arrays between renders (bytes: a 640 x 480 frame's
#: need 52 MB, most of it address space never touched).
_KEPT_BYTES = 64 * 2**20
_kept = threading.local()


def _working_arrays(ny: int, nx: int) -> tuple:
    """The render's own arrays for ``ny x nx`` pixels: ``(hits, children, spawned)``.

    Each thread keeps those of its last render, if they are small enough
    (:data:`_KEPT_BYTES`), and the next render of the same size reuses them: memory the system
    hands out new is cleared page by page at its first touch.  A Whitted frame at 640 x 480 (the
    lecture and the mirror-and-glass scenes, depth 5, one thread) took 12-15 % less CPU time
    so, where each frame followed another process's work, as the window's frames do; frames back
    to back in one process, where the C library keeps some freed memory for reuse, 3-8 % less.
    Only the thread that made them uses them, so two renders at once never share them.
    """
    from core.image_order.kernels import render as trace_render

    kept = getattr(_kept, "arrays", None)
    if kept is not None and kept[0].shape[:2] == (ny, nx):
        return kept
    arrays = (np.empty((ny, nx, flat_layout.HIT_SIZE)), trace_render.children_array(ny, nx),
              np.empty((ny, nx), np.uint8))
    _kept.arrays = arrays if sum(a.nbytes for a in arrays) <= _KEPT_BYTES else None
    return arrays


def _run_passes(xs, ys, k: KernelInputs, times: dict, heat: np.ndarray | None = None):
    """The three compiled stages; fills ``times`` and returns the image (colour in [0, 1], depth,
    object index) and the counters.  ``heat`` (ny, nx, HEAT_SIZE) int64, if given, gets each
    pixel's tests added."""
    import numba

    from core.image_order.kernels import render as trace_render

    ny, nx = len(ys), len(xs)
    # Left unset where a stage writes every pixel (hits, depth, objects: primary; colour, spawned:
    # shading), and children, written and read only where a ray goes on: no time spent clearing
    # megabytes.  The image (colour, depth, objects) is new each time: the caller keeps it.
    hits, children, spawned = _working_arrays(ny, nx)
    depth = np.empty((ny, nx))
    objects = np.empty((ny, nx), np.int64)
    color = np.empty((ny, nx, 3))
    counters = np.zeros(flat_layout.N_COUNTERS, np.int64)
    heat = trace_render.no_heat() if heat is None else heat
    for stage, name in ((trace_render.PRIMARY_STAGE, "primary"), (trace_render.SHADE_STAGE, "shading"),
                        (trace_render.SECONDARY_STAGE, "secondary")):
        start = time.perf_counter()
        if stage != trace_render.SECONDARY_STAGE or spawned.any():
            # Ctrl+C or Cancel: StoppedError within a pixel
            with stopping.watching(k.opts, flat_layout.OPT_STOP):
                counters += trace_render.render_pass(stage, k.cam, xs, ys, hits, depth, objects, color,
                                                     children, spawned, k.materials, k.lights, k.opts,
                                                     k.geo, k.grid, k.bvh, k.bvh_depth,
                                                     numba.get_num_threads(), heat)
        times[name] = time.perf_counter() - start
    return color, depth, objects, counters


def _stats(settings, plan, structure, build_s, cached, counters, times, compile_s, rows, step,
           pixels, n_prims, cam) -> dict:
    rays = {"primary": int(counters[flat_layout.PRIMARY]), "shadow": int(counters[flat_layout.SHADOW]),
            "reflection": int(counters[flat_layout.REFLECTION]),
            "refraction": int(counters[flat_layout.REFRACTION])}
    total = sum(rays.values())
    per_ray = 1.0 / max(total, 1)
    accel = {
        "method": settings.accel,
        "primitives": int(n_prims),
        "build_s": float(build_s),
        "cached": bool(cached),
        "prim_tests": int(counters[flat_layout.PRIM_TESTS]),
        "bounds_tests": int(counters[flat_layout.BOUNDS_TESTS]),
        "cells_visited": int(counters[flat_layout.CELLS]),
        "tests_per_ray": counters[flat_layout.PRIM_TESTS] * per_ray,
        "bounds_tests_per_ray": counters[flat_layout.BOUNDS_TESTS] * per_ray,
        "cells_per_ray": counters[flat_layout.CELLS] * per_ray,
    }
    accel.update(describe_structure(structure))
    return {
        "mode": settings.mode,
        "size": [cam.width, cam.height],
        "rows": list(rows),
        "step": step,
        "pixels_traced": int(pixels),
        "rays": {**rays, "total": total},
        "plan": plan.to_dict(),
        "accel": {k: float(v) if isinstance(v, np.floating) else v for k, v in accel.items()},
        "times": {k: float(v) for k, v in times.items()},
        "compile_s": float(compile_s),
        "settings": dataclasses.asdict(settings),
    }


def describe_structure(structure) -> dict:
    """Size figures of an acceleration structure, for the statistics."""
    if isinstance(structure, UniformGrid):
        return {"grid_resolution": [int(r) for r in structure.resolution],
                "grid_cells": structure.n_cells, "grid_entries": int(len(structure.cell_prims))}
    if isinstance(structure, Bvh):
        return {"bvh_nodes": int(len(structure.nodes)), "bvh_depth": structure.depth,
                "bvh_leaves": int(structure.is_leaf.sum())}
    return {}


_KERNELS = "core.image_order.kernels.jit"  # imports numba and puts the tracer's kernels in their cache


def _warm_up(accel: str) -> None:
    """Render a tiny scene with ``accel`` so the kernels see exactly the argument types of real
    renders; its structure is built too, so build times exclude compiling."""
    scene = warm_up_scene()
    flat = trace_scene(scene)
    settings = TraceSettings(accel=accel)
    structure, _, _ = flat.geometry.accel(accel)
    inputs = kernel_inputs(scene, settings, effects_plan(scene), flat, structure)
    _run_passes(np.arange(2.0), np.arange(2.0), inputs, {})


_compiled_for = {accel: WarmUp(functools.partial(_warm_up, accel), _KERNELS, "trace", accel)
                 for accel in flat_layout.ACCEL_CODES}
"""A render compiles only what its acceleration method needs: the window's first image waits for less."""


def _warm_up_renders() -> None:
    for accel in sorted(_compiled_for, key=lambda a: a != "bvh"):  # the window's first image's first
        _compiled_for[accel]()


compile_renders = WarmUp(_warm_up_renders, _KERNELS, "trace", "renders")
"""Compile the kernels of every image render (each acceleration method) once per process."""
compile_ray_tree = WarmUp(lambda: trace_pixel(warm_up_scene(), 1, 1, TraceSettings()), _KERNELS, "trace",
                          "ray tree")
"""Compile the kernels that trace one pixel's ray tree (a picked pixel) once per process."""


def _warm_up_shadow_rays() -> None:
    """Trace two shadow rays in a batch, as ``python -m app bench trace`` times them."""
    from core.image_order.kernels.shadow_rays import trace_shadow_rays

    scene = warm_up_scene()
    flat = trace_scene(scene)
    structure, _, _ = flat.geometry.accel("bvh")
    k = kernel_inputs(scene, TraceSettings(accel="bvh"), effects_plan(scene), flat, structure)
    origins, directions = np.zeros((2, 3), np.float32), np.ones((2, 3), np.float32)
    trace_shadow_rays(origins, directions, np.zeros(2, np.float32), np.ones(2, np.float32), k.bvh,
                      k.geo[flat_layout.GEO_N_SPHERES], k.bvh_depth, 1, np.full(2, -1, np.int64),
                      np.full(2, np.inf))


compile_shadow_rays = WarmUp(_warm_up_shadow_rays, _KERNELS, "trace", "shadow rays")
"""Compile the kernel that traces a batch of shadow rays (``bench trace``'s) once per process."""


def _warm_up_ray_tree_and_shadow_rays() -> None:
    compile_ray_tree()
    compile_shadow_rays()  # after the ray tree, in its process: its walks are compiled already


compile_ray_tree_and_shadow_rays = WarmUp(_warm_up_ray_tree_and_shadow_rays, _KERNELS, "trace",
                                          "ray tree and shadow rays")
"""The ``ray-tree`` group of ``python -m app compile``: a picked pixel's kernels, then the shadow
rays' batch kernel (4 s more in that process, 9 s in one of its own)."""


def _warm_up_all() -> None:
    compile_renders()
    compile_ray_tree()


ensure_compiled = WarmUp(_warm_up_all, _KERNELS, "trace", "all")
"""Compile every tracer kernel once per process; returns the seconds it took (0.0 later)."""


def warm_up_for(accel: str) -> WarmUp:
    """The warm-up that compiles the kernels a render with ``accel`` runs."""
    return _compiled_for[accel]


def compiled_for(accel: str) -> bool:
    """Whether a render with ``accel`` starts without compiling (see :meth:`WarmUp.ready`)."""
    return _compiled_for[accel].ready()


def compile_for(accel: str) -> float:
    """Compile the kernels a render with ``accel`` runs, once per process; the seconds it took (0.0 later)."""
    return _compiled_for[accel]()


def merge_band_stats(parts: list[dict]) -> dict:
    """One image's statistics from its bands': counts and times add up, per-ray figures are redone."""
    merged = {**parts[0], "rays": {}, "times": {}, "accel": dict(parts[0]["accel"])}
    for part in parts:
        for group in ("rays", "times"):
            for key, value in part[group].items():
                merged[group][key] = merged[group].get(key, 0) + value
    for key in ("prim_tests", "bounds_tests", "cells_visited"):
        merged["accel"][key] = sum(p["accel"][key] for p in parts)
    rays = max(merged["rays"]["total"], 1)
    merged["accel"]["tests_per_ray"] = merged["accel"]["prim_tests"] / rays
    merged["accel"]["bounds_tests_per_ray"] = merged["accel"]["bounds_tests"] / rays
    merged["accel"]["cells_per_ray"] = merged["accel"]["cells_visited"] / rays
    merged["rows"] = [0, parts[-1]["rows"][1]]
    merged["pixels_traced"] = sum(p["pixels_traced"] for p in parts)
    return merged


def sample_tracer(scene: Scene, settings: TraceSettings = TraceSettings()):
    """Prepare ``scene`` once and return a function that traces any grid of sample positions.

    Supersampling traces many sub-pixel positions per pixel; this skips the
    preparation :func:`render_trace` repeats on every call.

    Returns
    -------
    trace(xs, ys) -> (color, depth, object_index)
        ``xs`` (nx,) and ``ys`` (ny,) float64 are sample positions in pixels,
        measured so that ``k`` is the centre of pixel column (row) ``k``: a
        pixel's top-left corner is at ``k - 0.5``.  The ray through every
        ``(xs[i], ys[j])`` is traced; ``color`` (ny, nx, 3) float64 RGB in
        [0, 1], ``depth`` (ny, nx) as :attr:`TraceResult.depth`,
        ``object_index`` (ny, nx) int64 as :attr:`TraceResult.object_index`.
    """
    ensure_compiled()
    flat = trace_scene(scene)
    structure, _, _ = flat.geometry.accel(settings.accel)
    inputs = kernel_inputs(scene, settings, effects_plan(scene, settings.mode), flat, structure)

    def trace(xs, ys):
        color, depth, object_index, _ = _run_passes(np.asarray(xs, dtype=np.float64),
                                                    np.asarray(ys, dtype=np.float64), inputs, {})
        return color, depth, object_index

    return trace
