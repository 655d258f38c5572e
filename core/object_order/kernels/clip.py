"""Clipping compiled: every triangle against the frustum in one loop.

For each triangle: accept it whole when its three corners are inside all six
planes, reject it when all three are outside the same plane, and otherwise
cut it with :func:`core.object_order.clipping.sutherland_hodgman`, the same
function the readable clipper calls, so both give bit-identical polygons.
The new vertices (clip and world positions) are returned for the 3D view's
display of the clipped polygons; :func:`core.object_order.stages.clip_triangles`
runs it and gathers the polygons.  Conventions: :mod:`core.object_order.clipping`.
"""

from __future__ import annotations

import numpy as np
from numba import njit

from core.object_order.clipping import (
    MAX_CLIPPED_VERTICES,
    VERTEX_COMPONENTS,
    boundary_distance,
    sutherland_hodgman,
)

#: What happened to a triangle (``outcome``): kept whole, dropped, cut to a smaller polygon,
#: or cut to nothing.
ACCEPTED, REJECTED, CUT, CUT_AWAY = range(4)


@njit(cache=True, nogil=True)
def clip_triangles(triangles, clip, world, test, outcome, counts):
    """Clip triangles against the frustum's six planes: what happened to each, and the
    new vertices (:func:`number_vertices` then numbers the polygons' vertices).

    Parameters
    ----------
    triangles : (K, 3) int64, vertex indices of the corners.
    clip : (N, 4) float64, vertex positions in clip space.
    world : (N, 3) float64, the same vertices in world space.
    test : (K,) bool, triangles that may cross the frustum; the others are
        accepted untested.
    outcome : (K,) int8, written: ``ACCEPTED``, ``REJECTED``, ``CUT`` or ``CUT_AWAY``.
    counts : (K,) int64, written: the vertices left of each triangle (0, 3 or more).

    Returns
    -------
    new : (V', 7) float64, the vertices of the cut polygons, triangle after
        triangle, each in order around its polygon: clip ``(x, y, z, w)`` then
        world ``(x, y, z)``.
    """
    k_total = triangles.shape[0]
    new = np.empty((64, VERTEX_COMPONENTS))
    n_new = 0
    poly = np.empty((MAX_CLIPPED_VERTICES + 1, VERTEX_COMPONENTS))
    spare = np.empty_like(poly)
    for k in range(k_total):
        counts[k] = 0
        if not test[k]:
            outcome[k], counts[k] = ACCEPTED, 3
            continue
        all_inside, outside_one = True, False
        for plane in range(6):
            outside = 0
            for corner in range(3):
                if boundary_distance(clip[triangles[k, corner]], plane) < 0:
                    outside += 1
            all_inside &= outside == 0
            outside_one |= outside == 3
        if all_inside:
            outcome[k], counts[k] = ACCEPTED, 3
            continue
        if outside_one:
            outcome[k] = REJECTED
            continue
        for corner in range(3):
            v = triangles[k, corner]
            poly[corner, :4] = clip[v]
            poly[corner, 4:] = world[v]
        m = sutherland_hodgman(poly, 3, spare)
        if m < 3:
            outcome[k] = CUT_AWAY
            continue
        if n_new + m > new.shape[0]:
            grown = np.empty((2 * new.shape[0], VERTEX_COMPONENTS))
            grown[:n_new] = new[:n_new]
            new = grown
        new[n_new:n_new + m] = poly[:m]
        n_new += m
        outcome[k], counts[k] = CUT, m
    return new[:n_new].copy()


@njit(cache=True, nogil=True)
def number_vertices(triangles, outcome, keep, offsets, first_new, vertex):
    """The vertex numbers of the polygons left after :func:`clip_triangles`, into ``vertex``.

    Parameters
    ----------
    triangles, outcome : as given to and written by :func:`clip_triangles`.
    keep : (P,) int64, the triangles with something left, in order.
    offsets : (P + 1,) int64, polygon ``p`` (of triangle ``keep[p]``) has the
        vertices ``vertex[offsets[p] : offsets[p + 1]]``.
    first_new : int, the number of the first new vertex (the vertices before clipping).
    vertex : (V,) int64, written: a whole triangle keeps its corners' numbers, a
        cut one gets new vertices numbered from ``first_new`` on, in the order of
        the new vertices.
    """
    next_new = first_new
    for p in range(keep.shape[0]):
        k = keep[p]
        for corner in range(offsets[p + 1] - offsets[p]):
            if outcome[k] == ACCEPTED:
                vertex[offsets[p] + corner] = triangles[k, corner]
            else:
                vertex[offsets[p] + corner] = next_new
                next_new += 1
