"""Flat shading compiled: one Lambert colour per polygon, every polygon in one loop.

Each polygon goes through :func:`core.object_order.flat_shading.lambert`, the
formula written once in the flat-shading module.  View space.
"""

from __future__ import annotations

from numba import njit

from core.object_order.flat_shading import lambert


@njit(cache=True, nogil=True)
def face_colors(face, material, normal, centroid, orthographic, base, ambient, diffuse,
                light_position, light_rgb, out):
    """Flat colours, RGB in [0, 1], written into ``out`` (P, 3); parameters as
    :func:`core.object_order.flat_shading.face_colors` (float64 / int64, C-contiguous)."""
    for p in range(face.shape[0]):
        f, m = face[p], material[p]
        n = (normal[f, 0], normal[f, 1], normal[f, 2])
        c = (centroid[f, 0], centroid[f, 1], centroid[f, 2])
        toward = (0.0, 0.0, 1.0) if orthographic else (-c[0], -c[1], -c[2])
        out[p, 0], out[p, 1], out[p, 2] = lambert(n, c, toward, (base[m, 0], base[m, 1], base[m, 2]),
                                                  ambient[m], diffuse[m], light_position, light_rgb)
