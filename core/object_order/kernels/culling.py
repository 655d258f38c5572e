"""Back-face culling compiled: the lecture's normal test for every face in one loop.

Each face goes through :func:`core.object_order.culling.face_facing`, the
formula written once in the culling module.  Conventions: view space, eye at
the origin looking down -z (:mod:`core.projection`).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from core.object_order.culling import face_facing


@njit(cache=True, nogil=True, parallel=True)
def back_face_test(view, triangles, orthographic):
    """Normals, centroids and the facing value of every face.

    Parameters
    ----------
    view : (N, 3) float64, vertex positions in view space.
    triangles : (F, 3) int64, vertex indices, counter-clockwise seen from outside.
    orthographic : bool, the parallel projection (else perspective).

    Returns
    -------
    normal : (F, 3) float64, unit outward normals.
    centroid : (F, 3) float64.
    facing : (F,) float64, > 0 for a front face (:func:`face_facing`).
    """
    n_faces = triangles.shape[0]
    normal = np.empty((n_faces, 3))
    centroid = np.empty((n_faces, 3))
    facing = np.empty(n_faces)
    for f in prange(n_faces):
        (normal[f, 0], normal[f, 1], normal[f, 2], centroid[f, 0], centroid[f, 1], centroid[f, 2],
         facing[f]) = face_facing(view[triangles[f, 0]], view[triangles[f, 1]], view[triangles[f, 2]],
                                  orthographic)
    return normal, centroid, facing


@njit(cache=True, nogil=True)
def bounding_sphere(points):
    """:func:`core.scene.bounding_sphere_of` in two passes over the points, with its
    arithmetic (bit for bit) and none of its temporary arrays.

    Parameters
    ----------
    points : (N, 3) float64, N >= 1.

    Returns
    -------
    center : (3,) float64, the middle of the bounding box; radius : float, out to
        the farthest point.
    """
    low = points[0].copy()
    high = points[0].copy()
    for i in range(1, points.shape[0]):
        for k in range(3):
            low[k] = min(low[k], points[i, k])
            high[k] = max(high[k], points[i, k])
    center = (low + high) / 2.0
    farthest = 0.0
    for i in range(points.shape[0]):
        dx, dy, dz = points[i, 0] - center[0], points[i, 1] - center[1], points[i, 2] - center[2]
        farthest = max(farthest, dx * dx + dy * dy + dz * dz)
    return center, np.sqrt(farthest)
