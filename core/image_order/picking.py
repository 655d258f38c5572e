"""Which object a ray meets first: a click in the 3D pane selects it.

Selecting by clicking is ray casting with one ray: from the eye of the view
through the clicked point, tested against every object, the nearest hit
wins (the lecture's first hit).  An analytic sphere is crossed exactly
(:func:`core.image_order.intersect_sphere.intersect_sphere`); a mesh is first
tested against its bounding sphere, and only a ray that meets that sphere is
tested against its triangles (:func:`core.image_order.mesh_hit.first_triangle_hit`).
"""

from __future__ import annotations

import math

from core.image_order.intersect_sphere import intersect_sphere
from core.image_order.mesh_hit import first_triangle_hit
from core.scene import Mesh


def first_object_hit(objects, origin, direction) -> tuple[int, float] | None:
    """The object the ray ``o + t d`` (``t >= 0``) meets first, and where.

    Parameters
    ----------
    objects : sequence of :class:`core.scene.Sphere` / :class:`core.scene.Mesh`, world space.
    origin, direction : (3,) float, world space; ``direction`` need not be unit.

    Returns
    -------
    (index, t) or None
        The object's index in ``objects`` and the ray parameter of the hit (in units
        of ``|d|``); ``None`` when the ray meets nothing.

    Examples
    --------
    >>> from core.scene import Sphere
    >>> balls = [Sphere((0.0, 0.0, -10.0), 1.0), Sphere((0.0, 0.0, -5.0), 1.0)]
    >>> first_object_hit(balls, (0, 0, 0), (0, 0, -1))
    (1, 4.0)
    """
    best = None
    for index, obj in enumerate(objects):
        if isinstance(obj, Mesh):
            center, radius = obj.bounding_sphere()
            if not intersect_sphere(origin, direction, center, max(radius, 1e-9)).hit:
                continue
            hit = first_triangle_hit(obj, origin, direction)
            t = hit[1].t if hit is not None else math.inf
        else:
            crossing = intersect_sphere(origin, direction, obj.center, obj.radius)
            t = crossing.t if crossing.hit else math.inf
        if t < math.inf and (best is None or t < best[1]):
            best = (index, float(t))
    return best
