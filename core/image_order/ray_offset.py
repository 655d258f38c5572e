"""Where a secondary ray starts: off the surface it leaves, by an amount that scales.

A shadow, reflected or refracted ray starts at a hit point.  The computed hit
point is a little off the true surface (rounding), so the new ray may "hit"
the very surface it leaves at a tiny ``t``: dark speckles appear on lit
surfaces (*shadow acne*) and mirrors reflect themselves.

Two remedies, selectable per render (``TraceSettings.offset``):

``"fixed"`` (Ray Tracing in One Weekend)
    The hit point is ``o + t d`` and the new ray ignores crossings closer than
    a fixed ``epsilon`` (default ``1e-4`` scene units).  Simple, but the right
    epsilon depends on the scene's scale: the rounding error of a point grows
    with its distance from the origin, so an epsilon that works near the origin
    fails far from it, and a large one skips real nearby geometry.  Set it to
    0 to see acne.

``"scaled"`` (pbrt's ``OffsetRayOrigin``, the default)
    The hit point is recomputed from the surface itself (barycentric
    combination of the triangle's corners, or projected back onto the sphere),
    so its error is bounded by a few units of rounding of the coordinates
    involved.  The new ray's origin is then pushed along the surface normal,
    to the side the ray leaves on, by :func:`error_bound`: ``ERROR_ULPS``
    units of rounding (``2^-53``) of the largest coordinate magnitude of the
    surface (the triangle's corners, or the sphere's centre plus its radius).
    The offset grows with the coordinates, so it works at any distance from the
    origin, and it stays far below anything visible (``3e-10`` for coordinates
    of ``10^4``).

Both functions are compiled into the tracer's kernels where those call them
(:func:`~core.compiling.jitable.jitable`, as in :mod:`core.image_order.optics`).
"""

from __future__ import annotations

from core.compiling.jitable import jitable

#: Unit roundoff of float64.
UNIT_ROUNDOFF = 2.0**-53

#: How many units of rounding of the largest coordinate the origin is pushed.
#: A triangle's barycentric point is within 7 of them (pbrt's gamma(7)); the
#: rest is margin for the error of the intersection test run from the new origin.
ERROR_ULPS = 256.0


@jitable
def error_bound(magnitude: float) -> float:
    """Distance to push a ray origin off a surface whose coordinates reach ``magnitude``.

    Examples
    --------
    >>> error_bound(1e4) < 1e-9
    True
    """
    return ERROR_ULPS * UNIT_ROUNDOFF * magnitude


@jitable
def offset_ray_origin(p, n, error: float, w) -> tuple[float, float, float]:
    """``p`` moved by ``error`` along the unit normal ``n``, to the side ``w`` points to.

    Parameters
    ----------
    p : (3,) hit point on the surface, world space.
    n : (3,) unit surface normal (either side).
    error : float, >= 0, the distance to move (:func:`error_bound`).
    w : (3,) direction of the new ray.

    Examples
    --------
    >>> offset_ray_origin((0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 0.5, (1.0, -1.0, 0.0))
    (0.0, -0.5, 0.0)
    """
    if w[0] * n[0] + w[1] * n[1] + w[2] * n[2] < 0.0:
        error = -error
    return p[0] + error * n[0], p[1] + error * n[1], p[2] + error * n[2]
