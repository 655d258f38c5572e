"""Crossing a ray with a triangle: barycentric coordinates, as in the lecture.

A point ``P`` of the plane of triangle ``(A, B, C)`` can be written as
``P = αA + βB + γC`` with ``α + β + γ = 1``; it lies in the triangle when all
three weights are ``>= 0``.  Here ``α`` weights ``A``, ``β`` weights ``B``
and ``γ = 1 - α - β`` weights ``C`` (pbrt calls them ``b0, b1, b2``).  The ray
``r(t) = o + t d`` (``t >= 0``, ``d`` need not be unit length) meets the
triangle where::

    o + t d = αA + βB + (1 - α - β)C,

three linear equations in the three unknowns ``α, β, t``.
:func:`cramer_solve` solves them the way the lecture does, with Cramer's rule.

Watertightness
--------------
Rounding can make a ray that passes exactly through an edge shared by two
triangles miss *both* (a crack in a closed mesh).  :func:`intersect_triangle`
therefore decides with pbrt-v4's watertight test (Woop, Benthin and Wald,
2013): move the vertices so the ray starts at the origin, rename the axes so
the ray's largest direction component is z, shear so the ray becomes the
+z axis, and look at the triangle from along the ray in 2D.  The edge
functions ``e0, e1, e2`` (twice the signed areas of the triangles the ray
makes with each edge) are computed so that

- an edge evaluated from its other end gives exactly the negated value (a
  ray is on exactly one side of a shared edge), and
- their sign is exact: when the rounded value is too small to trust, it is
  recomputed exactly with :class:`fractions.Fraction`.

The ray hits when the three values have the same sign, zeros included, and
do not all vanish.  Then ``α = e0 / (e0 + e1 + e2)`` and so on, and ``t``
follows the same way.  If an edge function is exactly zero (the ray passes
through an edge or vertex) ``t`` and the weights are computed exactly, so
neighbouring triangles report the very same ``t``.
"""

from __future__ import annotations

import contextlib
import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

_UNIT_ROUNDOFF = 2.0**-53
#: A rounded ``p*q - r*s`` is trusted when bigger than this times ``|pq| + |rs|``
#: (the true error bound is below 3 unit roundoffs); the tiny absolute term
#: covers products that underflow.
_EDGE_ERROR = 4 * _UNIT_ROUNDOFF
_UNDERFLOW = 2.0**-1070
#: Coordinates may be at most this big and ``|d|`` at least its inverse, so that
#: no product below over- or underflows.
LIMIT = 1e60
#: ``|det M|`` below this times ``|d| |A - C| |B - C|`` counts as parallel.
PARALLEL_TOLERANCE = 1e-12

NAMES = ("alpha", "beta", "gamma")


@dataclass(frozen=True)
class CramerSolution:
    """The lecture's 3x3 system solved with Cramer's rule.

    The system is ``α(A - C) + β(B - C) - t d = o - C``, with matrix
    ``M = [A - C | B - C | -d]`` (columns) and right-hand side ``o - C``.

    Attributes
    ----------
    matrix : (3, 3) float64
        ``M``; row ``k`` is the equation for coordinate ``k`` (x, y, z).
    rhs : (3,) float64
        ``o - C``.
    det : float
        ``det M``; zero when the ray is parallel to the triangle's plane.
    det_alpha, det_beta, det_t : float
        Determinants of ``M`` with the matching column replaced by ``rhs``.
    alpha, beta, gamma, t : float or None
        ``det_alpha / det`` and so on, ``gamma = 1 - alpha - beta``; ``None``
        when ``det == 0``.
    """

    matrix: np.ndarray
    rhs: np.ndarray
    det: float
    det_alpha: float
    det_beta: float
    det_t: float
    alpha: float | None
    beta: float | None
    gamma: float | None
    t: float | None


