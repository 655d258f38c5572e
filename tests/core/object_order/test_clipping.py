"""Clipping in clip space: correct polygons, nothing mirrored, neighbours stay watertight."""

from __future__ import annotations

import numpy as np
import pytest

from core.camera import Camera
from core.object_order import clipping, stages
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Mesh, Scene

CAM = Camera(eye=(0.0, 1.0, 0.0), target=(0.0, 1.0, -5.0), fov_y_deg=60, near=0.5, far=20,
             width=96, height=72)
# One corner 2 units behind the eye, two in front: the triangle crosses the near plane
# and the eye plane.  Dividing by w without clipping would throw the corner behind the
# eye to the mirrored side of the image.
BEHIND = np.array([[0.3, 0.2, 2.0], [-2.0, 0.0, -6.0], [2.5, 2.2, -4.0]])
# Behind the eye too, but its edges cross the near plane inside the near rectangle.
NEAR_ONLY = np.array([[0.0, 0.9, 0.6], [-0.4, 0.6, -1.6], [0.5, 1.3, -1.4]])


def _to_clip(points):
    return (CAM.clip_from_world @ np.c_[points, np.ones(len(points))].T).T


def test_triangle_reaching_behind_the_eye_is_cut_at_the_near_plane():
    clip, world = clipping.clip_polygon(_to_clip(NEAR_ONLY), NEAR_ONLY)
    assert len(clip) == 4  # the corner behind the eye is replaced by two near-plane points
    d = clipping.boundary_distances(clip)
    assert np.all(d >= -1e-12)  # every vertex inside all six planes
    assert np.all(clip[:, 3] > 0)  # nothing behind the eye is left to be mirrored
    on_near = np.abs(d[:, 4]) < 1e-12
    assert on_near.sum() == 2
    # The new vertices are where the edges from the hidden corner cross the near plane.
    view = (CAM.view_from_world @ np.c_[world, np.ones(4)].T).T
    assert np.allclose(-view[on_near, 2], CAM.near)
    for corner in (NEAR_ONLY[1], NEAR_ONLY[2]):
        edge = corner - NEAR_ONLY[0]
        t = ((world[on_near] - NEAR_ONLY[0]) @ edge) / (edge @ edge)
        closest = NEAR_ONLY[0] + t[:, None] * edge
        assert np.isclose(np.linalg.norm(world[on_near] - closest, axis=1), 0, atol=1e-12).any()
    # World and clip positions of the new vertices describe the same points.
    assert np.allclose(_to_clip(world), clip)


def _brute_force_coverage(cam, corners, jitter=0.0):
    """(H, W) bool: does the ray through each pixel (shifted by ``jitter``) meet the triangle
    between the near and far planes?  Moller-Trumbore, independent of the pipeline."""
    w, h = cam.width, cam.height
    hw, hh = cam.half_extent(1.0)
    xs = ((np.arange(w) + 0.5 + jitter) / w * 2 - 1) * hw
    ys = (1 - (np.arange(h) + 0.5 + jitter) / h * 2) * hh
    px, py = np.meshgrid(xs, ys)
    d = np.stack([px, py, -np.ones_like(px)], -1) @ cam.world_from_view[:3, :3].T
    o = np.asarray(cam.eye, dtype=float)
    a, b, c = corners
    e1, e2 = b - a, c - a
    p = np.cross(d, e2)
    det = p @ e1
    s = o - a
    u = (p @ s) / det
    q = np.cross(s, e1)
    v = (d @ q) / det
    t = (q @ e2) / det  # d has unit length along the viewing axis: t is the depth
    return (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= cam.near) & (t <= cam.far)


@pytest.mark.parametrize("corners", [BEHIND, NEAR_ONLY], ids=["near-and-side-planes", "near-plane"])
def test_clipped_triangle_covers_exactly_the_pixels_a_ray_caster_sees(corners):
    scene = Scene(camera=CAM, objects=(Mesh(corners, [[0, 1, 2]]),))
    result = render_raster(scene, RasterSettings(back_face_culling=False))
    assert result.stats["polygons_clipped"] == 1
    ours = np.isfinite(result.depth)
    samples = [_brute_force_coverage(CAM, corners, j) for j in (-0.02, 0.0, 0.02)]
    sure = (samples[0] == samples[1]) & (samples[1] == samples[2])  # away from the edges
    assert sure.mean() > 0.9
    assert np.array_equal(ours[sure], samples[1][sure])
    assert samples[1].mean() > 0.03


