"""Flat shading: one colour per polygon, lit by the scene's point lights.

Object order draws each polygon with a single colour computed once, at the
centroid of its face, with the Lambert part of the formula the ray caster
uses per pixel, so both images look alike:

    colour = base * (k_a + k_d * sum over lights of max(0, n . l) * intensity * light colour)

clamped to [0, 1], where ``n`` is the face's unit normal turned toward the
observer (so a one-sided ground plane is lit from either side) and ``l`` the
unit vector from the centroid to the light.  A scene without lights is shown
in its flat material colours.  No shadows.

Positions and directions are in view space: the observer at the origin
looking down -z (:mod:`core.projection`).  The formula is :func:`lambert`,
written once; :func:`core.object_order.stages.face_colors` runs it over all polygons,
compiled (:mod:`core.object_order.kernels.flat_shading`).
"""

from __future__ import annotations

import numpy as np

from core.compiling.jitable import jitable


@jitable
def lambert(n, c, toward_viewer, base, ambient, diffuse, light_position, light_rgb):
    """The flat Lambert colour of one face: ``(r, g, b)`` in [0, 1].

    Parameters
    ----------
    n, c : (3,) the face's unit normal and centroid (view space).
    toward_viewer : (3,) any vector from the face toward the observer.
    base : (3,) material colour; ambient, diffuse : its k_a and k_d.
    light_position, light_rgb : (L, 3) light positions (view space) and each
        light's colour times its intensity.

    Examples
    --------
    >>> [round(float(v), 6) for v in lambert((0.0, 1.0, 0.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0),
    ...                                (0.5, 0.5, 0.5), 0.1, 0.8, np.array([[0.0, 2.0, 0.0]]),
    ...                                np.ones((1, 3)))]
    [0.45, 0.45, 0.45]
    """
    side = 1.0
    if n[0] * toward_viewer[0] + n[1] * toward_viewer[1] + n[2] * toward_viewer[2] < 0:
        side = -1.0  # turn the normal toward the observer
    r = g = b = 0.0
    for k in range(light_position.shape[0]):
        lx, ly, lz = light_position[k, 0] - c[0], light_position[k, 1] - c[1], light_position[k, 2] - c[2]
        cos = side * (n[0] * lx + n[1] * ly + n[2] * lz) / np.sqrt(lx * lx + ly * ly + lz * lz)
        cos = max(cos, 0.0)
        r, g, b = r + cos * light_rgb[k, 0], g + cos * light_rgb[k, 1], b + cos * light_rgb[k, 2]
    if light_position.shape[0] == 0:  # no lights: the flat material colour
        r = g = b = 1.0
    return (min(max(base[0] * (ambient + diffuse * r), 0.0), 1.0),
            min(max(base[1] * (ambient + diffuse * g), 0.0), 1.0),
            min(max(base[2] * (ambient + diffuse * b), 0.0), 1.0))
