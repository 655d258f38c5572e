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
#: Bytes per pixel of an image kept on screen (float RGB and its 8-bit picture), and of the
#: temporaries of converting one for the screen (sRGB encoding in float64).
SHOWN_BYTES_PER_PIXEL, CONVERT_BYTES_PER_PIXEL = 30, 100
#: An estimate above this many seconds is announced before the work starts.
SLOW_SECONDS = 5.0


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


def estimate(scene, mode: str, accel: str = "bvh", max_depth: int = 5,
             sphere_triangles: int = SPHERE_TRIANGLES_RASTER) -> Estimate:
    """Estimate the memory and time of rendering ``scene`` from its camera.

    Parameters
    ----------
    scene : core.scene.Scene
    mode : ``"raster"``, ``"raycast"`` or ``"raytrace"``.
    accel : image order: ``"none"`` tests every ray against every primitive.
    max_depth : ray tracing: deepest bounce (counted only where the effects plan traces reflected rays).
    sphere_triangles : object order: triangles each analytic sphere is tessellated into.

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
        triangles += spheres * sphere_triangles
    parts = {"image buffers": pixels * BYTES_PER_PIXEL[mode],
             "triangles": triangles * BYTES_PER_TRIANGLE[mode]}
    slow = None
    if mode == "raster":
        seconds = triangles * SECONDS_PER_TRIANGLE + pixels * 1e-7
    else:
        lights = len(scene.lights)
        # Bounces only where the effects plan traces them (some surface mirrors or refracts): a scene
        # with none traces primary and shadow rays alone, in either mode.
        from core.image_order.effects_plan import effects_plan

        bounces = max_depth if mode == "raytrace" and effects_plan(scene, mode).reflection_rays else 0
        rays = pixels * (1 + lights) * (1 + bounces)
        primitives = spheres + triangles
        if accel == "none":
            seconds = rays * primitives * SECONDS_PER_TEST
            slow = (f"--accel none tests each of about {rays:,} rays against all "
                    f"{primitives:,} primitives; --accel bvh is far faster")
        else:
            seconds = rays * SECONDS_PER_RAY
    return Estimate(sum(parts.values()), parts, seconds, slow)


def combined(estimates, shown_pixels: int = 0, shown_images: int = 0) -> Estimate:
    """The cost of renders made one after another, whose results are shown on screen.

    Memory is the largest render's plus ``shown_images`` images of
    ``shown_pixels`` pixels kept for display (and converting one of them);
    time is the sum.
    """
    largest = max(estimates, key=lambda e: e.bytes)
    parts = dict(largest.parts)
    if shown_images:
        parts["shown images"] = shown_pixels * (CONVERT_BYTES_PER_PIXEL
                                                + shown_images * SHOWN_BYTES_PER_PIXEL)
    slow = next((e.slow_because for e in estimates if e.slow_because), None)
    return Estimate(sum(parts.values()), parts, sum(e.seconds for e in estimates), slow)


def memory_limit(given: int | None, option: str = "--memory-limit") -> tuple[int, str]:
    """The memory budget, bytes, and where it comes from: ``given`` (by ``option``), else
    :func:`default_budget`."""
    if given is not None:
        return given, option
    return default_budget(), f"half of the {format_bytes(available_memory())} available"


def refusal(what: str, cost: Estimate, limit: int, source: str) -> str | None:
    """Why a render of ``what`` costing ``cost`` is over the budget ``limit`` (from ``source``); None if not.

    Examples
    --------
    >>> cost = Estimate(40 * 10**9, {"image buffers": 39 * 10**9, "triangles": 10**9}, 60.0)
    >>> print(refusal("16384 × 16384 raycast", cost, 2 * 10**9, "--memory-limit"))
    16384 × 16384 raycast needs about 40 GB (image buffers 39 GB, triangles 1 GB); the budget is 2 GB \
(--memory-limit)
    >>> refusal("a small one", cost, 10**11, "--memory-limit") is None
    True
    """
    if cost.bytes <= limit:
        return None
    parts = ", ".join(f"{k} {format_bytes(v)}" for k, v in cost.parts.items() if v)
    return (f"{what} needs about {format_bytes(cost.bytes)} ({parts}); the budget is "
            f"{format_bytes(limit)} ({source})")


def largest_part(cost: Estimate) -> str:
    """The name of the part of ``cost`` that takes the most memory (what to reduce first)."""
    return max(cost.parts, key=cost.parts.get)


def format_bytes(n: float) -> str:
    """``n`` bytes as a short decimal figure: ``"3.2 GB"``, ``"512 MB"``, ``"20 kB"``.

    Examples
    --------
    >>> format_bytes(32e9), format_bytes(5e8), format_bytes(2e5), format_bytes(2e4), format_bytes(0)
    ('32 GB', '500 MB', '0.2 MB', '20 kB', '0 kB')
    """
    if n >= 1e9:
        return f"{n / 1e9:.3g} GB"
    if n >= 1e5:
        return f"{n / 1e6:.3g} MB"
    return f"{n / 1e3:.3g} kB"


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
