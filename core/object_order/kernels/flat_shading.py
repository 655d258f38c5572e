"""Flat shading compiled: one Lambert colour per polygon, every polygon in one loop.

Each polygon's face goes through :func:`core.object_order.culling.face_facing`
for its normal and centroid and then through
:func:`core.object_order.flat_shading.lambert`, the formulas written once in
their modules; the normals and centroids are used on the spot, never stored.
The threads share the polygons (each on its own).  View space.
"""

from __future__ import annotations

from numba import njit, prange

from core.object_order.culling import face_facing
from core.object_order.flat_shading import lambert


@njit(cache=True, nogil=True, parallel=True)
def face_colors(view, triangles, face, material, orthographic, base, ambient, diffuse,
                light_position, light_rgb, out, depth):
    """Flat colours, RGB in [0, 1], written into ``out`` (P, 3), and each face's centroid
    depth into ``depth`` (P,); parameters as :func:`core.object_order.stages.face_colors`
    (float64 / int64, C-contiguous)."""
    for p in prange(face.shape[0]):
        f, m = face[p], material[p]
        nx, ny, nz, cx, cy, cz, _ = face_facing(view[triangles[f, 0]], view[triangles[f, 1]],
                                                view[triangles[f, 2]], orthographic)
        toward = (0.0, 0.0, 1.0) if orthographic else (-cx, -cy, -cz)
        out[p, 0], out[p, 1], out[p, 2] = lambert((nx, ny, nz), (cx, cy, cz), toward,
                                                  (base[m, 0], base[m, 1], base[m, 2]),
                                                  ambient[m], diffuse[m], light_position, light_rgb)
        depth[p] = -cz
