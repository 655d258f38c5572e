"""Back-face culling compiled: the lecture's normal test for every face in one loop
(shared by the threads; each face on its own), and the normals and centroids of the
faces (run by :func:`core.object_order.stages.back_face_culling`).

Each face goes through :func:`core.object_order.culling.face_facing`, the
formula written once in the culling module.  Conventions: view space, eye at
the origin looking down -z (:mod:`core.projection`).
"""

from __future__ import annotations

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
