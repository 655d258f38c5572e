"""The tests' independent references: a brute-force ray caster, and exact crossings.

:func:`cast`: one ray per pixel, every object and every triangle tested, the
closest hit wins, Lambert shading without shadows.  Apart from the camera's
primary rays (:meth:`core.camera.Camera.primary_rays`) it shares no code with
the compiled tracer (:mod:`core.image_order.ray_tracing`) or the rasterizer
(:mod:`core.object_order.pipeline`), so agreeing with it means something.

:func:`exact_sphere_roots` and :func:`exact_triangle_solve` solve the
lecture's equations for one ray in exact rationals (and ``mpmath`` at 50
digits for the square root), with none of the tracer's formulas.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field
from fractions import Fraction

import mpmath
import numpy as np

from core.scene import Scene, Sphere


@dataclass(frozen=True)
class RaycastImage:
    """The result of ray casting a scene.

    Attributes
    ----------
    color : (H, W, 3) float64, RGB in [0, 1].
    t : (H, W) float64, ray parameter of the closest hit along the unit
        primary ray (distance from the ray origin), +inf where nothing was hit.
    object_index : (H, W) int64, index into ``scene.objects``, -1 for background.
    timings : seconds spent per stage (``rays``, ``intersect``, ``shade``).
    tests : number of ray-primitive intersection tests done.
    """

    color: np.ndarray
    t: np.ndarray
    object_index: np.ndarray
    timings: dict[str, float] = field(default_factory=dict)
    tests: int = 0


def hit_spheres(origins, directions, center, radius):
    """Nearest t >= 0 of unit rays against one sphere, +inf on a miss; (N,) each.

    The discriminant is formed from the ray's perpendicular offset from the
    centre, so a small sphere far away does not lose its precision.
    """
    f = origins - np.asarray(center)
    half_b = np.einsum("ij,ij->i", f, directions)
    perp = f - half_b[:, None] * directions
    disc = (radius - np.linalg.norm(perp, axis=1)) * (radius + np.linalg.norm(perp, axis=1))
    t = np.full(len(origins), np.inf)
    ok = disc >= 0
    root = np.sqrt(disc[ok])
    q = -(half_b[ok] + np.copysign(root, half_b[ok]))
    c = np.einsum("ij,ij->i", f[ok], f[ok]) - radius * radius
    with np.errstate(divide="ignore", invalid="ignore"):
        t0, t1 = q, np.where(q != 0, c / q, 0.0)
    near, far = np.minimum(t0, t1), np.maximum(t0, t1)
    t[ok] = np.where(near >= 0, near, np.where(far >= 0, far, np.inf))
    return t


def hit_triangle(origins, directions, a, b, c):
    """Nearest t >= 0 of rays against triangle (a, b, c), +inf on a miss; (N,).

    Solves ``o + t d = alpha A + beta B + (1 - alpha - beta) C`` by Cramer's rule.
    """
    e1, e2 = a - c, b - c
    p = np.cross(directions, e2)
    det = p @ e1
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = origins - c
        alpha = np.einsum("ij,ij->i", s, p) * inv
        q = np.cross(s, e1)
        beta = np.einsum("ij,ij->i", directions, q) * inv
        t = (q @ e2) * inv
    ok = (det != 0) & (alpha >= 0) & (beta >= 0) & (alpha + beta <= 1) & (t >= 0)
    return np.where(ok, t, np.inf)


def exact_sphere_roots(origin, direction, center, radius):
    """The roots ``t_near <= t_far`` of ``|o + t d - centre|² = r²`` to 50 digits, ``None`` on a miss.

    The coefficients ``a, b, c`` and ``Δ = b² - 4ac`` are exact rationals of
    the float inputs; only the square root and the division are rounded, at
    50 significant digits.  Returns ``(t_near, t_far, line_distance)`` as
    floats, ``line_distance`` being the exact distance from the centre to the
    line, rounded.
    """
    f = [Fraction(o) - Fraction(c) for o, c in zip(origin, center, strict=True)]
    d = [Fraction(x) for x in direction]
    a = sum(x * x for x in d)
    b = 2 * sum(fi * di for fi, di in zip(f, d, strict=True))
    c = sum(fi * fi for fi in f) - Fraction(radius) ** 2
    disc = b * b - 4 * a * c
    with mpmath.workdps(50):
        distance = float(mpmath.sqrt(mpmath.mpf(sum(fi * fi for fi in f) - (b / 2) ** 2 / a)))
        if disc < 0:
            return None
        root = mpmath.sqrt(mpmath.mpf(disc))
        near = (-mpmath.mpf(b) - root) / (2 * mpmath.mpf(a))
        far = (-mpmath.mpf(b) + root) / (2 * mpmath.mpf(a))
        return float(near), float(far), distance


def exact_triangle_solve(origin, direction, a, b, c):
    """``(alpha, beta, gamma, t)`` of ``o + t d = αA + βB + γC``, ``α + β + γ = 1``, as Fractions.

    Gauss-Jordan elimination in exact rationals; ``None`` when the system is
    singular (the ray is parallel to the triangle's plane).
    """
    o, d, A, B, C = ([Fraction(x) for x in v] for v in (origin, direction, a, b, c))
    rows = [[A[k] - C[k], B[k] - C[k], -d[k], o[k] - C[k]] for k in range(3)]
    for col in range(3):
        pivot = next((r for r in range(col, 3) if rows[r][col] != 0), None)
        if pivot is None:
            return None
        rows[col], rows[pivot] = rows[pivot], rows[col]
        rows[col] = [x / rows[col][col] for x in rows[col]]
        for r in range(3):
            if r != col:
                rows[r] = [x - rows[r][col] * y for x, y in zip(rows[r], rows[col], strict=True)]
    alpha, beta, t = (row[3] for row in rows)
    return alpha, beta, 1 - alpha - beta, t


def cast(scene: Scene, rows: tuple[int, int] | None = None) -> RaycastImage:
    """Ray cast ``scene`` from its camera: closest hit, Lambert shading.

    ``rows = (first, stop)`` casts only that band of image rows, so a caller
    can fill the image band by band, report progress and stop early.
    """
    cam = scene.camera
    first, stop = rows if rows is not None else (0, cam.height)
    t_start = time.perf_counter()
    origins, directions = cam.primary_rays((first, stop))
    origins, directions = origins.reshape(-1, 3), directions.reshape(-1, 3)
    n_rays = len(origins)
    best_t = np.full(n_rays, np.inf)
    best_obj = np.full(n_rays, -1, dtype=np.int64)
    normals = np.zeros((n_rays, 3))
    t_rays = time.perf_counter()
    tests = 0
    for index, obj in enumerate(scene.objects):
        if isinstance(obj, Sphere):
            t = hit_spheres(origins, directions, obj.center, obj.radius)
            tests += n_rays
            closer = t < best_t
            best_t[closer], best_obj[closer] = t[closer], index
            points = origins[closer] + t[closer, None] * directions[closer]
            normals[closer] = (points - obj.center) / obj.radius
            continue
        center, radius = obj.bounding_sphere()
        candidates = np.flatnonzero(hit_spheres(origins, directions, center, radius) < np.inf)
        tests += n_rays
        if candidates.size == 0:
            continue
        o, d = origins[candidates], directions[candidates]
        for corners, normal in zip(obj.corners, obj.normals, strict=True):
            t = hit_triangle(o, d, *corners)
            tests += len(candidates)
            closer = t < best_t[candidates]
            rows = candidates[closer]
            best_t[rows], best_obj[rows], normals[rows] = t[closer], index, normal
    t_hit = time.perf_counter()
    color = _lambert(scene, origins, directions, best_t, best_obj, normals)
    t_shade = time.perf_counter()
    shape = (stop - first, cam.width)
    return RaycastImage(
        color=color.reshape(*shape, 3),
        t=best_t.reshape(shape),
        object_index=best_obj.reshape(shape),
        timings={"rays": t_rays - t_start, "intersect": t_hit - t_rays, "shade": t_shade - t_hit},
        tests=tests,
    )


def _lambert(scene, origins, directions, t, obj_index, normals):
    """Ambient plus diffuse light from every point light (no shadows yet)."""
    color = np.broadcast_to(np.asarray(scene.background, dtype=float), origins.shape).copy()
    hit = obj_index >= 0
    if not hit.any():
        return color
    points = origins[hit] + t[hit, None] * directions[hit]
    n = normals[hit]
    # Two-sided: turn the normal toward the viewer so single-sided planes light up.
    n = np.where((np.einsum("ij,ij->i", n, directions[hit]) > 0)[:, None], -n, n)
    materials = [scene.objects[i].material for i in obj_index[hit]]
    base = np.array([m.color for m in materials])
    ka = np.array([m.ambient for m in materials])[:, None]
    kd = np.array([m.diffuse for m in materials])[:, None]
    light_sum = np.zeros_like(base)
    for light in scene.lights:
        to_light = np.asarray(light.position) - points
        to_light /= np.linalg.norm(to_light, axis=1, keepdims=True)
        lambert = np.clip(np.einsum("ij,ij->i", n, to_light), 0.0, None)[:, None]
        light_sum += lambert * light.intensity * np.asarray(light.color)
    if not scene.lights:
        light_sum[:] = 1.0  # an unlit scene is shown flat rather than black
    color[hit] = np.clip(base * (ka + kd * light_sum), 0.0, 1.0)
    return color
