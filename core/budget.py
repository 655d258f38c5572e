"""The cost of a render, estimated before the work: memory and time.

A render's memory grows with its pixels (colour, depth and per-pixel ray
buffers) and with its triangles (the rasterizer's transformed and clipped
polygons, the tracer's flattened primitives and acceleration structure).
:func:`estimate` adds these up from the scene and the settings alone, so a
command can refuse a render that would exhaust the machine *before*
allocating anything, and warn when one would take hours (every ray tested
against every triangle when there is no acceleration structure).

The per-pixel and per-triangle figures were measured as the peak resident
memory of renders of growing size (see the note of issue 11) and rounded up;
the time per ray-primitive test is a conservative figure for this code's
brute-force loop.  They are estimates, good to a factor of about two.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

#: Bytes per pixel of each mode (image buffers and the per-pixel work arrays).
BYTES_PER_PIXEL = {"raster": 130, "raycast": 150, "raytrace": 160}
#: Bytes per triangle: raster (transformed, clipped, drawn polygons), image order
#: (flattened primitive rows, bounds and the acceleration structure).
BYTES_PER_TRIANGLE = {"raster": 400, "raycast": 650, "raytrace": 650}
#: Triangles of an analytic sphere in object order (it is tessellated there).
SPHERE_TRIANGLES_RASTER = 2 * 64 * (32 - 1)
#: Seconds per ray-primitive test in the brute-force loop (no acceleration).
SECONDS_PER_TEST = 6e-9
#: Seconds per ray with an acceleration structure, and per rasterized triangle.
SECONDS_PER_RAY, SECONDS_PER_TRIANGLE = 3e-7, 1e-6


@dataclass(frozen=True)
class Estimate:
    """What a render will cost.

    Attributes
    ----------
    bytes : estimated peak memory of the render itself, bytes.
    parts : the same split into ``{"image buffers": ..., "triangles": ...}``, bytes.
    seconds : estimated wall-clock time on one core, seconds.
    slow_because : why it is slow, when ``seconds`` is large; else None.
    """

    bytes: int
    parts: dict
    seconds: float
    slow_because: str | None = None


def available_memory() -> int:
    """Memory the system can give a new program without swapping, bytes (``MemAvailable``)."""
    try:
        with open("/proc/meminfo") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except OSError:
        pass
    return os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_AVPHYS_PAGES")


def default_budget() -> int:
    """Half of :func:`available_memory`, bytes."""
    return available_memory() // 2


def count_primitives(scene) -> tuple[int, int]:
    """Analytic spheres and triangles of ``scene``."""
    spheres = sum(1 for obj in scene.objects if not hasattr(obj, "triangles"))
    triangles = sum(len(obj.triangles) for obj in scene.objects if hasattr(obj, "triangles"))
    return spheres, triangles


def estimate(scene, mode: str, accel: str = "bvh", max_depth: int = 5) -> Estimate:
    """Estimate the memory and time of rendering ``scene`` from its camera.

    Parameters
    ----------
    scene : core.scene.Scene
    mode : ``"raster"``, ``"raycast"`` or ``"raytrace"``.
    accel : image order: ``"none"`` tests every ray against every primitive.
    max_depth : ray tracing: deepest bounce.

    Examples
    --------
    >>> from core.scene import Scene
    >>> Scene().camera.width * Scene().camera.height
    76800
    >>> estimate(Scene(), "raster").parts["image buffers"] == 76800 * BYTES_PER_PIXEL["raster"]
    True
    """
    pixels = scene.camera.width * scene.camera.height
    spheres, triangles = count_primitives(scene)
    if mode == "raster":
        triangles += spheres * SPHERE_TRIANGLES_RASTER
    parts = {"image buffers": pixels * BYTES_PER_PIXEL[mode],
             "triangles": triangles * BYTES_PER_TRIANGLE[mode]}
    slow = None
    if mode == "raster":
        seconds = triangles * SECONDS_PER_TRIANGLE + pixels * 1e-7
    else:
        lights = len(scene.lights)
        rays = pixels * (1 + lights) * (1 if mode == "raycast" else 1 + max_depth)
        primitives = spheres + triangles
        if accel == "none":
            seconds = rays * primitives * SECONDS_PER_TEST
            slow = (f"--accel none tests each of about {rays:,} rays against all "
                    f"{primitives:,} primitives; --accel bvh is far faster")
        else:
            seconds = rays * SECONDS_PER_RAY
    return Estimate(sum(parts.values()), parts, seconds, slow)


def format_bytes(n: float) -> str:
    """``n`` bytes as a short decimal figure: ``"3.2 GB"``, ``"512 MB"``.

    Examples
    --------
    >>> format_bytes(32e9), format_bytes(5e8), format_bytes(2e4)
    ('32 GB', '500 MB', '0.02 MB')
    """
    if n >= 1e9:
        return f"{n / 1e9:.3g} GB"
    return f"{n / 1e6:.3g} MB"


def format_seconds(s: float) -> str:
    """A duration for people: ``"under a second"``, ``"40 s"``, ``"12 min"``, ``"3.5 hours"``."""
    if s < 1:
        return "under a second"
    if s < 120:
        return f"{s:.0f} s"
    if s < 7200:
        return f"{s / 60:.0f} min"
    return f"{s / 3600:.3g} hours"


def parse_size(text: str) -> int:
    """A memory size such as ``"8G"``, ``"512MB"`` or ``"1000000"`` in bytes (decimal units).

    Examples
    --------
    >>> parse_size("8G"), parse_size("1.5 GB"), parse_size("512M"), parse_size("100")
    (8000000000, 1500000000, 512000000, 100)
    """
    t = text.strip().upper().removesuffix("B").strip()
    scale = {"K": 1e3, "M": 1e6, "G": 1e9, "T": 1e12}.get(t[-1:], 1)
    number = t[:-1] if scale != 1 else t
    try:
        value = float(number)
    except ValueError:
        raise ValueError(f"expected a size such as 8G, 512M or a number of bytes, got {text!r}") from None
    if not (value > 0 and value * scale < 1e18):
        raise ValueError(f"must be a size > 0 (such as 8G), got {text!r}")
    return int(value * scale)
