"""Crossing a ray with a sphere: the lecture's quadratic, solved step by step.

The sphere with centre ``(l, m, n)`` and radius ``r`` is
``(x - l)^2 + (y - m)^2 + (z - n)^2 = r^2``.  The lecture writes the ray as a
*segment* from ``(x1, y1, z1)`` to ``(x2, y2, z2)``::

    x = x1 + i t,  y = y1 + j t,  z = z1 + k t,  0 <= t <= 1,
    with i = x2 - x1, j = y2 - y1, k = z2 - z1.

Substituting it into the sphere equation gives ``a t^2 + b t + c = 0``; the
sign of the discriminant ``Δ = b^2 - 4ac`` tells whether the line misses the
sphere, touches it or crosses it, and the smaller admissible root is the first
crossing.  The same algebra serves the half-line ``o + t d`` with ``t >= 0``
(:func:`intersect_sphere`); the segment (:func:`intersect_sphere_segment`) is
that ray with ``d = p2 - p1`` (not normalised) and the extra limit ``t <= 1``.

Numerics
--------
Written naively, ``b^2 - 4ac`` cancels catastrophically for a small or distant
sphere (both terms are huge and nearly equal), and ``(-b ± √Δ) / 2a`` loses the
root whose numerator cancels.  As pbrt does, this module

- works with ``f = o - centre``, the start point seen from the centre;
- computes ``Δ = 4a (r + |v|)(r - |v|)``, where ``v = f - (f·d / d·d) d`` is
  the offset from the centre to the closest point of the line, so
  ``|v|`` is the distance between the centre and the line (equal to
  ``b^2 - 4ac`` in exact arithmetic, with no cancellation);
- takes the roots as ``q = -(b + sign(b)√Δ) / 2``, ``t0 = q / a``,
  ``t1 = c / q`` (no subtraction of nearly equal numbers);
- calls the ray *tangent* when ``|v|`` equals ``r`` to within the rounding
  error of computing ``v`` (relative to ``|f| + r``); then both roots are
  ``-b / 2a``.

One formula, two users
----------------------
:func:`sphere_roots` is that arithmetic, once.  :func:`~core.compiling.jitable.jitable` leaves it
a plain Python function when :func:`intersect_sphere` calls it for the
worked solution, and compiles it into the tracer's kernels
(:mod:`core.image_order.kernels.intersect`) when they call it, so the
explanation and the rendered image cross every sphere with the very same
operations in the same order.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from core.compiling.jitable import jitable
from core.shown_numbers import shown_number as _g
from core.shown_numbers import shown_vector as _vec

#: Coordinates may be at most this big, and the radius and ``|d|`` at least its
#: inverse, so that no square or product in the solution over- or underflows.
LIMIT = 1e60

#: ``| |v| - r |`` below this times ``|f| + r`` counts as tangent: a few units of
#: rounding in ``f = o - centre`` and in the projection that gives ``v``.
TANGENT_TOLERANCE = 8 * np.finfo(float).eps

#: How the line meets the sphere, as :func:`sphere_roots` reports it (index into ``CLASSIFICATIONS``).
MISSES, TANGENT, CROSSES = 0, 1, 2
CLASSIFICATIONS = ("misses", "tangent", "crosses")


@jitable(forceinline=True)
def line_terms(ox, oy, oz, dx, dy, dz, cx, cy, cz, r):
    """The numbers the quadratic of the line ``o + t d`` and a sphere is made of:
    ``(fx, fy, fz, a, half_b, f2, r2)`` with ``f = o - centre``, ``a = d·d``, ``half_b = f·d``,
    ``f2 = f·f`` and ``r2 = r²`` (so ``c = f2 - r2``).  :func:`sphere_roots` and the tracer's
    quick answers for rays that clearly miss a sphere take them from here, rounded alike.

    Examples
    --------
    >>> line_terms(0.0, 0.0, 5.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0)
    (0.0, 0.0, 5.0, 1.0, -5.0, 25.0, 1.0)
    """
    fx, fy, fz = ox - cx, oy - cy, oz - cz
    return (fx, fy, fz, dx * dx + dy * dy + dz * dz, fx * dx + fy * dy + fz * dz, fx * fx + fy * fy + fz * fz,
            r * r)


@jitable(forceinline=True)
def sphere_roots(ox, oy, oz, dx, dy, dz, cx, cy, cz, r):
    """The quadratic of the line ``o + t d`` and a sphere, and its two roots, without cancellation.

    Parameters
    ----------
    ox, oy, oz, dx, dy, dz : float, world space
        The line's start point ``o`` and direction ``d`` (not zero, any length;
        ``t`` is in units of ``|d|``).
    cx, cy, cz, r : float, world space
        The sphere's centre and radius (``r > 0``).

    Returns
    -------
    (a, half_b, c, line_distance, discriminant, kind, t_near, t_far) : floats and an int
        ``a = d·d``, ``half_b = f·d`` and ``c = f·f - r²`` with ``f = o - centre``;
        ``line_distance = |v|``, the distance from the centre to the line;
        ``discriminant = b² - 4ac``, computed as ``4a (r + |v|)(r - |v|)``;
        ``kind`` is ``MISSES``, ``TANGENT`` or ``CROSSES``; the roots
        ``t_near <= t_far`` (both ``-half_b / a`` when tangent, both ``inf``
        when the line misses).

    Examples
    --------
    >>> sphere_roots(0.0, 0.0, 5.0, 0.0, 0.0, -1.0, 0.0, 0.0, 0.0, 1.0)
    (1.0, -5.0, 24.0, 0.0, 4.0, 2, 4.0, 6.0)
    """
    fx, fy, fz, a, half_b, f2, r2 = line_terms(ox, oy, oz, dx, dy, dz, cx, cy, cz, r)
    c = f2 - r2
    # The perpendicular offset v from the centre to the line, and its length |v|.
    k = half_b / a
    vx, vy, vz = fx - k * dx, fy - k * dy, fz - k * dz
    dist = math.sqrt(vx * vx + vy * vy + vz * vz)
    discriminant = 4.0 * a * (r + dist) * (r - dist)
    # Decide from the discriminant, then find the roots: q / a and c / q, no cancellation.
    if abs(dist - r) <= TANGENT_TOLERANCE * (math.sqrt(f2) + r):
        t = -half_b / a
        return a, half_b, c, dist, discriminant, TANGENT, t, t
    if dist > r:
        return a, half_b, c, dist, discriminant, MISSES, math.inf, math.inf
    q = -(half_b + math.copysign(math.sqrt(discriminant / 4.0), half_b))
    t0, t1 = q / a, c / q
    if t0 > t1:
        return a, half_b, c, dist, discriminant, CROSSES, t1, t0
    return a, half_b, c, dist, discriminant, CROSSES, t0, t1


@jitable(forceinline=True)
def outward_normal(px, py, pz, cx, cy, cz, dx, dy, dz):
    """The unit normal ``(p - centre) / |p - centre|`` at a point ``p`` of a sphere, pointing out.

    A sphere smaller than the rounding of its hit point (``p == centre``)
    has no usable normal; it then faces the ray that found it, ``-d / |d|``.

    Examples
    --------
    >>> outward_normal(0.0, 0.0, 2.0, 0.0, 0.0, 0.0, 0.0, 0.0, -1.0)
    (0.0, 0.0, 1.0)
    """
    ux, uy, uz = px - cx, py - cy, pz - cz
    length = math.sqrt(ux * ux + uy * uy + uz * uz)
    if length > 0.0:
        return ux / length, uy / length, uz / length
    length = math.sqrt(dx * dx + dy * dy + dz * dz)
    return -dx / length, -dy / length, -dz / length


@dataclass(frozen=True)
class SphereIntersection:
    """Everything a student writes down when crossing a ray with a sphere.

    Attributes
    ----------
    origin : (3,) float64, world space
        The start point ``o`` = ``(x1, y1, z1)``.
    direction : (3,) float64
        ``d`` = ``(i, j, k)``; for a segment ``p2 - p1`` (not normalised).
    end : (3,) float64 or None
        The segment's end point ``(x2, y2, z2)``; ``None`` for a ray.
    center : (3,) float64
        The sphere's centre ``(l, m, n)``.
    radius : float
        ``r > 0``.
    offset : (3,) float64
        ``f = o - centre``.
    a, b, c : float
        Coefficients of ``a t^2 + b t + c = 0``: ``a = d·d``, ``b = 2 f·d``,
        ``c = f·f - r^2``.
    half_b : float
        ``b / 2 = f·d`` (the form most ray tracers use).
    line_distance : float
        ``|v|``, the distance from the centre to the (infinite) line.
    discriminant : float
        ``Δ = b^2 - 4ac``, computed as ``4a (r + |v|)(r - |v|)``.
    classification : str
        ``"misses"`` (Δ < 0), ``"tangent"`` (Δ = 0 up to rounding) or
        ``"crosses"`` (Δ > 0).  This is about the whole line, before the limits
        on ``t`` are applied.
    t_near, t_far : float or None
        The roots, ``t_near <= t_far`` (equal when tangent, ``None`` when the
        line misses).
    origin_inside : bool
        The start point lies strictly inside the sphere (``c < 0``).
    t_max : float
        The largest admissible ``t``: ``1.0`` for a segment, ``inf`` for a ray.
    hit : bool
        A root lies in ``[0, t_max]``.
    t : float or None
        The first admissible root (the first crossing).
    chosen : str or None
        Which root was taken, ``"t_near"`` or ``"t_far"``.
    reason : str
        Why that root (or why none).
    point : (3,) float64 or None
        The first crossing point ``o + t d``.
    normal : (3,) float64 or None
        Unit normal at ``point``, pointing out of the sphere (also when the
        ray comes from inside).
    ray_hit_t : float or None
        The first crossing for ``t >= 0`` on the infinite ray through the
        segment (equal to ``t`` for a ray).
    ray_reason : str
        Why, for the infinite ray.
    """

    origin: np.ndarray
    direction: np.ndarray
    end: np.ndarray | None
    center: np.ndarray
    radius: float
    offset: np.ndarray
    a: float
    b: float
    c: float
    half_b: float
    line_distance: float
    discriminant: float
    classification: str
    t_near: float | None
    t_far: float | None
    origin_inside: bool
    t_max: float
    hit: bool
    t: float | None
    chosen: str | None
    reason: str
    point: np.ndarray | None
    normal: np.ndarray | None
    ray_hit_t: float | None
    ray_reason: str

    @property
    def is_segment(self) -> bool:
        """The lecture's segment form (``0 <= t <= 1``) rather than a ray."""
        return self.end is not None

    @property
    def offset_squared(self) -> float:
        """``f·f``, the start point's squared distance from the centre (``c + r^2``)."""
        return float(self.offset @ self.offset)

    @property
    def radius_squared(self) -> float:
        return self.radius * self.radius

    @property
    def sqrt_discriminant(self) -> float | None:
        """``√Δ``, which the roots ``(-b ∓ √Δ) / 2a`` use; None when the line misses (``Δ < 0``)."""
        return math.sqrt(self.discriminant) if self.discriminant >= 0 else None

    @property
    def front_face(self) -> bool:
        """The ray arrives from outside the sphere (it hit the entry crossing)."""
        return self.hit and self.chosen == "t_near"

    def explain(self) -> list[str]:
        """The worked solution, one line of text per step."""
        return explain(self)


