"""Numbers shown to students: six significant digits, the way the worked math writes them.

The worked solutions of ``python -m app intersect``
(:mod:`core.image_order.intersect_sphere`, :mod:`core.image_order.intersect_triangle`)
and the window's worked-math pane (:mod:`views.text.worked_math`,
:mod:`views.text.math_view`) write every number with :func:`shown_number`, so the
pane and the command line agree digit for digit.
"""

from __future__ import annotations

SIGNIFICANT_DIGITS = 6


def shown_number(x: float) -> str:
    """``x`` to :data:`SIGNIFICANT_DIGITS` significant digits, with ``0`` for a ``-0``.

    Examples
    --------
    >>> shown_number(1 / 3), shown_number(-0.0), shown_number(-1e-9), shown_number(1234567.0)
    ('0.333333', '0', '-1e-09', '1.23457e+06')
    """
    text = f"{x:.{SIGNIFICANT_DIGITS}g}"
    return "0" if text == "-0" else text


def shown_vector(v) -> str:
    """A vector as ``(x, y, z)``, each component a :func:`shown_number`.

    >>> shown_vector((1.0, -0.0, 2 / 3))
    '(1, 0, 0.666667)'
    """
    return "(" + ", ".join(shown_number(x) for x in v) + ")"
