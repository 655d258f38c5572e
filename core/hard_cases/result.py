"""What one hard case reports: the naive and the robust answer beside the exact one.

Every case of the lab (:mod:`core.hard_cases`) returns a :class:`CaseResult`.
It keeps the numbers a student compares (:class:`Row`: one quantity, as the
textbook method computes it, as the app's robust method computes it, and as
exact arithmetic gives it), one error figure per method in a stated unit, the
tolerance the robust method must meet, and optional images for failures one
can see.  The case's natural parameter (:class:`Parameter`) says what a slider
may sweep.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

#: Working precision of every mpmath reference, in decimal digits.
DIGITS = 50

#: Unit roundoff of float64.
U64 = 2.0**-53


@dataclass(frozen=True)
class Parameter:
    """The natural parameter of a case, for a slider.

    Attributes
    ----------
    name : keyword of the case function (``"distance"``).
    label : what it is, in words, with its unit.
    value : the value this result was computed at.
    minimum, maximum : the range a slider offers.
    log : the slider moves in decades (``value`` is then > 0).
    """

    name: str
    label: str
    value: float
    minimum: float
    maximum: float
    log: bool = True

    def with_value(self, value: float) -> Parameter:
        return Parameter(self.name, self.label, float(value), self.minimum, self.maximum, self.log)


@dataclass(frozen=True)
class Row:
    """One quantity three ways: textbook method, robust method, exact reference.

    Values are floats (shown with 16 significant digits, so the digits that
    differ can be marked), strings (verdicts such as ``"misses"``) or
    ``None`` (the method has no such value).  ``compare`` is False for rows
    that describe rather than answer (the three columns need not agree).
    """

    label: str
    naive: float | str | None
    robust: float | str | None
    exact: float | str | None
    compare: bool = True


@dataclass(frozen=True)
class CaseImage:
    """A picture of the case: what the naive method draws next to what the robust one does.

    ``naive`` and ``robust`` are (H, W, 3) float64 linear RGB in [0, 1]; row 0
    is the top of the image.
    """

    caption: str
    naive: np.ndarray
    robust: np.ndarray


@dataclass(frozen=True)
class CaseResult:
    """Everything one hard case found.

    Attributes
    ----------
    name, title : key (for ``--case``) and a one-line title.
    parameter : the case's natural parameter and the value used, or ``None``.
    naive_method, robust_method, reference_method : what each column is.
    rows : the numbers side by side.
    naive_error, robust_error : the error of each method, in ``error_unit``
        (NaN when the method produced no number at all).
    error_unit : e.g. ``"relative error"``, ``"wrong verdicts"``, ``"pixels"``.
    tolerance : the largest ``robust_error`` that passes, and ``tolerance_reason``
        why that bound (a rounding error bound, or 0 for a verdict).
    explanation : why the naive method fails and what the robust one does.
    images : pictures where the failure is visible.
    """

    name: str
    title: str
    parameter: Parameter | None
    naive_method: str
    robust_method: str
    reference_method: str
    rows: tuple[Row, ...]
    naive_error: float
    robust_error: float
    error_unit: str
    tolerance: float
    tolerance_reason: str
    explanation: str
    images: tuple[CaseImage, ...] = field(default=())

    @property
    def passed(self) -> bool:
        """The robust method met its tolerance (a NaN error never passes)."""
        return bool(self.robust_error <= self.tolerance)

    @property
    def naive_passed(self) -> bool:
        """Would the textbook method have met the same tolerance?"""
        return bool(self.naive_error <= self.tolerance)


def relative_error(computed: float, reference) -> float:
    """``|computed - reference| / |reference|`` (absolute when the reference is 0); NaN stays NaN.

    ``reference`` may be an mpmath number; the difference is taken at :data:`DIGITS` digits.

    Examples
    --------
    >>> relative_error(2.9375, 3), relative_error(float("nan"), 3)
    (0.020833333333333332, nan)
    """
    import mpmath  # loaded when a case is computed, not with the window

    if computed is None or not math.isfinite(computed):
        return math.nan if computed is None or math.isnan(computed) else math.inf
    with mpmath.workdps(DIGITS):
        ref = mpmath.mpf(reference)
        diff = abs(mpmath.mpf(float(computed)) - ref)
        return float(diff / abs(ref)) if ref != 0 else float(diff)


def digits_correct(rel_error: float) -> float:
    """Significant decimal digits a relative error leaves (0 when nothing is right, at most 17).

    Examples
    --------
    >>> digits_correct(1e-10), digits_correct(2.0)
    (10.0, 0.0)
    """
    if not math.isfinite(rel_error):
        return 0.0
    if rel_error == 0:
        return 17.0
    return max(0.0, min(17.0, -math.log10(rel_error)))