def intersect_sphere(origin, direction, center, radius) -> SphereIntersection:
    """Cross the ray ``o + t d`` (``t >= 0``) with a sphere.

    Parameters
    ----------
    origin, direction : (3,) float, world space
        Start point and direction of the ray; ``direction`` must not be zero
        and need not be unit length (``t`` is measured in units of ``|d|``).
    center : (3,) float, world space
    radius : float, > 0

    Returns
    -------
    SphereIntersection

    Raises
    ------
    ValueError
        Non-finite input or a coordinate beyond ``LIMIT`` (1e60), a direction
        shorter than ``1 / LIMIT``, or a radius outside ``[1 / LIMIT, LIMIT]``.

    Examples
    --------
    >>> s = intersect_sphere((0, 0, 5), (0, 0, -1), (0, 0, 0), 1.0)
    >>> s.classification, s.t, s.point.tolist()
    ('crosses', 4.0, [0.0, 0.0, 1.0])
    """
    return _intersect(origin, direction, None, center, radius)


def intersect_sphere_segment(start, end, center, radius) -> SphereIntersection:
    """Cross the lecture's segment ``x = x1 + (x2 - x1) t``, ``0 <= t <= 1``, with a sphere.

    Parameters
    ----------
    start, end : (3,) float, world space
        ``(x1, y1, z1)`` and ``(x2, y2, z2)``; they must differ.
    center : (3,) float, world space
    radius : float, > 0

    Returns
    -------
    SphereIntersection
        ``t`` is the segment parameter; ``ray_hit_t`` says where the
        infinite ray through the segment first crosses.

    Examples
    --------
    The lecture's exercise: both end points are inside the sphere.

    >>> s = intersect_sphere_segment((2, 1, 2), (10, 6, 6), (6, 4, 6), 10)
    >>> s.classification, s.hit, s.origin_inside, round(s.ray_hit_t, 4)
    ('crosses', False, True, 1.5602)
    """
    start_v = _vec3("start", start)
    end_v = _vec3("end", end)
    if np.max(np.abs(end_v - start_v)) < 1 / LIMIT:
        raise ValueError("end must differ from start (by at least 1e-60)")
    return _intersect(start_v, end_v - start_v, end_v, center, radius)