@dataclass(frozen=True)
class TriangleIntersection:
    """The crossing of a ray with a triangle, with the lecture's unknowns.

    Attributes
    ----------
    origin, direction : (3,) float64, world space
        The ray ``o + t d``, ``t >= 0``.
    vertices : (3, 3) float64, world space
        Rows ``A``, ``B``, ``C``.
    determinant : float
        ``det M`` of the lecture's system (see :class:`CramerSolution`);
        0 means the ray is parallel to the plane.
    edge_functions : (e0, e1, e2) floats
        The watertight test's edge functions, opposite ``A``, ``B``, ``C``:
        ``e0`` belongs to edge ``BC``.  Same signs: the ray passes inside.
    hit : bool
    t : float or None
        Ray parameter of the crossing with the plane (``None`` if parallel);
        reported on a miss too, so a miss can be explained.
    alpha, beta, gamma : float or None
        Barycentric weights of ``A``, ``B``, ``C`` at that crossing.
    point : (3,) float64 or None
        The hit point ``αA + βB + γC`` (``None`` on a miss).
    reason : str
        Why it hit or missed.
    """

    origin: np.ndarray
    direction: np.ndarray
    vertices: np.ndarray
    determinant: float
    edge_functions: tuple[float, float, float]
    hit: bool
    t: float | None
    alpha: float | None
    beta: float | None
    gamma: float | None
    point: np.ndarray | None
    reason: str

    def explain(self) -> list[str]:
        """The worked solution, one line of text per step."""
        return explain(self)


def _vec3(name: str, value) -> np.ndarray:
    v = np.asarray(value, dtype=float)
    if v.shape != (3,) or not all(abs(x) <= LIMIT for x in v.tolist()):
        raise ValueError(f"{name} must be three finite numbers of size at most 1e60, got {value!r}")
    return v


def _cross(u, v) -> tuple[float, float, float]:
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def _det3(c0, c1, c2) -> float:
    """Determinant of the 3x3 matrix with columns ``c0, c1, c2`` (triple product)."""
    w = _cross(c1, c2)
    return float(c0[0] * w[0] + c0[1] * w[1] + c0[2] * w[2])


def cramer_solve(origin, direction, a, b, c) -> CramerSolution:
    """Solve ``o + t d = αA + βB + (1 - α - β)C`` for ``α, β, t`` by Cramer's rule.

    This is the lecture's method, in plain floating point (no watertightness).

    Examples
    --------
    >>> s = cramer_solve((0, 0, 0), (1, 1, 1), (3, 0, 0), (0, 3, 0), (0, 0, 3))
    >>> s.det, s.det_alpha, s.det_beta, s.det_t
    (-27.0, -9.0, -9.0, -27.0)
    >>> s.t, round(s.alpha, 12), round(s.beta, 12), round(s.gamma, 12)
    (1.0, 0.333333333333, 0.333333333333, 0.333333333333)
    """
    o, d = _vec3("origin", origin), _vec3("direction", direction)
    return _cramer(o, d, _vec3("a", a), _vec3("b", b), _vec3("c", c))


def _cramer(o, d, A, B, C) -> CramerSolution:
    cols = (A - C, B - C, -d)
    rhs = o - C
    det = _det3(*cols)
    det_alpha = _det3(rhs, cols[1], cols[2])
    det_beta = _det3(cols[0], rhs, cols[2])
    det_t = _det3(cols[0], cols[1], rhs)
    if det == 0:
        alpha = beta = gamma = t = None
    else:
        alpha, beta, t = det_alpha / det, det_beta / det, det_t / det
        gamma = 1.0 - alpha - beta
    return CramerSolution(np.column_stack(cols), rhs, det, det_alpha, det_beta, det_t,
                          alpha, beta, gamma, t)


def _degenerate(A, B, C) -> bool:
    """The vertices are collinear (checked exactly when the float test says so)."""
    if any(_cross(B - A, C - A)):
        return False
    a, b, c = ([Fraction(x) for x in v.tolist()] for v in (A, B, C))
    return not any(_cross([q - p for q, p in zip(b, a, strict=True)],
                          [q - p for q, p in zip(c, a, strict=True)]))


