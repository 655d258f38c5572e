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
the ray's largest direction component is z (:func:`ray_shear`), shear so the
ray becomes the +z axis, and look at the triangle from along the ray in 2D
(:func:`to_ray_space`).  The edge functions ``e0, e1, e2``
(:func:`edge_functions`: twice the signed areas of the triangles the ray
makes with each edge) are computed so that

- an edge evaluated from its other end gives exactly the negated value (a
  ray is on exactly one side of a shared edge), and
- their sign is exact: when the rounded value is too small to trust, it is
  recomputed with error-free products (:func:`difference_of_products`).

The ray hits when the three values have the same sign, zeros included
(:func:`straddles` says when they do not), and do not all vanish.  Then
``α = e0 / (e0 + e1 + e2)`` and so on, and ``t`` follows the same way
(:func:`crossing`).

Tie rules
---------
- *Axis*: when two direction components are equal in size, the later axis
  becomes z (z before y before x, as pbrt's ``MaxComponentIndex``): for
  ``d = (1, 1, 0)`` and ``(1, -1, 0)`` it is y, for ``(1, 1, 1)`` it is z.
  Any axis with ``d_k != 0`` would do; this one is fixed so that the
  explanation and the tracer always look at a triangle the same way.
- *Shared edge*: triangles are closed (their edges and corners belong to
  them), so a ray through the inside of an edge shared by two triangles that
  lie on either side of it hits *both*, and a ray through a shared corner
  hits every triangle around it.  Proof: the shared edge's function is
  exactly ``0`` in both (exact sign, exact antisymmetry), and each
  triangle's other two edge functions are the ray's barycentric weights of
  that triangle's two ends of the edge times its determinant, so they share
  its sign.  There ``t`` and the weights come from the edge alone (see
  :func:`crossing`), so both triangles report the very same ``t`` and point,
  bit for bit.  The tracer's closest-hit search keeps the first of equal
  crossings it meets.

These functions are :func:`~core.compiling.jitable.jitable`: plain Python when
:func:`intersect_triangle` calls them for the worked solution, compiled into
the tracer (:mod:`core.image_order.kernels.intersect`) when a kernel calls
them, so both compute every crossing with the same operations.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from fractions import Fraction

import numpy as np

from core.compiling.jitable import jitable
from core.image_order.flat_layout import ROW_A, ROW_B, ROW_C
from core.shown_numbers import shown_number as _g
from core.shown_numbers import shown_vector as _vec

_UNIT_ROUNDOFF = 2.0**-53
#: A rounded ``p*q - r*s`` is trusted when bigger than this times ``|pq| + |rs|``
#: (the true error bound is below 3 unit roundoffs); the tiny absolute term
#: covers products that underflow.
EDGE_ERROR = 4 * _UNIT_ROUNDOFF
UNDERFLOW = 2.0**-1070
#: Veltkamp's splitter 2^27 + 1: cuts a double into two halves of 26 bits.
_SPLITTER = 134217729.0
#: Coordinates may be at most this big and ``|d|`` at least its inverse, so that
#: no product below over- or underflows.
LIMIT = 1e60
#: ``|det M|`` below this times ``|d| |A - C| |B - C|`` counts as parallel.
PARALLEL_TOLERANCE = 1e-12

NAMES = ("alpha", "beta", "gamma")


@jitable
def two_product(a, b):
    """``a * b`` as an unevaluated sum ``p + e`` that is exact (Dekker, 1971)."""
    p = a * b
    s = _SPLITTER * a
    a_hi = s - (s - a)
    a_lo = a - a_hi
    s = _SPLITTER * b
    b_hi = s - (s - b)
    b_lo = b - b_hi
    e = ((a_hi * b_hi - p) + a_hi * b_lo + a_lo * b_hi) + a_lo * b_lo
    return p, e


@jitable
def difference_of_products(a, b, c, d):
    """``a*b - c*d`` with the exact sign; swapping the products negates it exactly.

    Near zero the rounded difference may have the wrong sign; there the two
    products are formed exactly with :func:`two_product`.  The high parts are
    then within a factor two of each other, so their difference is exact
    (Sterbenz), and adding the difference of the low parts keeps the sign.
    An exact zero stays ``0.0``.
    """
    left = a * b
    right = c * d
    value = left - right
    if abs(value) > EDGE_ERROR * (abs(left) + abs(right)) + UNDERFLOW:
        return value
    l_hi, l_lo = two_product(a, b)
    r_hi, r_lo = two_product(c, d)
    return (l_hi - r_hi) + (l_lo - r_lo)


@jitable(forceinline=True)
def ray_shear(dx, dy, dz):
    """The per-ray constants of the watertight test: ``(kx, ky, kz, sx, sy, sz)``.

    ``kz`` is the axis of the largest ``|d|`` component (on a tie the later
    axis: z before y before x), ``kx, ky`` the next two in cyclic order; the
    shear ``(sx, sy, sz) = (-d_kx/d_kz, -d_ky/d_kz, 1/d_kz)`` maps the ray
    direction to +z.

    Examples
    --------
    >>> ray_shear(1.0, 1.0, 0.0)[:3], ray_shear(1.0, 1.0, 1.0)[:3]
    ((2, 0, 1), (0, 1, 2))
    """
    ax, ay, az = abs(dx), abs(dy), abs(dz)
    # x only when strictly the largest, else y when strictly larger than z, else z.  (Written
    # without branches: numba's inliner mislays a variable assigned on several branches.)
    x_largest = (ax > ay) & (ax > az)
    y_largest = (ay > az) & (ax <= ay)
    kz = 2 - 1 * y_largest - 2 * x_largest
    # (kz + 1) % 3 without the remainder, whose integer division made the compiler judge a loop
    # making a packet's rays not worth four rays per vector instruction
    kx = kz + 1 - 3 * (kz == 2)
    ky = kx + 1 - 3 * (kx == 2)
    d_kx, d_ky, d_kz = on_shear_axes(dx, dy, dz, kz)
    return kx, ky, kz, -d_kx / d_kz, -d_ky / d_kz, 1.0 / d_kz


@jitable(forceinline=True)
def on_shear_axes(x, y, z, kz):
    """The point or vector ``(x, y, z)`` on the axes ``kx, ky, kz`` of :func:`ray_shear`.

    Picked by comparisons, not by indexing a tuple: compiled in a loop over a packet's
    rays (:mod:`core.image_order.kernels.bvh_packet`), comparisons become vector selects and
    the loop runs four rays per instruction, where an index would leave it one ray at a time.

    Examples
    --------
    >>> on_shear_axes(1.0, 2.0, 3.0, 0), on_shear_axes(1.0, 2.0, 3.0, 2)
    ((2.0, 3.0, 1.0), (1.0, 2.0, 3.0))
    """
    return ((y if kz == 0 else z if kz == 1 else x),
            (z if kz == 0 else x if kz == 1 else y),
            (x if kz == 0 else y if kz == 1 else z))


@jitable(forceinline=True)
def to_ray_space(rows, k, o, shear):
    """The corners of triangle ``rows[k]`` seen from along the ray: translate, permute, shear.

    Parameters
    ----------
    rows : (n, 9) float64 array, k : int
        Row ``k`` holds the corners ``A, B, C`` one after the other, world
        space.  (Indexed in place: in the kernels a row view would cost a
        reference count update per test.)
    o : (3,) float tuple, world space, the ray origin.
    shear : the ray's :func:`ray_shear`.

    Returns
    -------
    (x0, y0, z0, x1, y1, z1, x2, y2, z2) : floats
        Corner ``i`` in ray space, where the ray is the +z axis from the
        origin; ``z`` is not yet scaled by ``sz`` (``t = z * sz`` on the ray).
    """
    kx, ky, kz, sx, sy, _ = shear
    okx, oky, okz = o[kx], o[ky], o[kz]
    z0 = rows[k, ROW_A + kz] - okz
    z1 = rows[k, ROW_B + kz] - okz
    z2 = rows[k, ROW_C + kz] - okz
    x0 = rows[k, ROW_A + kx] - okx + sx * z0
    y0 = rows[k, ROW_A + ky] - oky + sy * z0
    x1 = rows[k, ROW_B + kx] - okx + sx * z1
    y1 = rows[k, ROW_B + ky] - oky + sy * z1
    x2 = rows[k, ROW_C + kx] - okx + sx * z2
    y2 = rows[k, ROW_C + ky] - oky + sy * z2
    return x0, y0, z0, x1, y1, z1, x2, y2, z2


@jitable(forceinline=True)
def barycentric_point(rows, k, b0, b1, b2):
    """The point ``b0 A + b1 B + b2 C`` of triangle ``rows[k]`` (as :func:`to_ray_space`), world space."""
    return (b0 * rows[k, ROW_A] + b1 * rows[k, ROW_B] + b2 * rows[k, ROW_C],
            b0 * rows[k, ROW_A + 1] + b1 * rows[k, ROW_B + 1] + b2 * rows[k, ROW_C + 1],
            b0 * rows[k, ROW_A + 2] + b1 * rows[k, ROW_B + 2] + b2 * rows[k, ROW_C + 2])


@jitable(forceinline=True)
def edge_functions(x0, y0, x1, y1, x2, y2):
    """``(e0, e1, e2)``: the edge functions of edges BC, CA, AB at the ray (the 2D origin).

    ``e0 = x1 y2 - y1 x2`` and cyclically, each with the exact sign
    (:func:`difference_of_products`); ``e0`` is the weight of corner A times
    ``e0 + e1 + e2``.
    """
    e0 = difference_of_products(x1, y2, y1, x2)
    e1 = difference_of_products(x2, y0, y2, x0)
    e2 = difference_of_products(x0, y1, y0, x1)
    return e0, e1, e2


@jitable(forceinline=True)
def straddles(e0, e1, e2):
    """The edge functions have mixed signs: the ray passes outside the triangle."""
    negative = (e0 < 0.0) | (e1 < 0.0) | (e2 < 0.0)
    positive = (e0 > 0.0) | (e1 > 0.0) | (e2 > 0.0)
    return negative & positive


@jitable(forceinline=True)
def plane_crossing(e0, e1, e2, z0, z1, z2, sz):
    """``(det, t, b0, b1, b2)`` where the ray meets the triangle's plane, from the edge functions.

    ``det = e0 + e1 + e2``; ``b_i = e_i / det`` weights corner ``i`` and ``t``
    is the same mix of the corners' ``z * sz``.  ``det == 0`` (the ray is
    parallel to the plane, or lies in it) gives NaN for the rest.
    """
    det = e0 + e1 + e2
    if det == 0.0:
        return det, math.nan, math.nan, math.nan, math.nan
    t = (e0 * (z0 * sz) + e1 * (z1 * sz) + e2 * (z2 * sz)) / det
    return det, t, e0 / det, e1 / det, e2 / det


@jitable(forceinline=True)
def crossing(e0, e1, e2, x0, y0, z0, x1, y1, z1, x2, y2, z2, sz):
    """``(det, t, b0, b1, b2)`` of a ray that does not straddle the triangle.

    As :func:`plane_crossing`, except where the ray passes exactly through an
    edge or a corner (an edge function is exactly 0).  There the crossing is
    computed from that edge alone, symmetrically in its two ends, so that the
    neighbouring triangle sharing the edge gets the very same ``t`` and weights:

    - corner ``i`` (two edge functions are 0): ``t = z_i sz``, weight 1;
    - edge from corner ``j`` to ``k``: with ``n_i = |x_i| + |y_i|``, the
      distance of corner ``i`` from the ray in ray space (L1), the weights are
      ``n_k / (n_j + n_k)`` for ``j`` and ``n_j / (n_j + n_k)`` for ``k``.
    """
    if (e0 != 0.0 and e1 != 0.0 and e2 != 0.0) or e0 + e1 + e2 == 0.0:
        return plane_crossing(e0, e1, e2, z0, z1, z2, sz)
    return _through_edge_or_corner(e0, e1, e2, x0, y0, z0, x1, y1, z1, x2, y2, z2, sz)


# The rare case stays out of line, so that the tracer's hot loops stay small.
@jitable(error_model="numpy")
def _through_edge_or_corner(e0, e1, e2, x0, y0, z0, x1, y1, z1, x2, y2, z2, sz):
    """:func:`crossing` where an edge function is exactly 0 (and ``e0 + e1 + e2 != 0``)."""
    det = e0 + e1 + e2
    if e1 == 0.0 and e2 == 0.0:
        return det, z0 * sz, 1.0, 0.0, 0.0
    if e2 == 0.0 and e0 == 0.0:
        return det, z1 * sz, 0.0, 1.0, 0.0
    if e0 == 0.0 and e1 == 0.0:
        return det, z2 * sz, 0.0, 0.0, 1.0
    n0, n1, n2 = abs(x0) + abs(y0), abs(x1) + abs(y1), abs(x2) + abs(y2)
    if e0 == 0.0:  # on edge BC
        s = n1 + n2
        return det, (n2 * (z1 * sz) + n1 * (z2 * sz)) / s, 0.0, n2 / s, n1 / s
    if e1 == 0.0:  # on edge CA
        s = n2 + n0
        return det, (n0 * (z2 * sz) + n2 * (z0 * sz)) / s, n2 / s, 0.0, n0 / s
    s = n0 + n1  # on edge AB
    return det, (n1 * (z0 * sz) + n0 * (z1 * sz)) / s, n1 / s, n0 / s, 0.0


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

    rows = vertices.reshape(1, 9)

    def result(hit, reason, e=(0.0, 0.0, 0.0), solved=(None, None, None, None)):
        t, alpha, beta, gamma = solved
        point = np.array(barycentric_point(rows, 0, alpha, beta, gamma)) if hit else None
        return TriangleIntersection(o, d, vertices, lecture.det, tuple(map(float, e)), hit,
                                    t, alpha, beta, gamma, point, reason)

    if _degenerate(A, B, C):
        return result(False, "degenerate triangle: its vertices are collinear, so it has no plane")

    # The watertight test, with the tracer's own functions: ray space, edge functions, crossing.
    shear = ray_shear(*d.tolist())
    x0, y0, z0, x1, y1, z1, x2, y2, z2 = (
        float(v) for v in to_ray_space(rows, 0, tuple(o.tolist()), shear))
    e = edge_functions(x0, y0, x1, y1, x2, y2)
    outside = straddles(*e)
    if outside:  # where the ray meets the plane, to say which weights are negative
        det, *solved = plane_crossing(*e, z0, z1, z2, shear[5])
    else:
        det, *solved = crossing(*e, x0, y0, z0, x1, y1, z1, x2, y2, z2, shear[5])
    if det == 0.0 or not all(map(math.isfinite, solved)):  # no crossing, or one beyond float64
        solved = (None, None, None, None)
    scale = math.hypot(*d) * math.hypot(*(A - C)) * math.hypot(*(B - C))
    parallel = solved[0] is None or abs(lecture.det) <= PARALLEL_TOLERANCE * scale

    # Perform the triangle edge and determinant tests.
    if outside:
        if parallel:
            return result(False, "parallel to the triangle's plane", e)
        negative = [name for name, ei in zip(NAMES, e, strict=True) if ei * det < 0]
        return result(False, "outside: " + " and ".join(f"{n} < 0" for n in negative), e, solved)
    if solved[0] is None:
        return result(False, "parallel to the triangle's plane (the ray lies in it)", e)
    if solved[0] < 0:
        return result(False, "behind the origin: t < 0", e, solved)
    return result(True, "inside: alpha, beta, gamma >= 0 and t >= 0", e, solved)


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