def _vec3(name: str, value) -> np.ndarray:
    v = np.asarray(value, dtype=float)
    if v.shape != (3,) or not all(abs(x) <= LIMIT for x in v.tolist()):
        raise ValueError(f"{name} must be three finite numbers of size at most 1e60, got {value!r}")
    return v


def _intersect(origin, direction, end, center, radius) -> SphereIntersection:
    o = _vec3("origin", origin)
    d = _vec3("direction", direction)
    centre = _vec3("center", center)
    r = float(radius)
    if not 1 / LIMIT <= r <= LIMIT:
        raise ValueError(f"radius must be a number > 0 between 1e-60 and 1e60, got {radius!r}")
    if np.max(np.abs(d)) < 1 / LIMIT:
        raise ValueError("direction must not be the zero vector (nor shorter than 1e-60)")

    # The quadratic's coefficients, its discriminant and roots: the tracer's own arithmetic.
    f = o - centre
    a, half_b, c, dist, discriminant, kind, t_near, t_far = sphere_roots(
        *o.tolist(), *d.tolist(), *centre.tolist(), r)
    classification = CLASSIFICATIONS[kind]
    if kind == MISSES:
        t_near = t_far = None

    t_max = 1.0 if end is not None else math.inf
    t, chosen, reason = _choose(classification, t_near, t_far, t_max)
    ray_t, _, ray_reason = _choose(classification, t_near, t_far, math.inf)
    point = normal = None
    if t is not None:
        point = o + t * d
        normal = np.array(outward_normal(*point.tolist(), *centre.tolist(), *d.tolist()))
    return SphereIntersection(
        origin=o, direction=d, end=end, center=centre, radius=r, offset=f,
        a=a, b=2.0 * half_b, c=c, half_b=half_b, line_distance=dist,
        discriminant=discriminant, classification=classification,
        t_near=t_near, t_far=t_far, origin_inside=c < 0, t_max=t_max,
        hit=t is not None, t=t, chosen=chosen, reason=reason,
        point=point, normal=normal, ray_hit_t=ray_t, ray_reason=ray_reason,
    )


