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
can be drawn in the 3D view.

Each crossing point is computed from the edge's inside end toward its outside
end, so two triangles sharing an edge get bit-identical new vertices and stay
watertight after clipping.  Conventions are those of :mod:`core.projection`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

PLANES = ("left", "right", "bottom", "top", "near", "far")


def boundary_distances(clip: np.ndarray) -> np.ndarray:
    """Signed distances from the six clip-space planes, inside when ``>= 0``.

    Parameters
    ----------
    clip : (..., 4) float64, homogeneous clip coordinates ``(x, y, z, w)``.

    Returns
    -------
    (..., 6) float64: ``w + x, w - x, w + y, w - y, w + z, w - z`` (left, right,
    bottom, top, near, far).

    Examples
    --------
    >>> boundary_distances(np.array([0.5, 0.0, -2.0, 1.0])).tolist()   # in front of the near plane
    [1.5, 0.5, 1.0, 1.0, -1.0, 3.0]
    """
    x, y, z, w = clip[..., 0], clip[..., 1], clip[..., 2], clip[..., 3]
    return np.stack([w + x, w - x, w + y, w - y, w + z, w - z], axis=-1)


def clip_polygon(clip: np.ndarray, world: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Sutherland-Hodgman: clip one convex polygon against the six planes.

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
    vertices = np.hstack([clip, world])
    for plane in range(6):
        if len(vertices) == 0:
            break
        d = boundary_distances(vertices[:, :4])[:, plane]
        if np.all(d >= 0):
            continue
        kept = []
        n = len(vertices)
        for k in range(n):
            s, e = k - 1 if k else n - 1, k  # the edge from the previous vertex s to e
            if (d[s] >= 0) != (d[e] >= 0):
                inner, outer = (s, e) if d[s] >= 0 else (e, s)
                t = d[inner] / (d[inner] - d[outer])
                kept.append(vertices[inner] + t * (vertices[outer] - vertices[inner]))
            if d[e] >= 0:
                kept.append(vertices[e])
        vertices = np.array(kept).reshape(-1, 7)
    return vertices[:, :4], vertices[:, 4:]


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


def clip_triangles(face: np.ndarray, triangles: np.ndarray, clip: np.ndarray, world: np.ndarray,
                   test: np.ndarray | None = None) -> ClipResult:
    """Clip triangles against the frustum, deciding the easy cases all at once.

    A triangle whose corners are all inside every plane is accepted whole; one
    whose corners are all outside the same plane is rejected; only the rest go
    through :func:`clip_polygon`.

    Parameters
    ----------
    face : (K,) int64, the global face number of each triangle.
    triangles : (K, 3) int64, vertex indices of its corners.
    clip : (N, 4) float64, vertex positions in clip space.
    world : (N, 3) float64, the same vertices in world space.
    test : (K,) bool, which triangles may cross the frustum; the others (their
        object lies inside it) are accepted untested.  Default: test all.
    """
    k = len(face)
    test = np.ones(k, dtype=bool) if test is None else test
    accept, reject = ~test, np.zeros(k, dtype=bool)
    if test.any():
        inside = boundary_distances(clip[triangles[test]]) >= 0  # (K', 3 corners, 6 planes)
        accept[test] = inside.all(axis=(1, 2))
        reject[test] = (~inside).all(axis=1).any(axis=1)
    cut = np.flatnonzero(~accept & ~reject)
    pieces = [clip_polygon(clip[triangles[i]], world[triangles[i]]) for i in cut]
    survivors = [i for i, (c, _) in enumerate(pieces) if len(c) >= 3]
    counts = np.where(accept, 3, 0)
    counts[cut[survivors]] = [len(pieces[i][0]) for i in survivors]
    keep = np.flatnonzero(counts)
    offsets = np.concatenate([[0], np.cumsum(counts[keep])]).astype(np.int64)
    vertex = np.empty(offsets[-1], dtype=np.int64)
    whole = accept[keep]
    vertex[(offsets[:-1][whole][:, None] + np.arange(3)).ravel()] = triangles[keep[whole]].ravel()
    if survivors:
        new_clip = np.vstack([pieces[i][0] for i in survivors])
        new_world = np.vstack([pieces[i][1] for i in survivors])
        vertex[np.repeat(~whole, counts[keep])] = len(clip) + np.arange(len(new_clip))
        clip, world = np.vstack([clip, new_clip]), np.vstack([world, new_world])
    polygons = Polygons(offsets, vertex, clip, world, face[keep], ~whole)
    return ClipResult(polygons, int(accept.sum()), k - len(keep), len(survivors))