def _edge(p, q) -> float:
    """``p.x q.y - p.y q.x`` with the exact sign; ``_edge(q, p) == -_edge(p, q)`` exactly."""
    left, right = p[0] * q[1], p[1] * q[0]
    value = left - right
    if abs(value) > _EDGE_ERROR * (abs(left) + abs(right)) + _UNDERFLOW:
        return value
    return float(_edge_exact(p, q))


def _edge_exact(p, q) -> Fraction:
    return Fraction(p[0]) * Fraction(q[1]) - Fraction(p[1]) * Fraction(q[0])


def intersect_triangle(origin, direction, a, b, c) -> TriangleIntersection:
    """Cross the ray ``o + t d`` (``t >= 0``) with the triangle ``(A, B, C)``, watertight.

    Parameters
    ----------
    origin, direction : (3,) float, world space
        ``direction`` must not be zero; ``t`` is in units of ``|d|``.
    a, b, c : (3,) float, world space
        The vertices ``A``, ``B``, ``C``; either winding.

    Returns
    -------
    TriangleIntersection
        ``alpha``, ``beta``, ``gamma`` weight ``A``, ``B``, ``C``.

    Raises
    ------
    ValueError
        Non-finite input or a coordinate beyond ``LIMIT`` (1e60), or a
        direction shorter than ``1 / LIMIT``.

    Examples
    --------
    >>> h = intersect_triangle((0.5, 0.25, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 1, 0))
    >>> h.hit, h.t, h.alpha, h.beta, h.gamma
    (True, 1.0, 0.25, 0.5, 0.25)
    """
    o, d = _vec3("origin", origin), _vec3("direction", direction)
    vertices = np.array([_vec3("a", a), _vec3("b", b), _vec3("c", c)])
    if max(abs(x) for x in d.tolist()) < 1 / LIMIT:
        raise ValueError("direction must not be the zero vector (nor shorter than 1e-60)")
    lecture = _cramer(o, d, *vertices)
    A, B, C = vertices

    def result(hit, reason, e=(0.0, 0.0, 0.0), solved=(None, None, None, None)):
        t, alpha, beta, gamma = solved
        point = alpha * A + beta * B + gamma * C if hit else None
        return TriangleIntersection(o, d, vertices, lecture.det, tuple(map(float, e)), hit,
                                    t, alpha, beta, gamma, point, reason)

    if _degenerate(A, B, C):
        return result(False, "degenerate triangle: its vertices are collinear, so it has no plane")

    # Transform the vertices to ray space: translate, permute (largest |d| is z), shear.
    kz = int(np.argmax(np.abs(d)))
    kx, ky = (kz + 1) % 3, (kz + 2) % 3
    dx, dy, dz = float(d[kx]), float(d[ky]), float(d[kz])
    sx, sy, sz = -dx / dz, -dy / dz, 1.0 / dz
    pts = []
    for vertex in vertices:
        rel = vertex - o
        x, y, z = float(rel[kx]), float(rel[ky]), float(rel[kz])
        pts.append((x + sx * z, y + sy * z, z * sz))
    p0, p1, p2 = pts

    # Compute the edge functions (exact sign, exactly antisymmetric).
    e = [_edge(p1, p2), _edge(p2, p0), _edge(p0, p1)]
    z = [p[2] for p in pts]
    if 0.0 in e:  # through an edge or vertex: finish in exact arithmetic
        e = [_edge_exact(p1, p2), _edge_exact(p2, p0), _edge_exact(p0, p1)]
        z = [Fraction(zi) for zi in z]
    det = sum(e)
    solved = (None, None, None, None)
    if det != 0:
        t_scaled = e[0] * z[0] + e[1] * z[1] + e[2] * z[2]
        with contextlib.suppress(OverflowError):  # an exact ratio beyond float64: ~parallel
            solved = tuple(float(x / det) for x in (t_scaled, *e))
    scale = math.hypot(*d) * math.hypot(*(A - C)) * math.hypot(*(B - C))
    parallel = (solved[0] is None or not all(map(math.isfinite, solved))
                or abs(lecture.det) <= PARALLEL_TOLERANCE * scale)

    # Perform the triangle edge and determinant tests.
    if min(e) < 0 < max(e):
        if parallel:
            return result(False, "parallel to the triangle's plane", e)
        outside = [name for name, ei in zip(NAMES, e, strict=True) if ei * det < 0]
        return result(False, "outside: " + " and ".join(f"{n} < 0" for n in outside), e, solved)
    if det == 0 or solved[0] is None:
        return result(False, "parallel to the triangle's plane (the ray lies in it)", e)
    if solved[0] < 0:
        return result(False, "behind the origin: t < 0", e, solved)
    return result(True, "inside: alpha, beta, gamma >= 0 and t >= 0", e, solved)


