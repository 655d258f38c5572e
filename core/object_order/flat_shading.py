"""Flat shading: one colour per polygon, lit by the scene's point lights.

Object order draws each polygon with a single colour computed once, at the
centroid of its face, with the Lambert part of the formula the ray caster
uses per pixel, so both images look alike:

    colour = base * (k_a + k_d * sum over lights of max(0, n . l) * intensity * light colour)

clamped to [0, 1], where ``n`` is the face's unit normal turned toward the
observer (so a one-sided ground plane is lit from either side) and ``l`` the
unit vector from the centroid to the light.  A scene without lights is shown
in its flat material colours.  No shadows.

Positions and directions may be given in any one frame (world or view space);
the formula only uses differences and dot products.
"""

from __future__ import annotations

import numpy as np


def face_colors(centroid: np.ndarray, normal: np.ndarray, toward_viewer: np.ndarray, base: np.ndarray,
                ambient: np.ndarray, diffuse: np.ndarray, light_position: np.ndarray,
                light_rgb: np.ndarray) -> np.ndarray:
    """The flat Lambert colour of each face.

    Parameters
    ----------
    centroid : (F, 3) float64, the point each face is lit at.
    normal : (F, 3) float64, unit face normals.
    toward_viewer : (F, 3) or (3,) float64, any vector from the face toward the
        observer (decides which side of the face is lit).
    base : (F, 3) float64, material colour, RGB in [0, 1].
    ambient, diffuse : (F,) float64, the material's k_a and k_d.
    light_position : (L, 3) float64, point light positions (same frame).
    light_rgb : (L, 3) float64, each light's colour times its intensity.

    Returns
    -------
    (F, 3) float64, RGB in [0, 1].

    Examples
    --------
    >>> one = np.ones((1, 3))
    >>> face_colors(np.zeros((1, 3)), np.array([[0.0, 1.0, 0.0]]), np.array([0.0, 1.0, 0.0]),
    ...             0.5 * one, np.array([0.1]), np.array([0.8]), np.array([[0.0, 2.0, 0.0]]),
    ...             one).round(6).tolist()
    [[0.45, 0.45, 0.45]]
    """
    if len(light_position) == 0:
        return np.clip(base * (ambient + diffuse)[:, None], 0.0, 1.0)
    n = np.ascontiguousarray(normal.T)  # (3, F): per-coordinate rows are fast to combine
    c = np.ascontiguousarray(centroid.T)
    v = np.broadcast_to(np.asarray(toward_viewer, dtype=float), normal.shape).T
    side = np.where(n[0] * v[0] + n[1] * v[1] + n[2] * v[2] < 0, -1.0, 1.0)
    light_sum = np.zeros_like(base)
    for position, rgb in zip(light_position, light_rgb, strict=True):
        to_light = position[:, None] - c
        cos = side * (n[0] * to_light[0] + n[1] * to_light[1] + n[2] * to_light[2])
        cos /= np.sqrt(to_light[0] ** 2 + to_light[1] ** 2 + to_light[2] ** 2)
        light_sum += np.maximum(cos, 0.0)[:, None] * rgb
    return np.clip(base * (ambient[:, None] + diffuse[:, None] * light_sum), 0.0, 1.0)
