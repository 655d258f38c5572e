"""What light does at a mirror or a glass surface: reflection, Snell's law, Fresnel.

The lecture's ray tracer follows a ray that hits a shiny surface in the
mirror direction ("the angle of reflection is equal to the angle of
incidence"); at a semitransparent surface it splits the ray in a reflected and
a refracted part.  Snell's law gives the refracted direction, the Fresnel
equations give how the light divides between the two.

Conventions
-----------
- Directions are unit 3-vectors (tuples, or arrays of shape (3,)), world space.
- ``d`` is the direction the ray travels, *towards* the surface.
- ``n`` is the unit normal on the side the ray comes from, so ``d . n <= 0``.
- ``cos_i = -d . n`` is the cosine of the angle of incidence ``θ1`` (between
  the ray and the normal), in [0, 1].
- ``n1`` is the index of refraction of the medium the ray comes from, ``n2``
  of the medium it enters; ``eta = n1 / n2``.  Snell's law reads
  ``n1 sin θ1 = n2 sin θ2``.

The functions take plain numbers and tuples.  :func:`~core.compiling.jitable.jitable` leaves
them ordinary Python functions when called from Python and compiles them
into the tracer's kernels (:mod:`core.image_order.kernels.shade`) when called from
there, so the explanations and the renderer run the very same code.
"""

from __future__ import annotations

import math

from core.compiling.jitable import jitable


@jitable
def dot(a, b) -> float:
    """Scalar product of two 3-vectors."""
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


@jitable
def reflect(d, n) -> tuple[float, float, float]:
    """Mirror direction of ``d`` at a surface with unit normal ``n``: ``d - 2 (d . n) n``.

    The angle of reflection equals the angle of incidence, and the reflected
    ray lies in the plane of ``d`` and ``n``.  ``n`` may face either side.

    Examples
    --------
    >>> reflect((1.0, -1.0, 0.0), (0.0, 1.0, 0.0))
    (1.0, 1.0, 0.0)
    """
    k = 2.0 * dot(d, n)
    return d[0] - k * n[0], d[1] - k * n[1], d[2] - k * n[2]


@jitable
def refract(d, n, eta):
    """Direction of the ray refracted by Snell's law, and whether there is one.

    Parameters
    ----------
    d : (3,) unit direction of the incident ray (towards the surface).
    n : (3,) unit normal facing the incident ray (``d . n <= 0``).
    eta : float, ``n1 / n2``.

    Returns
    -------
    (ok, t) : bool and (3,) tuple
        ``t`` is the unit refracted direction ``eta d + (eta cos θ1 - cos θ2) n``
        with ``sin θ2 = eta sin θ1``.  ``ok`` is False, and ``t`` zero, when
        ``sin θ2`` would exceed 1: past the critical angle Snell's law has no
        solution (total internal reflection).  (pbrt's ``Refract`` likewise
        returns a flag; a compiled kernel cannot index an optional tuple.)

    Examples
    --------
    Straight through at normal incidence; bent towards the normal entering glass:

    >>> refract((0.0, -1.0, 0.0), (0.0, 1.0, 0.0), 1 / 1.5)
    (True, (0.0, -1.0, 0.0))
    >>> s = 2 ** -0.5
    >>> ok, (x, y, _) = refract((s, -s, 0.0), (0.0, 1.0, 0.0), 1 / 1.5)
    >>> round(x, 6), round(y, 6)   # sin θ2 = sin 45° / 1.5
    (0.471405, -0.881917)
    >>> refract((0.8, -0.6, 0.0), (0.0, 1.0, 0.0), 1.5)   # from glass, 53° > 41.8°
    (False, (0.0, 0.0, 0.0))
    """
    cos_i = -dot(d, n)
    sin2_t = eta * eta * max(0.0, 1.0 - cos_i * cos_i)
    if sin2_t >= 1.0:
        return False, (0.0, 0.0, 0.0)
    cos_t = math.sqrt(1.0 - sin2_t)
    k = eta * cos_i - cos_t
    return True, (eta * d[0] + k * n[0], eta * d[1] + k * n[1], eta * d[2] + k * n[2])


@jitable
def fresnel_dielectric(cos_i: float, n1: float, n2: float) -> tuple[float, float]:
    """Reflectance and transmittance of unpolarised light at a dielectric boundary.

    The Fresnel equations give the amplitude ratios for light polarised
    perpendicular (s) and parallel (p) to the plane of incidence::

        r_s = (n1 cos θ1 - n2 cos θ2) / (n1 cos θ1 + n2 cos θ2)
        r_p = (n2 cos θ1 - n1 cos θ2) / (n2 cos θ1 + n1 cos θ2)
        t_s = 2 n1 cos θ1 / (n1 cos θ1 + n2 cos θ2)
        t_p = 2 n1 cos θ1 / (n2 cos θ1 + n1 cos θ2)

    Unpolarised light is the average of the two.  The reflected fraction of
    the power is ``R = (r_s² + r_p²) / 2``; the transmitted fraction is
    ``T = (n2 cos θ2) / (n1 cos θ1) (t_s² + t_p²) / 2`` (the factor accounts for
    the change of speed and of beam width).  Energy is conserved: ``R + T = 1``.
    Beyond the critical angle ``R = 1, T = 0`` (total internal reflection).

    Parameters
    ----------
    cos_i : float in [0, 1]
        Cosine of the angle of incidence.
    n1, n2 : float
        Indices of refraction of the incident and the transmitting medium.

    Returns
    -------
    (R, T) : floats in [0, 1]

    Examples
    --------
    Air to glass at normal incidence: ``((1 - 1.5) / (1 + 1.5))² = 0.04``.

    >>> r, t = fresnel_dielectric(1.0, 1.0, 1.5)
    >>> round(r, 12), round(t, 12)
    (0.04, 0.96)
    """
    sin_t = n1 / n2 * math.sqrt(max(0.0, 1.0 - cos_i * cos_i))
    if sin_t >= 1.0 or cos_i <= 0.0:
        return 1.0, 0.0
    cos_t = math.sqrt(1.0 - sin_t * sin_t)
    a_s, b_s = n1 * cos_i, n2 * cos_t
    a_p, b_p = n2 * cos_i, n1 * cos_t
    r_s = (a_s - b_s) / (a_s + b_s)
    r_p = (a_p - b_p) / (a_p + b_p)
    t_s = 2.0 * a_s / (a_s + b_s)
    t_p = 2.0 * a_s / (a_p + b_p)
    reflectance = 0.5 * (r_s * r_s + r_p * r_p)
    transmittance = (b_s / a_s) * 0.5 * (t_s * t_s + t_p * t_p)
    return reflectance, transmittance


def critical_angle_deg(n1: float, n2: float) -> float | None:
    """Angle of incidence beyond which all light is reflected, in degrees.

    Only light going from a denser to a thinner medium (``n1 > n2``) has one:
    ``sin θc = n2 / n1``.  Returns ``None`` otherwise.

    Examples
    --------
    >>> round(critical_angle_deg(1.5, 1.0), 4)   # glass to air
    41.8103
    >>> critical_angle_deg(1.0, 1.5) is None
    True
    """
    if n1 <= n2:
        return None
    return math.degrees(math.asin(n2 / n1))