def _g(x: float) -> str:
    """A number to 6 significant digits, without a ``-0``."""
    text = f"{x:.6g}"
    return "0" if text == "-0" else text


def _vec(v) -> str:
    return "(" + ", ".join(_g(x) for x in v) + ")"


def explain(h: TriangleIntersection) -> list[str]:
    """The worked solution of :class:`TriangleIntersection` ``h``, step by step."""
    A, B, C = h.vertices
    s = cramer_solve(h.origin, h.direction, A, B, C)
    lines = [
        "Crossing a ray with a triangle (barycentric coordinates)",
        f"Ray r(t) = o + t d, o = {_vec(h.origin)}, d = {_vec(h.direction)}, t >= 0",
        f"Triangle A = {_vec(A)}, B = {_vec(B)}, C = {_vec(C)}",
        "A point of the triangle's plane: P = αA + βB + (1 - α - β)C  (γ = 1 - α - β weights C).",
        "It is on the ray when o + t d = αA + βB + (1 - α - β)C, i.e.",
        "  α(A - C) + β(B - C) - t d = o - C, one equation per coordinate:",
    ]
    for k, axis in enumerate("xyz"):
        m = s.matrix[k]
        lines.append(f"  {axis}: ({_g(m[0])})α + ({_g(m[1])})β + ({_g(m[2])})t = {_g(s.rhs[k])}")
    lines.append(f"Determinant det M = det[A - C, B - C, -d] = {_g(s.det)}")
    if s.det == 0:
        lines.append("det M = 0: the ray is parallel to the triangle's plane, no single solution.")
    else:
        lines += [
            "det M != 0, so by Cramer's rule (replace one column by o - C):",
            f"  α = det M_α / det M = {_g(s.det_alpha)} / {_g(s.det)} = {_g(s.alpha)}",
            f"  β = det M_β / det M = {_g(s.det_beta)} / {_g(s.det)} = {_g(s.beta)}",
            f"  t = det M_t / det M = {_g(s.det_t)} / {_g(s.det)} = {_g(s.t)}",
            f"  γ = 1 - α - β = {_g(s.gamma)}",
            "Inside test: P is in the triangle when α >= 0, β >= 0 and γ >= 0,",
            "  and the crossing is on the ray (not behind o) when t >= 0. Here:",
            "  " + ", ".join(f"{n} {'>=' if v >= 0 else '<'} 0"
                             for n, v in zip("αβγt", (s.alpha, s.beta, s.gamma, s.t), strict=True)),
        ]
    e0, e1, e2 = h.edge_functions
    lines += [
        "Watertight check (seen along the ray): edge functions "
        f"e0 = {_g(e0)}, e1 = {_g(e1)}, e2 = {_g(e2)};",
        "  all of one sign (zeros allowed) means inside, exactly consistent for shared edges.",
    ]
    if h.alpha is not None:
        lines.append(f"  α = {_g(h.alpha)}, β = {_g(h.beta)}, γ = {_g(h.gamma)}, t = {_g(h.t)}")
    if h.hit:
        lines.append(f"Hit: {h.reason}; P = αA + βB + γC = o + t d = {_vec(h.point)}")
    else:
        lines.append(f"No hit: {h.reason}.")
    return lines
