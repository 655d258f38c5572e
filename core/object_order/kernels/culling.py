"""Back-face culling compiled: the lecture's normal test for every face in one loop.

Each face goes through :func:`core.object_order.culling.face_facing`, the
formula written once in the culling module.  Conventions: view space, eye at
the origin looking down -z (:mod:`core.projection`).
"""

from __future__ import annotations

import numpy as np
from numba import njit

from core.object_order.culling import face_facing


@njit(cache=True, nogil=True)
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
    for f in range(n_faces):
        (normal[f, 0], normal[f, 1], normal[f, 2], centroid[f, 0], centroid[f, 1], centroid[f, 2],
         facing[f]) = face_facing(view[triangles[f, 0]], view[triangles[f, 1]], view[triangles[f, 2]],
                                  orthographic)
    return normal, centroid, facing
