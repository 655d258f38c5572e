"""Clipping: cutting polygons to the frustum (viewing pyramid) before projection.

Polygons of objects that cross the frustum are cut by its six planes with the
Sutherland-Hodgman algorithm: the polygon is clipped against one plane after
the other; walking its edges, every vertex inside a plane is kept and every
edge that crosses the plane contributes its crossing point.

The clipping is done in homogeneous *clip space*, before the perspective
divide.  There the frustum is ``-w <= x, y, z <= w``, six linear inequalities,
and a point behind the eye (``w < 0``) simply fails the near one.  Dividing by
``w`` first would instead throw such a point to the mirrored side of the
image; clipping first guarantees ``w >= near > 0`` for everything that is
projected.  Clip coordinates are linear in world space, so every new vertex
gets its world-space position by the same interpolation; the clipped polygons
can be drawn in the 3D view.  A frame's triangles are clipped all at once,
compiled (:func:`core.object_order.stages.clip_triangles`), each with
:func:`sutherland_hodgman`, the formula written once here.

Each crossing point is computed from the edge's inside end toward its outside
end, so two triangles sharing an edge get bit-identical new vertices and stay
watertight after clipping.  Conventions are those of :mod:`core.projection`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.compiling.jitable import jitable

PLANES = ("left", "right", "bottom", "top", "near", "far")


#: Most vertices a triangle can have after clipping: each of the six planes cuts
#: one corner off a convex polygon, adding at most one vertex.
MAX_CLIPPED_VERTICES = 3 + 6
#: Components of a vertex while it is clipped: clip ``(x, y, z, w)`` then world ``(x, y, z)``.
VERTEX_COMPONENTS = 7


def boundary_distances(clip: np.ndarray) -> np.ndarray:
    """Signed distances from the six clip-space planes, inside when ``>= 0``.

    Parameters
    ----------
    clip : (..., 4) float64, homogeneous clip coordinates ``(x, y, z, w)``.

    Returns
    -------
    (..., 6) float64: ``w + x, w - x, w + y, w - y, w + z, w - z`` (left, right,
    bottom, top, near, far), each :func:`boundary_distance`.

    Examples
    --------
    >>> boundary_distances(np.array([0.5, 0.0, -2.0, 1.0])).tolist()   # in front of the near plane
    [1.5, 0.5, 1.0, 1.0, -1.0, 3.0]
    """
    return np.stack([boundary_distance(clip, plane) for plane in range(6)], axis=-1)


@jitable
def boundary_distance(v, plane):
    """Signed distance of clip-space point ``v = (x, y, z, w, ...)`` from one plane of the frustum.

    ``plane`` numbers :data:`PLANES`: ``w + x`` (left), ``w - x`` (right),
    ``w + y`` (bottom), ``w - y`` (top), ``w + z`` (near), ``w - z`` (far);
    inside when ``>= 0``.  ``v`` may be one vertex or an array of them
    (components along the last axis).
    """
    axis = plane // 2
    if plane % 2 == 0:
        return v[..., 3] + v[..., axis]
    return v[..., 3] - v[..., axis]


@jitable
def sutherland_hodgman(poly, n, spare):
    """Clip the convex polygon ``poly[:n]`` against the six planes, in place.

    Walking the polygon's edges plane after plane, every vertex inside the
    plane is kept and every edge that crosses it contributes its crossing
    point ``inner + t (outer - inner)`` with ``t = d_inner / (d_inner - d_outer)``,
    always taken from the inside end so that two triangles sharing an edge get
    bit-identical new vertices.  A plane no vertex is outside of is skipped.

    Parameters
    ----------
    poly : (M, 7) float64, rows clip ``(x, y, z, w)`` then world ``(x, y, z)``;
        ``M >= n + 6`` (:data:`MAX_CLIPPED_VERTICES` for a triangle).
        Overwritten with the clipped polygon.
    n : int, vertices in ``poly``.
    spare : (M, 7) float64, scratch space.  A polygon so thin that rounding
        makes it cross a plane more than twice keeps only its first ``M``
        vertices (memory stays safe in the compiled loop).

    Returns
    -------
    int, vertices of the clipped polygon in ``poly[:m]`` (0 when nothing is left).
    """
    for plane in range(6):
        if n == 0:
            break
        outside = False
        for k in range(n):
            if boundary_distance(poly[k], plane) < 0:
                outside = True
        if not outside:
            continue
        m = 0
        for e in range(n):
            s = e - 1 if e else n - 1  # the edge from the previous vertex s to e
            ds, de = boundary_distance(poly[s], plane), boundary_distance(poly[e], plane)
            if (ds >= 0) != (de >= 0) and m < spare.shape[0]:
                inner, outer, d_inner, d_outer = (s, e, ds, de) if ds >= 0 else (e, s, de, ds)
                t = d_inner / (d_inner - d_outer)
                for c in range(VERTEX_COMPONENTS):
                    spare[m, c] = poly[inner, c] + t * (poly[outer, c] - poly[inner, c])
                m += 1
            if de >= 0 and m < spare.shape[0]:
                for c in range(VERTEX_COMPONENTS):
                    spare[m, c] = poly[e, c]
                m += 1
        for k in range(m):
            for c in range(VERTEX_COMPONENTS):
                poly[k, c] = spare[k, c]
        n = m
    return n


def clip_polygon(clip: np.ndarray, world: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sutherland-Hodgman: clip one convex polygon against the six planes.

    The readable entry to :func:`sutherland_hodgman`, the same function the
    compiled clipper (:mod:`core.object_order.kernels.clip`) runs.

    Parameters
    ----------
    clip : (n, 4) float64, its vertices in clip space, in order around it.
    world : (n, 3) float64, the same vertices in world space.

    Returns
    -------
    clip, world : (m, 4) and (m, 3) float64, the clipped polygon (m = 0 when
        nothing is left; at most n + 6 vertices).

    Examples
    --------
    >>> tri = np.array([[0.0, 0.0, 0.0, 1.0], [4.0, 0.0, 0.0, 1.0], [0.0, 0.5, 0.0, 1.0]])
    >>> c, _ = clip_polygon(tri, tri[:, :3])   # cut at x = w = 1
    >>> c[:, :2].tolist()
    [[0.0, 0.0], [1.0, 0.0], [1.0, 0.375], [0.0, 0.5]]
    """
    n = len(clip)
    poly = np.zeros((n + 6, VERTEX_COMPONENTS))
    poly[:n, :4], poly[:n, 4:] = clip, world
    m = sutherland_hodgman(poly, n, np.zeros_like(poly))
    return poly[:m, :4].copy(), poly[:m, 4:].copy()


