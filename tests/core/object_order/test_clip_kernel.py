"""The compiled clipper gives the readable clipper's polygons, and both give the exact ones.

Random triangles around the observer cross every plane of the frustum, and
many reach behind the eye (``w < 0``).  The compiled
:func:`core.object_order.stages.clip_triangles` must return, triangle by
triangle, bit-identical polygons to :func:`core.object_order.clipping.clip_polygon`,
and both must match Sutherland-Hodgman done here independently in exact
rational arithmetic (:class:`fractions.Fraction`).
"""

from __future__ import annotations

from fractions import Fraction

import numpy as np

from core.camera import Camera
from core.object_order import clipping, stages

CAM = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=60, near=0.5, far=8.0,
             width=64, height=48)


def _random_triangles(seed: int, n: int):
    """World triangles near the eye (many behind it), their clip coordinates."""
    rng = np.random.default_rng(seed)
    centre = rng.uniform([-3, -3, -9], [3, 3, 1], (n, 1, 3))
    world = (centre + rng.normal(0, 1.5, (n, 3, 3))).reshape(-1, 3)
    clip = (CAM.clip_from_world @ np.c_[world, np.ones(len(world))].T).T
    return world, clip, np.arange(3 * n).reshape(-1, 3)


def _exact_clip(vertices):
    """Sutherland-Hodgman in rationals: rows of 7 Fractions (clip x, y, z, w, world x, y, z)."""
    for plane in range(6):
        axis, sign = plane // 2, 1 if plane % 2 == 0 else -1
        dist = [v[3] + sign * v[axis] for v in vertices]
        out = []
        for e in range(len(vertices)):
            s = e - 1
            if (dist[s] >= 0) != (dist[e] >= 0):
                t = dist[s] / (dist[s] - dist[e])  # the crossing, as a point of the line s -> e
                out.append([a + t * (b - a) for a, b in zip(vertices[s], vertices[e], strict=True)])
            if dist[e] >= 0:
                out.append(vertices[e])
        vertices = out
        if not vertices:
            break
    return vertices


def _kernel_polygons(world, clip, triangles):
    result = stages.clip_triangles(np.arange(len(triangles)), triangles, clip, world)
    poly = result.polygons
    return result, {int(poly.face[p]): (poly.clip[poly.vertex[poly.offsets[p]:poly.offsets[p + 1]]],
                                        poly.world[poly.vertex[poly.offsets[p]:poly.offsets[p + 1]]])
                    for p in range(len(poly))}


def test_random_triangles_cross_every_plane_and_pass_behind_the_eye():
    world, clip, triangles = _random_triangles(1, 600)
    d = clipping.boundary_distances(clip[triangles])  # (T, 3, 6)
    crossing = (d.min(axis=1) < 0) & (d.max(axis=1) >= 0)
    assert np.all(crossing.sum(axis=0) >= 20)  # every one of the six planes cuts many
    assert (clip[triangles][..., 3] < 0).any(axis=1).sum() >= 50  # corners behind the eye
    result, _ = _kernel_polygons(world, clip, triangles)
    assert result.accepted >= 20 and result.rejected >= 20 and result.clipped >= 200


def test_kernel_gives_the_readable_clippers_polygons_bit_for_bit():
    world, clip, triangles = _random_triangles(2, 600)
    result, polygons = _kernel_polygons(world, clip, triangles)
    for t, tri in enumerate(triangles):
        ref_clip, ref_world = clipping.clip_polygon(clip[tri], world[tri])
        if len(ref_clip) < 3:
            assert t not in polygons
            continue
        got_clip, got_world = polygons[t]
        assert np.array_equal(got_clip, ref_clip) and np.array_equal(got_world, ref_world), t
    whole = ~result.polygons.clipped
    assert np.array_equal(result.polygons.vertex[np.repeat(whole, np.diff(result.polygons.offsets))],
                          triangles[result.polygons.face[whole]].ravel())


def test_kernel_polygons_are_the_exact_rational_clip():
    world, clip, triangles = _random_triangles(3, 300)
    _, polygons = _kernel_polygons(world, clip, triangles)
    compared = 0
    for t, tri in enumerate(triangles):
        rows = [[Fraction(float(v)) for v in (*clip[i], *world[i])] for i in tri]
        exact = _exact_clip(rows)
        if len(exact) < 3:
            assert t not in polygons
            continue
        got_clip, got_world = polygons[t]
        assert len(got_clip) == len(exact), t
        expected = np.array([[float(v) for v in row] for row in exact])
        assert np.allclose(np.c_[got_clip, got_world], expected, rtol=0, atol=1e-12), t
        compared += 1
    assert compared >= 150


def test_triangles_not_tested_are_kept_whole_even_outside():
    world, clip, triangles = _random_triangles(4, 50)
    result = stages.clip_triangles(np.arange(50), triangles, clip, world, np.zeros(50, dtype=bool))
    assert result.accepted == 50 and result.rejected == 0 and result.clipped == 0
    assert np.array_equal(result.polygons.vertex, triangles.ravel())
