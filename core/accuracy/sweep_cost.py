"""What a sweep will cost, before it starts: its largest render's memory, and its time.

A sweep (:class:`core.accuracy.sweep.Sweep`) makes, one after another, each
setting's warm-up, timed and visible-surface renders and a reference per
pipeline; it keeps every finished setting's image, error map and visible
surface.  :func:`estimate` adds these up with :func:`core.budget.estimate`
from the scene and the settings alone (a tessellation is counted from its
rings and segments, never built), so a caller can refuse a sweep that would
exhaust the machine and announce one that would take hours.
"""

from __future__ import annotations

from dataclasses import replace

from core import budget
from core.accuracy import reference, resolution
from core.accuracy.sweep import ADAPTIVE_N

#: Bytes per pixel each finished setting, and each reference, keeps until the sweep is dropped:
#: colour (3 float64), error map (float32), samples and the visible surface (index and depth).
KEPT_BYTES_PER_PIXEL = 60


def _tessellation(rings: int, segments: int) -> int:
    """Triangles of a sphere tessellated into ``rings`` x ``segments`` (:func:`core.shapes.uv_sphere`)."""
    return 2 * segments * (rings - 1)


def _renders(sweep, setting) -> tuple[budget.Estimate, int]:
    """One of ``setting``'s renders, and how many the sweep makes of it (warm-up, runs, visible surface)."""
    scene, mode, value, knob = sweep.scene, setting.mode, setting.value, setting.knob
    count = sweep.runs + 2
    if knob == "spp":
        return budget.estimate(scene, mode), count * value * value
    if knob == "adaptive":
        return budget.estimate(scene, mode), count * ADAPTIVE_N * ADAPTIVE_N  # every pixel refined, at most
    if knob == "depth":
        return budget.estimate(scene, mode, max_depth=value), count
    if knob == "accel":
        return budget.estimate(scene, mode, accel=value), count
    if knob == "resolution":
        w, h = resolution.scaled_size(scene.camera.width, scene.camera.height, value)
        return budget.estimate(replace(scene, camera=scene.camera.replace(width=w, height=h)), mode), count
    if knob == "tessellation":
        return budget.estimate(scene, "raster", sphere_triangles=_tessellation(*value)), count
    return budget.estimate(scene, mode), count  # min-weight, depth-format: the default render's cost


def _reference(sweep, mode: str) -> tuple[budget.Estimate, int]:
    """One pass of the reference of ``mode``, and how many passes it takes (samples per pixel)."""
    passes = sweep.reference_spp ** 2
    if mode == "raster":
        fine = _tessellation(reference.REFERENCE_RINGS, reference.REFERENCE_SEGMENTS)
        return budget.estimate(sweep.scene, mode, sphere_triangles=fine), passes
    return budget.estimate(sweep.scene, mode, max_depth=reference.REFERENCE_DEPTH), passes


def estimate(sweep) -> budget.Estimate:
    """The memory and time of running every setting of ``sweep`` (see the module docstring).

    Memory is the largest single render plus what the finished settings and
    references keep (part ``"kept images"``); time is the sum over all renders.
    """
    modes = {s.mode for s in sweep.settings}
    renders = [_renders(sweep, s) for s in sweep.settings] + [_reference(sweep, m) for m in modes]
    largest = max((e for e, _ in renders), key=lambda e: e.bytes)
    cam = sweep.scene.camera
    kept = (len(sweep.settings) + len(modes)) * cam.width * cam.height * KEPT_BYTES_PER_PIXEL
    parts = {**largest.parts, "kept images": kept}
    return budget.Estimate(sum(parts.values()), parts, sum(e.seconds * n for e, n in renders))
