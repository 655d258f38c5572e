"""Local shading: the colour a surface point gets from the lights that reach it.

Ray casting (and each hit of ray tracing) shades a point with the Phong
model: an ambient term, Lambert's diffuse term and Phong's specular
highlight for every point light whose shadow ray reaches it::

    local = w_local (k_a C + sum_L I_L k_d C max(0, N.L))
            + sum_L I_L k_s max(0, R.V)^n

with ``C`` the material colour, ``I_L`` the light's colour times its
intensity, ``N`` the unit normal facing the viewer, ``L`` the unit vector to
the light, ``V`` the unit vector to the viewer and ``R`` the mirror image of
``L`` about ``N``.  Lights are not dimmed with distance, and the ambient
light is white with intensity 1.

Ray tracing adds what the surface mirrors (``k_r``, the material's
``reflectivity``) and what it lets through (``k_t``, its ``transparency``):
only the remaining fraction ``w_local = 1 - k_r - k_t`` of the ambient and
diffuse light is the surface's own colour (:func:`surface_split`).  The
highlight is not scaled: it is the mirror image of a point light, which a
reflected ray can never hit, so a mirror and a glass ball keep their
highlights.

The functions take plain numbers and tuples and, like :mod:`core.image_order.optics`, are
compiled into the tracer's kernels where those call them (see there for the
conventions on vectors).
"""

from __future__ import annotations

from core.compiling.jitable import jitable
from core.image_order.optics import dot, reflect


@jitable
def lambert(n, to_light) -> float:
    """Lambert's cosine law: ``max(0, N . L)`` for unit vectors ``N`` and ``L``.

    Examples
    --------
    >>> lambert((0.0, 1.0, 0.0), (0.6, 0.8, 0.0))
    0.8
    """
    return max(0.0, dot(n, to_light))


@jitable
def phong(n, to_light, to_eye, shininess: float) -> float:
    """Phong's highlight factor ``max(0, R . V)^n``, ``R`` the mirror image of ``L``.

    Zero when the light is behind the surface (``N . L <= 0``).

    Examples
    --------
    Light and viewer mirrored about the normal see the full highlight:

    >>> phong((0.0, 1.0, 0.0), (0.6, 0.8, 0.0), (-0.6, 0.8, 0.0), 32.0)
    1.0
    """
    if dot(n, to_light) <= 0.0:
        return 0.0
    r = reflect((-to_light[0], -to_light[1], -to_light[2]), n)
    cos_rv = dot(r, to_eye)
    if cos_rv <= 0.0 and shininess > 0.0:  # 0^n = 0: the same answer without the power
        return 0.0
    return power(max(0.0, cos_rv), shininess)


#: Whole exponents up to this are raised by repeated squaring (:func:`power`).
WHOLE_POWERS = 1024


@jitable
def power(x: float, n: float) -> float:
    """``x ** n`` for ``0 <= x <= 1`` and ``n >= 0``: by repeated squaring where ``n`` is a whole
    number up to ``WHOLE_POWERS`` (a Phong exponent almost always is), else by the C library.

    Each of the at most ``2 log2(n)`` products rounds once, and the relative error of ``x^(2^k)``
    at most doubles with each squaring, so the result lies within ``n`` units in the last place
    of ``x ** n`` (before it underflows).  ``0 ** 0`` is 1, as Python has it.

    Examples
    --------
    >>> power(0.5, 3.0), power(0.0, 0.0), power(0.25, 0.5)
    (0.125, 1.0, 0.5)
    """
    if 0.0 <= n <= WHOLE_POWERS and n == int(n):  # in range before int(), which a huge n overflows
        k = int(n)
        result, base = 1.0, x
        while k > 0:
            if k & 1:
                result *= base
            base *= base
            k >>= 1
        return result
    return x ** n


@jitable
def surface_split(reflectivity: float, transparency: float) -> tuple[float, float, float]:
    """How a surface's light divides: ``(w_local, k_r, k_t)``, summing to 1.

    ``k_r`` and ``k_t`` are the material's reflectivity and transparency; when
    they add up to more than 1 both are scaled down so that they add up to 1.

    Examples
    --------
    >>> surface_split(0.1, 0.8)
    (0.09999999999999998, 0.1, 0.8)
    >>> surface_split(0.6, 0.6)
    (0.0, 0.5, 0.5)
    """
    total = reflectivity + transparency
    if total > 1.0:
        return 0.0, reflectivity / total, transparency / total
    return 1.0 - total, reflectivity, transparency
