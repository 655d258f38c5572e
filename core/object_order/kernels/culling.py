"""Back-face culling compiled: the lecture's normal test for every face in one loop
(shared by the threads; each face on its own), the normals and centroids of some
faces, and the bounding sphere of a mesh.

Each face goes through :func:`core.object_order.culling.face_facing`, the
formula written once in the culling module.  Conventions: view space, eye at
the origin looking down -z (:mod:`core.projection`).
"""

from __future__ import annotations

import numpy as np
from numba import njit, prange

from core.object_order.culling import face_facing


@njit(cache=True, nogil=True, parallel=True)
def front_faces(view, triangles, orthographic, visible):
    """``visible[f] = facing > 0`` for every face ``f`` (:func:`face_facing`): the test
    alone, keeping none of the normals and centroids it finds on the way.

    Parameters
    ----------
    view : (N, 3) float64, vertex positions in view space.
    triangles : (F, 3) int64, vertex indices, counter-clockwise seen from outside.
    orthographic : bool, the parallel projection (else perspective).
    visible : (F,) bool, written.
    """
    for f in prange(triangles.shape[0]):
        visible[f] = face_facing(view[triangles[f, 0]], view[triangles[f, 1]], view[triangles[f, 2]],
                                 orthographic)[6] > 0


@njit(cache=True, nogil=True)
def back_face_test(view, triangles, face, orthographic, normal, centroid, facing):
    """Normals, centroids and the facing value of the faces ``face``, written into the
    last three arrays.

    Parameters
    ----------
    view : (N, 3) float64, vertex positions in view space.
    triangles : (F, 3) int64, vertex indices, counter-clockwise seen from outside.
    face : (K,) int64, the faces wanted (rows of ``triangles``).
    orthographic : bool, the parallel projection (else perspective).

    normal : (K, 3) float64, unit outward normals.
    centroid : (K, 3) float64.
    facing : (K,) float64, > 0 for a front face (:func:`face_facing`).
    """
    for k in range(face.shape[0]):
        f = face[k]
        (normal[k, 0], normal[k, 1], normal[k, 2], centroid[k, 0], centroid[k, 1], centroid[k, 2],
         facing[k]) = face_facing(view[triangles[f, 0]], view[triangles[f, 1]], view[triangles[f, 2]],
                                  orthographic)


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