def _choose(classification, t_near, t_far, t_max):
    """Pick the first root in ``[0, t_max]``: ``(t, which, why)``."""
    end_word = "the end point (t > 1)" if t_max == 1.0 else "t_max"
    if classification == "misses":
        return None, None, "Δ < 0: the line passes farther than r from the centre, so it misses the sphere"
    if classification == "tangent":
        if t_near < 0:
            return None, None, "Δ = 0, but the line touches the sphere at t < 0, behind the start point"
        if t_near > t_max:
            return None, None, f"Δ = 0, but the line touches the sphere beyond {end_word}"
        return t_near, "t_near", "Δ = 0: a double root, the ray just touches the sphere at one point"
    if 0 <= t_near <= t_max:
        return t_near, "t_near", "t_near >= 0: the smaller root lies ahead, where the ray enters the sphere"
    if t_near < 0 <= t_far:
        if t_far == 0:
            return t_far, "t_far", (
                "t_far = 0: the start point lies on the sphere (c = 0) and the ray heads out, "
                "so it leaves the surface where it starts"
            )
        if t_far <= t_max:
            return t_far, "t_far", (
                "t_near < 0 because the start point is inside the sphere, "
                "so the exit t_far is the first crossing"
            )
        return None, None, (
            "t_near < 0 and t_far > 1: both ends of the segment are inside the sphere, "
            "so the segment never reaches its surface"
        )
    if t_far < 0:
        return None, None, "both roots are negative: the sphere lies behind the start point"
    return None, None, f"both roots lie beyond {end_word}: the segment stops before the sphere"


