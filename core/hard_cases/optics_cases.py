"""Total internal reflection: a ray inside a glass sphere meets its surface beyond the critical angle.

Snell's law ``n1 sin θ1 = n2 sin θ2`` asks for ``sin θ2 = (n1 / n2) sin θ1``;
going from glass (1.5) to air (1.0) that exceeds 1 past the critical angle
(41.8°), and there is no refracted ray: all light is reflected.  The
textbook refraction formula takes ``cos θ2 = √(1 - sin² θ2)`` regardless and
returns NaN.  The app's :func:`core.image_order.optics.refract` notices that
the radicand is negative and says so; the tracer then follows the mirror
direction (:func:`core.image_order.optics.reflect`) with the whole weight, as
:func:`core.image_order.optics.fresnel_dielectric` gives ``R = 1``.
"""

from __future__ import annotations

import math

import numpy as np

from core.hard_cases.result import DIGITS, U64, CaseResult, Parameter, Row
from core.image_order.optics import critical_angle_deg, fresnel_dielectric, reflect, refract

GLASS, AIR = 1.5, 1.0
#: The outward normal at the point where the ray meets the sphere from inside (a generic direction).
NORMAL = np.array([0.36, 0.48, 0.8])
TANGENT = np.array([0.8, -0.6, 0.0])


def textbook_refract(d, n, eta) -> np.ndarray:
    """``eta d + (eta cos θ1 - √(1 - eta² (1 - cos² θ1))) n`` with no check of the radicand.

    ``n`` faces the incoming ray (``d·n < 0``).  Past the critical angle the
    square root of a negative number is NaN, and so is every component.
    """
    d, n = np.asarray(d, float), np.asarray(n, float)
    cos_i = -float(d @ n)
    with np.errstate(invalid="ignore"):
        cos_t = np.sqrt(np.float64(1.0 - eta * eta * (1.0 - cos_i * cos_i)))
    return eta * d + (eta * cos_i - cos_t) * n


def _exact(d, n, eta):
    """In mpmath: ``(total, direction, R)``, the continuing direction and the reflected fraction."""
    import mpmath  # loaded when a case is computed, not with the window

    with mpmath.workdps(DIGITS):
        d = [mpmath.mpf(float(x)) for x in d]
        n = [mpmath.mpf(float(x)) for x in n]
        e = mpmath.mpf(eta)
        cos_i = -mpmath.fsum(a * b for a, b in zip(d, n, strict=True))
        sin2_t = e * e * (1 - cos_i * cos_i)
        if sin2_t >= 1:
            return True, [a - 2 * (-cos_i) * b for a, b in zip(d, n, strict=True)], mpmath.mpf(1)
        cos_t = mpmath.sqrt(1 - sin2_t)
        n1, n2 = mpmath.mpf(GLASS), mpmath.mpf(AIR)
        rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t)
        rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t)
        direction = [e * a + (e * cos_i - cos_t) * b for a, b in zip(d, n, strict=True)]
        return False, direction, (rs * rs + rp * rp) / 2


def _distance(computed, reference) -> float:
    """``|computed - reference|`` of two directions (about the angle between them, radians)."""
    import mpmath  # loaded when a case is computed, not with the window

    if not all(math.isfinite(float(x)) for x in computed):
        return math.nan
    with mpmath.workdps(DIGITS):
        return float(mpmath.sqrt(mpmath.fsum((mpmath.mpf(float(a)) - b) ** 2
                                            for a, b in zip(computed, reference, strict=True))))


def _vec(v) -> str:
    return "(" + ", ".join(f"{float(x):.6g}" for x in v) + ")"


def total_internal_reflection(angle_deg: float = 60.0) -> CaseResult:
    """A ray inside a glass sphere reaching its surface at ``angle_deg`` from the normal.

    Parameters
    ----------
    angle_deg : float in [0, 90), angle of incidence in degrees.
    """
    import mpmath  # loaded when a case is computed, not with the window

    normal = NORMAL / np.linalg.norm(NORMAL)
    tangent = TANGENT / np.linalg.norm(TANGENT)
    a = math.radians(angle_deg)
    d = math.cos(a) * normal + math.sin(a) * tangent  # travelling outwards, towards the surface
    facing = -normal  # the normal on the ray's side (inside the glass)
    eta = GLASS / AIR
    naive = textbook_refract(d, facing, eta)
    ok, refracted = refract(tuple(d), tuple(facing), eta)
    robust = np.array(refracted if ok else reflect(tuple(d), tuple(facing)))
    cos_i = float(-(d @ facing))
    reflectance, _ = fresnel_dielectric(cos_i, GLASS, AIR)
    total, exact_dir, exact_r = _exact(d, facing, eta)
    radicand = 1.0 - eta * eta * (1.0 - cos_i * cos_i)
    errors = (_distance(naive, exact_dir), _distance(robust, exact_dir))
    naive_kind = "NaN" if np.isnan(naive).any() else "refracted"
    rows = (
        Row("the ray that continues", naive_kind, "refracted" if ok else "reflected (total)",
            "reflected (total)" if total else "refracted"),
        Row("1 - sin² θ2 (the radicand)", radicand, radicand,
            float(1 - eta**2 * (1 - mpmath.mpf(cos_i) ** 2))),
        Row("its direction", _vec(naive), _vec(robust), _vec(exact_dir)),
        Row("direction error", errors[0], errors[1], 0.0, compare=False),
        Row("reflected fraction R (Fresnel)", None, reflectance, float(exact_r)),
    )
    return CaseResult(
        name="total_reflection", title="8. Total internal reflection inside a glass sphere",
        parameter=Parameter("angle_deg", f"angle of incidence (degrees); critical angle "
                            f"{critical_angle_deg(GLASS, AIR):.2f}°", angle_deg, 0.0, 89.0, log=False),
        naive_method="Snell's formula with √ of the radicand", robust_method="refract, else reflect",
        reference_method="mpmath, 50 digits",
        rows=rows, naive_error=errors[0], robust_error=errors[1], error_unit="direction error (radians)",
        tolerance=16 * U64, tolerance_reason="a few units of rounding of each unit-vector component",
        explanation=(
            "Leaving glass past the critical angle, Snell's law would need sin θ2 > 1: the radicand "
            "1 - sin² θ2 is negative, its square root is NaN, and a NaN direction poisons everything "
            "traced after it (a black or garbage pixel). The robust code checks the radicand first: "
            "when it is negative there is no refracted ray, Fresnel's R is 1, and the ray continues in "
            "the mirror direction with all its light."
        ),
    )
