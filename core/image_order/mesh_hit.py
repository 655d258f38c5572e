"""Which triangle of a mesh a ray meets first, for explaining one picked ray.

The renderer's kernels report the object a ray hit, not the triangle.  To
show the lecture's triangle test for a picked pixel, :func:`first_triangle_hit`
finds that triangle: a quick vectorised pass (Möller and Trumbore's form of
the same barycentric system) orders the candidate triangles by distance, and
:func:`core.image_order.intersect_triangle.intersect_triangle` decides, nearest
candidate first, so the answer comes from the same test the ``intersect``
command explains.
"""

from __future__ import annotations

import numpy as np

from core.image_order.intersect_triangle import TriangleIntersection, intersect_triangle
from core.scene import Mesh

#: Barycentric slack of the quick pass, so that rays through an edge keep both
#: neighbours as candidates; the exact test then decides.
_SLACK = 1e-6


def first_triangle_hit(mesh: Mesh, origin, direction) -> tuple[int, TriangleIntersection] | None:
    """The first triangle of ``mesh`` hit by the ray ``o + t d`` (``t >= 0``).

    Parameters
    ----------
    mesh : Mesh, world space.
    origin, direction : (3,) float, world space; ``direction`` need not be unit.

    Returns
    -------
    (index, TriangleIntersection) or None
        The triangle's index in ``mesh.triangles`` and its worked crossing;
        ``None`` when the ray misses every triangle.
    """
    o = np.asarray(origin, dtype=float)
    d = np.asarray(direction, dtype=float)
    corners = mesh.vertices[mesh.triangles]
    A, B, C = corners[:, 0], corners[:, 1], corners[:, 2]
    e1, e2 = B - A, C - A
    p = np.cross(d, e2)
    det = np.einsum("ij,ij->i", e1, p)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = o - A
        u = np.einsum("ij,ij->i", s, p) * inv
        q = np.cross(s, e1)
        v = (q @ d) * inv
        t = np.einsum("ij,ij->i", e2, q) * inv
        ok = np.isfinite(t) & (t >= -_SLACK) & (u >= -_SLACK) & (v >= -_SLACK) & (u + v <= 1 + _SLACK)
    for k in np.flatnonzero(ok)[np.argsort(t[ok], kind="stable")]:
        hit = intersect_triangle(o, d, *corners[k])
        if hit.hit:
            return int(k), hit
    return None