def _plus(x: float) -> str:
    """`` + x`` or `` - |x|`` for continuing a sum."""
    return f" - {_g(-x)}" if x < 0 else f" + {_g(x)}"


def _minus(x: float) -> str:
    """`` - x`` or `` + |x|`` for subtracting ``x`` (``-0`` reads `` - 0``)."""
    return f" - {_g(x)}" if x >= 0 else f" + {_g(-x)}"


def explain(s: SphereIntersection) -> list[str]:
    """The worked solution of :class:`SphereIntersection` ``s``, step by step."""
    o, d, centre, r = s.origin, s.direction, s.center, s.radius
    names = ("x", "y", "z")
    lines = [
        "Crossing a ray with a sphere",
        f"Sphere: (x - l)² + (y - m)² + (z - n)² = r², centre (l, m, n) = {_vec(centre)}, "
        f"r = {_g(r)}",
    ]
    if s.is_segment:
        lines += [
            f"Segment from (x1, y1, z1) = {_vec(o)} to (x2, y2, z2) = {_vec(s.end)}, 0 <= t <= 1:",
            f"  i = x2 - x1 = {_g(d[0])},  j = y2 - y1 = {_g(d[1])},  k = z2 - z1 = {_g(d[2])}",
        ]
    else:
        lines.append(
            f"Ray from (x1, y1, z1) = {_vec(o)} along (i, j, k) = {_vec(d)}, t >= 0:"
        )
    lines.append("  " + ",  ".join(f"{n} = {_g(o[k])}{_plus(d[k])}t" for k, n in enumerate(names)))
    lines += [
        "Substitute x, y, z into the sphere equation:",
        "  " + " + ".join(f"({_g(o[k])}{_plus(d[k])}t{_minus(centre[k])})²" for k in range(3))
        + f" = {_g(r)}²",
        "  " + " + ".join(f"({_g(s.offset[k])}{_plus(d[k])}t)²" for k in range(3))
        + f" = {_g(r * r)}",
        "Expand and collect powers of t: a t² + b t + c = 0 with",
        f"  a = i² + j² + k² = {_g(s.a)}",
        f"  b = 2[i(x1 - l) + j(y1 - m) + k(z1 - n)] = {_g(s.b)}",
        f"  c = (x1 - l)² + (y1 - m)² + (z1 - n)² - r² = {_g(s.c + r * r)} - {_g(r * r)} = {_g(s.c)}",
        f"Discriminant: Δ = b² - 4ac = {_g(s.discriminant)}",
        f"  (computed as 4a(r + |v|)(r - |v|), where |v| = {_g(s.line_distance)} is the distance",
        "   from the centre to the line; this form does not cancel for small or far spheres)",
    ]
    if s.classification == "misses":
        lines.append("Δ < 0: no real roots, the line does not meet the sphere.")
    elif s.classification == "tangent":
        lines += [
            "Δ = 0 (up to rounding, |v| = r): the line is tangent to the sphere.",
            f"Double root: t = -b / 2a = {_g(s.t_near)}",
        ]
    else:
        lines += [
            "Δ > 0: two real roots, the line crosses the sphere twice (in and out).",
            f"Roots: t = (-b ± √Δ) / 2a:  t_near = {_g(s.t_near)},  t_far = {_g(s.t_far)}",
        ]
    if s.origin_inside:
        lines.append("c < 0: the start point is inside the sphere.")
    limits = "0 <= t <= 1" if s.is_segment else "t >= 0"
    lines.append(f"Choice ({limits}): {s.reason}.")
    if s.hit:
        lines += [
            f"First crossing: t = {_g(s.t)}, point (x, y, z) = {_vec(s.point)}",
            f"  outward unit normal (point - centre) / r = {_vec(s.normal)}",
        ]
    else:
        lines.append(f"No crossing for {limits}.")
    if s.is_segment:
        if s.ray_hit_t is None:
            lines.append(f"On the infinite ray (t >= 0): no crossing either; {s.ray_reason}.")
        else:
            lines.append(
                f"On the infinite ray (t >= 0) the first crossing is at t = {_g(s.ray_hit_t)}, "
                f"point {_vec(o + s.ray_hit_t * d)}."
            )
    return lines
