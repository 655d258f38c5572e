"""Compiled ray-sphere and ray-triangle crossings for the tracer's hot loops.

These are the numba twins of :func:`core.image_order.intersect_sphere.intersect_sphere`
and :func:`core.image_order.intersect_triangle.intersect_triangle`: the same robust
arithmetic, without the worked-solution record.

- Sphere: pbrt's stable form.  The discriminant is ``a (r + |v|)(r - |v|)``
  with ``|v|`` the distance from the centre to the line (no cancellation), and
  the roots are ``q / a`` and ``c / q`` with ``q = -(b/2 + sign(b) sqrt(Δ/4))``.
- Triangle: the watertight test of Woop, Benthin and Wald as in pbrt-v4.  The
  ray is made the +z axis of "ray space" (translate, permute, shear) once per
  ray by :func:`ray_shear`; each triangle then costs three edge functions.
  Where a rounded edge function is too small to trust, it is recomputed with
  error-free products (Dekker's two-product), so its sign is exact and
  ``e(q, p) == -e(p, q)`` holds exactly: a ray through an edge shared by two
  triangles hits at least one of them.

Rays are ``o + t d`` with ``t`` in units of ``|d|``; a crossing counts when
``t_min <= t < t_max`` (``t_max`` is the closest crossing found so far, or the
distance to a light).  Misses return ``t = inf``.
"""

from __future__ import annotations

import math

from core.image_order.intersect_sphere import TANGENT_TOLERANCE
from core.image_order.kernels.jit import jit, jit_inline

_UNIT_ROUNDOFF = 2.0**-53
#: A rounded ``a*b - c*d`` is trusted when bigger than this times ``|ab| + |cd|``.
EDGE_ERROR = 4 * _UNIT_ROUNDOFF
UNDERFLOW = 2.0**-1070
#: Veltkamp's splitter 2^27 + 1: cuts a double into two halves of 26 bits.
_SPLITTER = 134217729.0


@jit
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


@jit
def difference_of_products(a, b, c, d):
    """``a*b - c*d`` with the exact sign; swapping the products negates it exactly.

    Near zero the rounded difference may have the wrong sign; there the two
    products are formed exactly with :func:`two_product`.  The high parts are
    then within a factor two of each other, so their difference is exact
    (Sterbenz), and adding the difference of the low parts keeps the sign.
    """
    left = a * b
    right = c * d
    value = left - right
    if abs(value) > EDGE_ERROR * (abs(left) + abs(right)) + UNDERFLOW:
        return value
    l_hi, l_lo = two_product(a, b)
    r_hi, r_lo = two_product(c, d)
    return (l_hi - r_hi) + (l_lo - r_lo)


@jit
def sphere_roots(ox, oy, oz, dx, dy, dz, cx, cy, cz, r):
    """Both crossings ``t_near <= t_far`` of the line ``o + t d`` with a sphere.

    Returns ``(inf, inf)`` when the line misses (``|v| > r``).
    """
    fx, fy, fz = ox - cx, oy - cy, oz - cz
    a = dx * dx + dy * dy + dz * dz
    half_b = fx * dx + fy * dy + fz * dz
    c = fx * fx + fy * fy + fz * fz - r * r
    k = half_b / a
    vx, vy, vz = fx - k * dx, fy - k * dy, fz - k * dz
    dist = math.sqrt(vx * vx + vy * vy + vz * vz)
    if abs(dist - r) <= TANGENT_TOLERANCE * (math.sqrt(fx * fx + fy * fy + fz * fz) + r):
        t = -half_b / a
        return t, t
    if dist > r:
        return math.inf, math.inf
    quarter_disc = (4.0 * a * (r + dist) * (r - dist)) / 4.0
    q = -(half_b + math.copysign(math.sqrt(quarter_disc), half_b))
    t0, t1 = q / a, c / q
    if t0 > t1:
        return t1, t0
    return t0, t1


@jit
def sphere_hit(ox, oy, oz, dx, dy, dz, cx, cy, cz, r, t_min, t_max):
    """The first crossing with ``t_min <= t < t_max`` of a ray with a sphere, ``inf`` if none."""
    t0, t1 = sphere_roots(ox, oy, oz, dx, dy, dz, cx, cy, cz, r)
    if t_min <= t0 < t_max:
        return t0
    if t_min <= t1 < t_max:
        return t1
    return math.inf


@jit_inline
def ray_shear(dx, dy, dz):
    """The per-ray constants of the watertight test: ``(kx, ky, kz, sx, sy, sz)``.

    ``kz`` is the axis of the largest ``|d|`` component, ``kx, ky`` the next two
    in cyclic order; the shear ``(sx, sy, sz) = (-d_kx/d_kz, -d_ky/d_kz, 1/d_kz)``
    maps the ray direction to +z.
    """
    ax, ay, az = abs(dx), abs(dy), abs(dz)
    if ax > ay and ax > az:
        kz = 0
    elif ay > az:
        kz = 1
    else:
        kz = 2
    kx = (kz + 1) % 3
    ky = (kx + 1) % 3
    d = (dx, dy, dz)
    return kx, ky, kz, -d[kx] / d[kz], -d[ky] / d[kz], 1.0 / d[kz]


@jit_inline
def triangle_hit(o, shear, rows, k, t_min, t_max):
    """Watertight crossing of a ray with the triangle ``rows[k]``.

    Parameters
    ----------
    o : (3,) float64 tuple or array, world space
        Ray origin.
    shear : tuple
        :func:`ray_shear` of the ray direction.
    rows : (n, 9) float64 array, k : int
        Row ``k`` holds the corners ``A, B, C`` one after the other, world
        space.  (Indexed in place: a row view would cost a reference count
        update per test.)
    t_min, t_max : float
        Admissible range of ``t``: ``t_min <= t < t_max``.

    Returns
    -------
    (t, b0, b1, b2) : floats
        ``t = inf`` on a miss; ``b0, b1, b2`` weight ``A, B, C`` (the lecture's
        alpha, beta and gamma).
    """
    kx, ky, kz, sx, sy, sz = shear
    okx, oky, okz = o[kx], o[ky], o[kz]
    # Transform the vertices to ray space: translate, permute, shear.
    z0 = rows[k, kz] - okz
    z1 = rows[k, 3 + kz] - okz
    z2 = rows[k, 6 + kz] - okz
    x0 = rows[k, kx] - okx + sx * z0
    y0 = rows[k, ky] - oky + sy * z0
    x1 = rows[k, 3 + kx] - okx + sx * z1
    y1 = rows[k, 3 + ky] - oky + sy * z1
    x2 = rows[k, 6 + kx] - okx + sx * z2
    y2 = rows[k, 6 + ky] - oky + sy * z2
    # Compute the edge functions; perform the triangle edge and determinant tests.
    e0 = difference_of_products(x1, y2, y1, x2)
    e1 = difference_of_products(x2, y0, y2, x0)
    e2 = difference_of_products(x0, y1, y0, x1)
    if (e0 < 0.0 or e1 < 0.0 or e2 < 0.0) and (e0 > 0.0 or e1 > 0.0 or e2 > 0.0):
        return math.inf, 0.0, 0.0, 0.0
    det = e0 + e1 + e2
    if det == 0.0:
        return math.inf, 0.0, 0.0, 0.0
    t = (e0 * (z0 * sz) + e1 * (z1 * sz) + e2 * (z2 * sz)) / det
    if not t_min <= t < t_max:  # also rejects NaN
        return math.inf, 0.0, 0.0, 0.0
    return t, e0 / det, e1 / det, e2 / det