@dataclass(frozen=True)
class Polygons:
    """Convex polygons as lists of vertex indices into shared vertex arrays.

    Triangles that need no clipping keep their mesh's vertex indices; clipping
    adds the new vertices at the end of the shared arrays.

    Attributes
    ----------
    offsets : (P + 1,) int64, polygon ``p`` has the vertices
        ``vertex[offsets[p] : offsets[p + 1]]``, in order around it.
    vertex : (V,) int64, indices into ``clip`` and ``world``.
    clip : (N, 4) float64, vertex positions in clip space.
    world : (N, 3) float64, the same vertices in world space.
    face : (P,) int64, the scene face (global triangle number) each came from.
    clipped : (P,) bool, the polygon was cut by a frustum plane.
    """

    offsets: np.ndarray
    vertex: np.ndarray
    clip: np.ndarray
    world: np.ndarray
    face: np.ndarray
    clipped: np.ndarray

    def __len__(self) -> int:
        return len(self.face)

    def world_vertices(self, p: int) -> np.ndarray:
        """(n, 3) float64, the world-space vertices of polygon ``p``."""
        return self.world[self.vertex[self.offsets[p]:self.offsets[p + 1]]]

    def take(self, order: np.ndarray) -> Polygons:
        """The polygons ``order[0], order[1], ...`` (sharing the vertex arrays)."""
        counts = np.diff(self.offsets)[order]
        offsets = np.concatenate([[0], np.cumsum(counts)]).astype(np.int64)
        index = np.repeat(self.offsets[:-1][order] - offsets[:-1], counts) + np.arange(offsets[-1])
        return Polygons(offsets, self.vertex[index], self.clip, self.world, self.face[order],
                        self.clipped[order])


@dataclass(frozen=True)
class ClipResult:
    """What clipping did to the triangles it was given.

    Attributes
    ----------
    polygons : the surviving polygons, in the order of their faces.
    accepted : int, triangles entirely inside (kept whole, or not tested
        because their object lies inside the frustum).
    rejected : int, triangles entirely outside (nothing left).
    clipped : int, triangles cut into a smaller polygon.
    """

    polygons: Polygons
    accepted: int
    rejected: int
    clipped: int

    def clipped_polygons(self) -> list[np.ndarray]:
        """The cut polygons in world space, one (n, 3) array each, for the 3D view."""
        return [self.polygons.world_vertices(p) for p in np.flatnonzero(self.polygons.clipped)]
