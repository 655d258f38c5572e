"""Hard cases of crossing a ray with a sphere: tangent rays, the lecture's segment, a far sphere.

The textbook solution substitutes the ray into the sphere equation, forms
``Δ = b² - 4ac`` and takes ``(-b - √Δ) / 2a`` as the first crossing.  Each
case below puts that next to the app's
:func:`core.image_order.intersect_sphere.intersect_sphere` (pbrt's
cancellation-free ``Δ = 4a(r + |v|)(r - |v|)``, stable roots, the segment's
limits) and next to the exact answer for the very same floating-point inputs,
computed in rational arithmetic (:class:`fractions.Fraction`) or with mpmath
at 50 digits.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from core.hard_cases.result import DIGITS, U64, CaseResult, Parameter, Row, digits_correct, relative_error
from core.image_order.intersect_sphere import (
    TANGENT_TOLERANCE,
    intersect_sphere,
    intersect_sphere_segment,
)
from core.image_order.optics import dot

VERDICT = "wrong verdicts"


def textbook_discriminant(origin, direction, center, radius, dtype=np.float64):
    """The textbook ``Δ = b² - 4ac`` in ``dtype`` (float64 or float32), and ``a, b, c``.

    ``a = d·d``, ``b = 2 (o - centre)·d``, ``c = |o - centre|² - r²``: both
    ``b²`` and ``4ac`` grow like the squared distance to the sphere, so their
    difference loses that many digits.  Each product and sum is rounded in turn, as
    the formula is written (``@`` would hand the dot products to BLAS, whose fused and
    reordered sums differ between builds, and the lab's numbers with them).
    """
    o, d, ctr = (np.asarray(v, dtype=dtype) for v in (origin, direction, center))
    r = dtype(radius)
    f = o - ctr
    a = dot(d, d)
    b = dtype(2) * dot(f, d)
    c = dot(f, f) - r * r
    return b * b - dtype(4) * a * c, a, b, c


def textbook_classify(disc: float) -> str:
    """The sign of Δ read literally: < 0 misses, exactly 0 tangent, > 0 crosses."""
    return "misses" if disc < 0 else "tangent" if disc == 0 else "crosses"


def _fractions(*vectors):
    return [[Fraction(float(x)) for x in v] for v in vectors]


def _dot(p, q):
    return sum((x * y for x, y in zip(p, q, strict=True)), Fraction(0))


def exact_discriminant(origin, direction, center, radius) -> Fraction:
    """``b² - 4ac`` of the given floats, in exact rational arithmetic."""
    o, d, ctr = _fractions(origin, direction, center)
    r = Fraction(float(radius))
    f = [p - q for p, q in zip(o, ctr, strict=True)]
    a, b, c = _dot(d, d), 2 * _dot(f, d), _dot(f, f) - r * r
    return b * b - 4 * a * c


def exact_classify(origin, direction, center, radius) -> str:
    """Misses / tangent / crosses of the given floats, decided exactly.

    "Tangent" means the line's distance ``|v|`` from the centre is within the
    rounding of computing it, ``TANGENT_TOLERANCE (|f| + r)``, of ``r`` (the
    stated meaning of a touching ray); outside that band the exact sign of
    ``r² - |v|²`` decides.  ``|v|²`` and the band's ends are compared squared,
    so nothing is rounded.
    """
    o, d, ctr = _fractions(origin, direction, center)
    r = Fraction(float(radius))
    f = [p - q for p, q in zip(o, ctr, strict=True)]
    v2 = _dot(f, f) - _dot(f, d) ** 2 / _dot(d, d)
    band = Fraction(TANGENT_TOLERANCE) * (Fraction(math.sqrt(float(_dot(f, f)))) + r)
    low, high = max(r - band, Fraction(0)), r + band
    if low * low <= v2 <= high * high:
        return "tangent"
    return "misses" if v2 > r * r else "crosses"


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


TANGENT_CENTER = (1.3, -0.7, 2.9)
TANGENT_DIRECTION = _unit((0.48, 0.6, -0.64))
TANGENT_BACK = 1234.5


def tangent_rays(offset: float = 3e-11) -> CaseResult:
    """A ray tangent to a unit sphere from 1234.5 radii away, and two rays ``offset`` radii off it.

    Parameters
    ----------
    offset : float > 0
        How far (in radii) the other two rays pass outside and inside the
        tangent one.
    """
    center, r = np.array(TANGENT_CENTER), 1.0
    d = TANGENT_DIRECTION
    side = _unit(np.cross(d, (0.0, 0.0, 1.0)))
    rows, verdicts, wrong_naive, wrong_robust = [], ([], [], []), 0, 0
    apart = 0.0  # the largest |Δ| of the two rays off the tangent one, exactly
    for name, s in (("outside by offset", 1.0), ("tangent", 0.0), ("inside by offset", -1.0)):
        o = center - TANGENT_BACK * d + r * (1.0 + s * offset) * side
        naive_disc, _, b, _ = textbook_discriminant(o, d, center, r)
        robust = intersect_sphere(o, d, center, r)
        truth = exact_classify(o, d, center, r)
        naive_verdict = textbook_classify(naive_disc)
        wrong_naive += naive_verdict != truth
        wrong_robust += robust.classification != truth
        for column, verdict in zip(verdicts, (naive_verdict, robust.classification, truth), strict=True):
            column.append(verdict)
        exact = float(exact_discriminant(o, d, center, r))
        apart = max(apart, abs(exact)) if s else apart
        rows += [Row(f"ray {name}: verdict", naive_verdict, robust.classification, truth),
                 Row(f"ray {name}: Δ", float(naive_disc), robust.discriminant, exact)]
    square = float(b * b)
    rounding = float(np.spacing(square))  # one unit of rounding of b² (and of 4ac, as large)
    called = ", ".join(verdicts[0])
    if set(verdicts[2]) == {"tangent"}:
        told = (f"their Δ is at most {apart:.1g}, so close that the exact reference calls all three tangent "
                f"too (within the rounding of |v|), and b² - 4ac calls them {called}")
    elif apart < rounding:
        told = (f"their Δ, at most {apart:.1g}, is smaller than that: what b² - 4ac keeps is rounding, not "
                f"Δ, and here it calls them {called}, {wrong_naive} of 3 wrong")
    else:
        told = (f"their Δ, about {apart:.1g}, is larger than that, so at this offset b² - 4ac still tells "
                f"them apart; slide the offset below about {rounding / 8:.0e} radii to see it fail")
    return CaseResult(
        name="tangent", title="1. Tangent ray: misses, touches or crosses?",
        parameter=Parameter("offset", "offset of the other two rays from the tangent one (radii)",
                            offset, 1e-13, 1e-6),
        naive_method="sign of b² - 4ac (float64)",
        robust_method="intersect_sphere: |v| against r",
        reference_method="exact rationals of the same inputs",
        rows=(Row("verdicts: outside, tangent, inside", *(", ".join(v) for v in verdicts)), *rows),
        naive_error=float(wrong_naive), robust_error=float(wrong_robust),
        error_unit=VERDICT, tolerance=0.0, tolerance_reason="a verdict is right or wrong",
        explanation=(
            f"Seen from {TANGENT_BACK:g} radii away, b² and 4ac are both about {square:.2g} and each is "
            f"rounded in steps of {rounding:.1g}, while the two rays {offset:.1g} radii off the tangent one "
            f"change Δ by about 8 times that offset: {told}. The robust test compares the distance |v| "
            "from the centre to the line with r directly, so nothing large cancels, and it calls a ray "
            "tangent only within the rounding error of |v|."
        ),
    )


LECTURE = ((2.0, 1.0, 2.0), (10.0, 6.0, 6.0), (6.0, 4.0, 6.0), 10.0)


def textbook_segment(start, end, center, radius):
    """The textbook reading: Δ > 0 means a crossing, at the smaller root ``(-b - √Δ) / 2a``."""
    d = np.subtract(end, start, dtype=float)
    disc, a, b, _ = textbook_discriminant(start, d, center, radius)
    if disc < 0:
        return disc, None, None
    root = math.sqrt(disc)
    return disc, (-b - root) / (2 * a), (-b + root) / (2 * a)


def lecture_segment() -> CaseResult:
    """The lecture's exercise: segment (2,1,2)→(10,6,6), sphere at (6,4,6) with r = 10."""
    import mpmath  # loaded when a case is computed, not with the window

    start, end, center, r = LECTURE
    disc, t0, t1 = textbook_segment(start, end, center, r)
    robust = intersect_sphere_segment(start, end, center, r)
    with mpmath.workdps(DIGITS):
        d = [mpmath.mpf(e) - mpmath.mpf(s) for s, e in zip(start, end, strict=True)]
        f = [mpmath.mpf(s) - mpmath.mpf(c) for s, c in zip(start, center, strict=True)]
        a = mpmath.fsum(x * x for x in d)
        b = 2 * mpmath.fsum(x * y for x, y in zip(f, d, strict=True))
        c = mpmath.fsum(x * x for x in f) - mpmath.mpf(r) ** 2
        delta = b * b - 4 * a * c
        roots = sorted(((-b - mpmath.sqrt(delta)) / (2 * a), (-b + mpmath.sqrt(delta)) / (2 * a)))
        exact_hit = any(0 <= t <= 1 for t in roots)
    naive_verdict = f"crosses at t = {t0:.4f}" if t0 is not None else "no crossing"
    robust_verdict = f"crosses at t = {robust.t:.4f}" if robust.hit else "no crossing"
    exact_verdict = "no crossing" if not exact_hit else "crosses"
    rows = (
        Row("first crossing in 0 <= t <= 1", naive_verdict, robust_verdict, exact_verdict),
        Row("Δ = b² - 4ac", float(disc), robust.discriminant, float(delta)),
        Row("t_near", float(t0), robust.t_near, float(roots[0])),
        Row("t_far", float(t1), robust.t_far, float(roots[1])),
    )
    return CaseResult(
        name="lecture_segment", title="2. The lecture's exercise: both ends inside the sphere",
        parameter=None,
        naive_method="Δ > 0, so take (-b - √Δ) / 2a",
        robust_method="intersect_sphere_segment: roots checked against [0, 1]",
        reference_method="mpmath, 50 digits",
        rows=rows, naive_error=float(naive_verdict.startswith("crosses") != exact_hit),
        robust_error=float(robust.hit != exact_hit), error_unit=VERDICT, tolerance=0.0,
        tolerance_reason="a verdict is right or wrong",
        explanation=(
            "Δ > 0 only says that the infinite line crosses the sphere. Here both ends of the segment "
            "lie inside it (c < 0), so the roots are t ≈ -0.36, behind the start, and t ≈ 1.56, past "
            "the end: the textbook's 'first crossing' at t = -0.36 is not on the segment at all. The "
            "robust solver keeps only roots in 0 <= t <= 1 and says why there is none."
        ),
    )


FAR_DIRECTION = _unit((0.37, 0.81, -0.45))
FAR_ORIGIN = np.array([0.1, -0.2, 0.3])


def _pbrt_discriminant_float32(origin, direction, center, radius) -> float:
    """The robust ``4a(r + |v|)(r - |v|)`` evaluated entirely in float32 (lab code)."""
    o, d, ctr = (np.asarray(v, dtype=np.float32) for v in (origin, direction, center))
    r = np.float32(radius)
    f = o - ctr
    a = dot(d, d)
    v = f - (dot(f, d) / a) * d
    dist = np.sqrt(dot(v, v))
    return float(np.float32(4) * a * (r + dist) * (r - dist))


def _exact_disc_mp(origin, direction, center, radius):
    """The exact discriminant, read as an mpmath number at 50 digits."""
    import mpmath  # loaded when a case is computed, not with the window

    q = exact_discriminant(origin, direction, center, radius)
    with mpmath.workdps(DIGITS):
        return mpmath.mpf(q.numerator) / q.denominator


def far_sphere(distance: float = 1e8) -> CaseResult:
    """A sphere of radius 1 ``distance`` units from the ray's origin; the ray passes 0.5 from its centre.

    Parameters
    ----------
    distance : float > 0, scene units.
    """
    center = distance * FAR_DIRECTION
    side = _unit(np.cross(FAR_DIRECTION, (0.0, 0.0, 1.0)))
    d = _unit(center + 0.5 * side - FAR_ORIGIN)
    o, r = FAR_ORIGIN, 1.0
    naive64, *_ = textbook_discriminant(o, d, center, r)
    naive32, *_ = textbook_discriminant(o, d, center, r, np.float32)
    robust = intersect_sphere(o, d, center, r)
    robust32 = _pbrt_discriminant_float32(o, d, center, r)
    exact64 = _exact_disc_mp(o, d, center, r)
    f32 = [np.asarray(v, dtype=np.float32).astype(float) for v in (o, d, center)]
    exact32 = _exact_disc_mp(*f32, r)
    errors = {
        "naive64": relative_error(float(naive64), exact64),
        "robust64": relative_error(robust.discriminant, exact64),
        "naive32": relative_error(float(naive32), exact32),
        "robust32": relative_error(robust32, exact32),
    }
    f_norm = float(np.linalg.norm(o - center))
    gap = abs(r - robust.line_distance)
    tolerance = 16 * U64 * (f_norm + r) / gap + 8 * U64
    rows = (
        Row("Δ in float64", float(naive64), robust.discriminant, float(exact64)),
        Row("relative error (float64)", errors["naive64"], errors["robust64"], 0.0, compare=False),
        Row("digits correct of 16 (float64)", digits_correct(errors["naive64"]),
            digits_correct(errors["robust64"]), 16.0, compare=False),
        Row("Δ in float32", float(naive32), robust32, float(exact32)),
        Row("relative error (float32)", errors["naive32"], errors["robust32"], 0.0, compare=False),
        Row("digits correct of 7 (float32)", min(7.2, digits_correct(errors["naive32"])),
            min(7.2, digits_correct(errors["robust32"])), 7.2, compare=False),
        Row("verdict", textbook_classify(float(naive64)), robust.classification, "crosses"),
    )
    return CaseResult(
        name="far_sphere", title="3. A small sphere far away: b² - 4ac cancels",
        parameter=Parameter("distance", "distance of the sphere (radius 1) from the ray's origin",
                            distance, 1.0, 1e9),
        naive_method="b² - 4ac", robust_method="4a(r + |v|)(r - |v|) (intersect_sphere)",
        reference_method="exact rationals, read at 50 digits",
        rows=rows, naive_error=errors["naive64"], robust_error=errors["robust64"],
        error_unit="relative error of Δ (float64)", tolerance=tolerance,
        tolerance_reason=(f"16 units of rounding of |f| + r = {f_norm:.3g}, relative to r - |v| = {gap:.3g}: "
                          "v = f - (f·d / d·d) d cancels down from |f|"),
        explanation=(
            "b² and 4ac both grow like the squared distance (here about "
            f"{4 * distance**2:.1g}) while their difference stays about 3, so b² - 4ac keeps only "
            "the digits the square did not use up: none at all in float32 beyond a few thousand units, "
            "none in float64 beyond about 10^8. The robust form subtracts lengths instead of squares, "
            "r - |v| with |v| the distance from the centre to the line, and loses only the digits of "
            "the distance itself."
        ),
    )

