"""One primitive test, whatever the primitive: the common currency of every acceleration method.

The flattened scene (:mod:`core.image_order.flat_scene`) numbers its primitives with the
analytic spheres first and the triangles after them, and stores each as one
row of nine numbers: ``(cx, cy, cz, r, 0, 0, 0, 0, 0)`` for a sphere, the
corners ``A, B, C`` for a triangle (columns ``ROW_*`` of
:mod:`core.image_order.flat_layout`).  Every acceleration method ends in
:func:`prim_hit` on such a row, so all of them compute bit-identical crossings
and differ only in how many rows they test.
"""

from __future__ import annotations

import math

from core.image_order.flat_layout import ROW_CENTER, ROW_RADIUS
from core.image_order.kernels.intersect import sphere_hit, triangle_hit
from core.image_order.kernels.jit import jit, jit_inline


@jit_inline
def prim_hit(rows, k, is_sphere, o, d, shear, t_min, t_max):
    """Cross the ray ``o + t d`` with the primitive in ``rows[k]``: ``(t, b0, b1, b2)``, ``inf`` on a miss.

    ``b0, b1, b2`` are the barycentric weights of a triangle's corners (zeros
    for a sphere).
    """
    if is_sphere:
        c = ROW_CENTER
        t = sphere_hit(o[0], o[1], o[2], d[0], d[1], d[2], rows[k, c], rows[k, c + 1], rows[k, c + 2],
                       rows[k, ROW_RADIUS], t_min, t_max)
        return t, 0.0, 0.0, 0.0
    return triangle_hit(o, shear, rows, k, t_min, t_max)


@jit
def no_hit():
    """The result of a query that found nothing: ``(prim, t, b0, b1, b2)`` (see ``flat_layout.HIT_*``)."""
    return -1, math.inf, 0.0, 0.0, 0.0
