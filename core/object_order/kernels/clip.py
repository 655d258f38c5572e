"""Clipping compiled: every triangle against the frustum in one loop.

For each triangle: accept it whole when its three corners are inside all six
planes, reject it when all three are outside the same plane, and otherwise
cut it with :func:`core.object_order.clipping.sutherland_hodgman`, the same
function the readable clipper calls, so both give bit-identical polygons.
The new vertices (clip and world positions) are returned for the 3D view's
display of the clipped polygons.  Conventions: :mod:`core.object_order.clipping`.
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
def clip_triangles(triangles, clip, world, test):
    """Clip triangles against the frustum's six planes.

    Parameters
    ----------
    triangles : (K, 3) int64, vertex indices of the corners.
    clip : (N, 4) float64, vertex positions in clip space.
    world : (N, 3) float64, the same vertices in world space.
    test : (K,) bool, triangles that may cross the frustum; the others are
        accepted untested.

    Returns
    -------
    outcome : (K,) int8, ``ACCEPTED``, ``REJECTED``, ``CUT`` or ``CUT_AWAY``.
    keep : (P,) int64, the triangles with something left, in order.
    offsets : (P + 1,) int64, polygon ``p`` (of triangle ``keep[p]``) has the
        vertices ``vertex[offsets[p] : offsets[p + 1]]``.
    vertex : (V,) int64, vertex numbers: a whole triangle keeps its corners'
        numbers, a cut one gets new vertices numbered from ``N`` on, in the
        order of ``new``.
    new : (V', 7) float64, the vertices of the cut polygons, triangle after
        triangle, each in order around its polygon: clip ``(x, y, z, w)`` then
        world ``(x, y, z)``.
    """
    k_total = triangles.shape[0]
    outcome = np.empty(k_total, np.int8)
    counts = np.zeros(k_total, np.int64)
    new = np.empty((64, VERTEX_COMPONENTS))
    n_new = 0
    poly = np.empty((MAX_CLIPPED_VERTICES + 1, VERTEX_COMPONENTS))
    spare = np.empty_like(poly)
    for k in range(k_total):
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
    keep = np.flatnonzero(counts)
    offsets = np.zeros(keep.shape[0] + 1, np.int64)
    for p in range(keep.shape[0]):
        offsets[p + 1] = offsets[p] + counts[keep[p]]
    vertex = np.empty(offsets[-1], np.int64)
    next_new = clip.shape[0]
    for p in range(keep.shape[0]):
        k = keep[p]
        for corner in range(counts[k]):
            if outcome[k] == ACCEPTED:
                vertex[offsets[p] + corner] = triangles[k, corner]
            else:
                vertex[offsets[p] + corner] = next_new
                next_new += 1
    return outcome, keep, offsets, vertex, new[:n_new].copy()
