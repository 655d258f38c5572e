"""Compiled ray-sphere and ray-triangle crossings for the tracer's hot loops.

The arithmetic is not written here: it is the lecture modules' own
``register_jitable`` functions, compiled in.

- Sphere: :func:`core.image_order.intersect_sphere.sphere_roots`, pbrt's
  stable form (a discriminant without cancellation, roots ``q / a`` and
  ``c / q``).
- Triangle: the watertight test of :mod:`core.image_order.intersect_triangle`
  (Woop, Benthin and Wald, as in pbrt-v4).  The ray is made the +z axis of
  "ray space" (translate, permute, shear) once per ray by
  :func:`~core.image_order.intersect_triangle.ray_shear`;
  each triangle then costs three edge functions with an exact sign.  A ray
  through an edge shared by two triangles hits both, at the same ``t``.

What this module adds is what only the tracer needs: the admissible range of
``t`` and the early way out of a miss.  Rays are ``o + t d`` with ``t`` in
units of ``|d|``; a crossing counts when ``t_min <= t < t_max`` (``t_max`` is
the closest crossing found so far, or the distance to a light).  Misses
return ``t = inf``.
"""

from __future__ import annotations

import math

from core.image_order.intersect_sphere import line_terms
from core.image_order.intersect_sphere import sphere_roots as sphere_formula
from core.image_order.intersect_triangle import crossing, edge_functions, straddles, to_ray_space
from core.image_order.kernels.jit import jit, jit_inline


@jit
def sphere_roots(ox, oy, oz, dx, dy, dz, cx, cy, cz, r):
    """Both crossings ``t_near <= t_far`` of the line ``o + t d`` with a sphere.

    Returns ``(inf, inf)`` when the line misses.
    """
    _, _, _, _, _, _, t_near, t_far = sphere_formula(ox, oy, oz, dx, dy, dz, cx, cy, cz, r)
    return t_near, t_far


@jit_inline
def sphere_hit(ox, oy, oz, dx, dy, dz, cx, cy, cz, r, t_min, t_max):
    """The first crossing with ``t_min <= t < t_max`` of a ray with a sphere, ``inf`` if none.

    A ray that starts outside the sphere and moves away from its centre has both crossings
    behind it: those rays are answered before the roots (:func:`_behind`).

    Inlined into its callers (a sphere's leaf, a shadow ray from inside its sphere): as a call,
    with four of its twelve numbers on the stack and its answer through memory, it was the one
    function of the render that the compiler left on its own, a tenth of the samples of a mirror
    and glass frame (perf); inlined, that frame took 0.93-0.97 of its time (one thread,
    alternating in one process, three runs), the lecture's (no spheres) the same.  The bench's batch
    of shadow rays, which meets no sphere but carries the inlined test in its code, took 1.008-1.024
    of its time on the 100,000- and 1,000,000-triangle balls (five runs); with the packets' sphere
    leaves tested through a call instead, the frame lost all it gained (1.076).
    """
    if _behind(ox, oy, oz, dx, dy, dz, cx, cy, cz, r, t_min):
        return math.inf
    t0, t1 = sphere_roots(ox, oy, oz, dx, dy, dz, cx, cy, cz, r)
    if t_min <= t0 < t_max:
        return t0
    if t_min <= t1 < t_max:
        return t1
    return math.inf


#: Bounds within which :func:`_behind` decides: no quotient of the roots' formula can then
#: round to zero (its numbers lie between ``2^-400`` and ``2^401``).
_SMALLEST, _LARGEST = 2.0**-400, 2.0**400


@jit_inline
def _behind(ox, oy, oz, dx, dy, dz, cx, cy, cz, r, t_min):
    """Whether :func:`sphere_roots` would find no crossing at or after ``t_min >= 0``: the ray starts
    outside the sphere (``c = |f|^2 - r^2 > 0``, ``f = o - centre``) and moves away from its centre
    (``half_b = f . d > 0``), both as the roots' formula rounds them.

    Such are a mirror's reflected ray and a glass ball's ray out, tested against their own
    sphere, and every ray whose sphere lies behind it; they cost no square root or division.
    The answer is that of the roots, exactly: the formula's ``q = -(half_b + sqrt(...))`` is
    then negative, so both roots ``q / a`` and ``c / q`` (or the tangent's ``-half_b / a``) are
    negative, and within the bounds none of them rounds to ``-0.0``, which ``t_min = 0`` would
    let through.
    """
    _, _, _, a, half_b, f2, r2 = line_terms(ox, oy, oz, dx, dy, dz, cx, cy, cz, r)
    return (t_min >= 0.0 and half_b > _SMALLEST and f2 - r2 > _SMALLEST and f2 < _LARGEST and r2 < _LARGEST
            and a < _LARGEST)


@jit_inline
def triangle_hit(o, shear, rows, k, t_min, t_max):
    """Watertight crossing of a ray with the triangle ``rows[k]``.

    Parameters
    ----------
    o : (3,) float64 tuple or array, world space
        Ray origin.
    shear : tuple
        :func:`~core.image_order.intersect_triangle.ray_shear` of the ray direction.
    rows : (n, 9) float64 array, k : int
        Row ``k`` holds the corners ``A, B, C`` one after the other, world space.
    t_min, t_max : float
        Admissible range of ``t``: ``t_min <= t < t_max``.

    Returns
    -------
    (t, b0, b1, b2) : floats
        ``t = inf`` on a miss; ``b0, b1, b2`` weight ``A, B, C`` (the lecture's
        alpha, beta and gamma).
    """
    x0, y0, z0, x1, y1, z1, x2, y2, z2 = to_ray_space(rows, k, o, shear)
    e0, e1, e2 = edge_functions(x0, y0, x1, y1, x2, y2)
    if straddles(e0, e1, e2):
        return math.inf, 0.0, 0.0, 0.0
    _, t, b0, b1, b2 = crossing(e0, e1, e2, x0, y0, z0, x1, y1, z1, x2, y2, z2, shear[5])
    if not t_min <= t < t_max:  # also rejects NaN: the ray is parallel to the triangle
        return math.inf, 0.0, 0.0, 0.0
    return t, b0, b1, b2