def test_without_clipping_the_same_triangle_comes_out_mirrored():
    scene = Scene(camera=CAM, objects=(Mesh(BEHIND, [[0, 1, 2]]),))
    wrong = np.isfinite(render_raster(scene, RasterSettings(back_face_culling=False,
                                                           clipping=False)).depth)
    truth = _brute_force_coverage(CAM, BEHIND)
    assert np.mean(wrong != truth) > 0.05


def test_edge_shared_by_two_triangles_gets_identical_new_vertices():
    # Two triangles sharing the edge BEHIND[0] - BEHIND[1], which crosses the near plane.
    other = np.array([BEHIND[1], BEHIND[0], [-3.0, 2.0, 0.5]])
    c1, w1 = clipping.clip_polygon(_to_clip(BEHIND), BEHIND)
    c2, w2 = clipping.clip_polygon(_to_clip(other), other)
    shared_1 = {tuple(v) for v in c1.tolist()}
    shared_2 = {tuple(v) for v in c2.tolist()}
    common = shared_1 & shared_2
    assert len(common) == 2  # the far end of the edge and its near-plane crossing, bit for bit


def test_clip_polygon_against_a_side_plane_is_the_hand_worked_cut():
    # A square 0 <= x <= 3, -0.5 <= y <= 0.5 at w = 1: the right plane x = w cuts it at x = 1.
    square = np.array([[0.0, -0.5, 0.0, 1.0], [3.0, -0.5, 0.0, 1.0], [3.0, 0.5, 0.0, 1.0],
                       [0.0, 0.5, 0.0, 1.0]])
    clip, _ = clipping.clip_polygon(square, square[:, :3])
    assert sorted(map(tuple, clip[:, :2].round(12).tolist())) == [
        (0.0, -0.5), (0.0, 0.5), (1.0, -0.5), (1.0, 0.5)]


def test_clip_polygon_outside_returns_nothing():
    outside = np.array([[5.0, 0.0, 0.0, 1.0], [6.0, 0.0, 0.0, 1.0], [5.0, 1.0, 0.0, 1.0]])
    clip, world = clipping.clip_polygon(outside, outside[:, :3])
    assert clip.shape == (0, 4) and world.shape == (0, 3)


def test_clip_triangles_sorts_out_accepted_rejected_and_cut():
    w = 1.0
    tris = np.array([
        [[0, 0, 0, w], [0.5, 0, 0, w], [0, 0.5, 0, w]],  # inside: accepted whole
        [[2, 0, 0, w], [3, 0, 0, w], [2, 1, 0, w]],  # right of x = w: rejected
        [[0, 0, 0, w], [2, 0, 0, w], [0, 0.5, 0, w]],  # crosses x = w: cut
        [[2, 2, 0, w], [-2, 2, 0, w], [0, 2.5, 0, w]],  # above y = w: rejected
    ], dtype=float)
    clip = tris.reshape(-1, 4)
    result = stages.clip_triangles(np.arange(4) + 10, np.arange(12).reshape(4, 3), clip, clip[:, :3])
    assert (result.accepted, result.rejected, result.clipped) == (1, 2, 1)
    polys = result.polygons
    assert polys.face.tolist() == [10, 12]
    assert polys.clipped.tolist() == [False, True]
    assert np.array_equal(polys.vertex[:3], [0, 1, 2])  # kept whole: the original vertices
    assert len(polys.world_vertices(1)) == 4
    assert len(result.clipped_polygons()) == 1


def test_untested_triangles_are_accepted_whole():
    clip = np.array([[5.0, 0.0, 0.0, 1.0], [6.0, 0.0, 0.0, 1.0], [5.0, 1.0, 0.0, 1.0]])
    result = stages.clip_triangles(np.array([0]), np.array([[0, 1, 2]]), clip, clip[:, :3],
                                     test=np.array([False]))
    assert (result.accepted, result.rejected) == (1, 0)


@pytest.mark.parametrize("seed", range(3))
def test_random_triangles_are_clipped_to_the_frustum(seed):
    """Property: whatever survives lies inside, and points of the original inside survive."""
    rng = np.random.default_rng(seed)
    for _ in range(40):
        tri = rng.uniform(-3, 3, (3, 3)) + [0, 1, -3]
        clip, world = clipping.clip_polygon(_to_clip(tri), tri)
        if len(clip):
            assert np.all(clipping.boundary_distances(clip) >= -1e-9)
            assert np.allclose(_to_clip(world), clip)
        # A random point of the triangle that is inside the frustum lies in the clipped polygon.
        bary = rng.dirichlet(np.ones(3), 20)
        inside = np.all(clipping.boundary_distances(_to_clip(bary @ tri)) > 1e-9, axis=1)
        assert len(clip) >= 3 or not inside.any()
