"""Rasterization: the fill rule tiles the screen exactly once, depth is exact on the plane."""

from __future__ import annotations

import numpy as np
import pytest

from core.camera import Camera
from core.object_order import rasterization, zbuffer
from core.object_order.pipeline import render_raster
from core.scene import Mesh, Scene


def coverage_counts(triangles_xy, width, height) -> np.ndarray:
    """(H, W) int: how many of the given pixel-space triangles produced a fragment at each pixel.

    Every triangle is its own polygon and all lie at the same depth, so the
    count includes fragments that failed the depth test.
    """
    tris = np.asarray(triangles_xy, dtype=float).reshape(-1, 3, 2)
    xy = tris.reshape(-1, 2)
    corners = np.arange(len(xy)).reshape(-1, 3)
    n = len(tris)
    result = zbuffer.draw(xy, np.full(len(xy), 0.5), corners, np.arange(n), np.ones((n, 3)), np.ones(n),
                          width, height, (0, 0, 0), record=True)
    return np.bincount(result.fragments.pixel, minlength=width * height).reshape(height, width)


def test_square_of_two_triangles_covers_each_pixel_once_even_with_edges_through_centres():
    # Corners at pixel centres: all four sides and the diagonal run exactly through
    # pixel centres, so only the top-left rule decides who owns them.
    a, b, c, d = (2.5, 2.5), (10.5, 2.5), (10.5, 10.5), (2.5, 10.5)
    counts = coverage_counts([[a, b, c], [a, c, d]], 16, 16)
    expected = np.zeros((16, 16), int)
    expected[2:10, 2:10] = 1  # left and top sides included, right and bottom excluded
    assert np.array_equal(counts, expected)


@pytest.mark.parametrize("seed", range(5))
def test_fan_around_a_vertex_covers_each_pixel_once(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 13))
    hub = np.array([20.5, 15.5])  # on a pixel centre: every spoke passes through it
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    rim = hub + 12 * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    fan_around_hub = [[hub, rim[k], rim[(k + 1) % n]] for k in range(n)]
    counts = coverage_counts(fan_around_hub, 40, 32)
    assert counts.max() == 1
    assert counts[15, 20] == 1
    # The same convex polygon triangulated differently (fan from its first rim
    # vertex) covers exactly the same pixels: no gaps inside, same boundary.
    fan_from_rim = [[rim[0], rim[k], rim[k + 1]] for k in range(1, n - 1)]
    other = coverage_counts(fan_from_rim, 40, 32)
    assert other.max() == 1
    assert np.array_equal(counts, other)


@pytest.mark.parametrize("seed", range(4))
def test_mesh_of_random_triangles_is_watertight(seed):
    """A grid of jittered points, triangulated: every pixel centre inside the grid exactly once."""
    rng = np.random.default_rng(seed)
    gx, gy = np.meshgrid(np.linspace(4, 60, 8), np.linspace(4, 44, 6))
    pts = np.stack([gx, gy], axis=-1)
    pts[1:-1, 1:-1] += rng.uniform(-2.5, 2.5, pts[1:-1, 1:-1].shape)
    tris = []
    for j in range(5):
        for i in range(7):
            p00, p10, p01, p11 = pts[j, i], pts[j, i + 1], pts[j + 1, i], pts[j + 1, i + 1]
            tris += [[p00, p10, p11], [p00, p11, p01]] if (i + j) % 2 else [[p00, p10, p01], [p10, p11, p01]]
    tris = np.array(tris)
    tris[1::3] = tris[1::3, ::-1]  # the fill rule does not depend on the winding
    counts = coverage_counts(tris, 64, 48)
    assert counts.max() == 1
    # Every pixel whose centre lies strictly inside the outer rectangle is covered.
    assert counts[4:44, 4:60].min() == 1
    assert counts.sum() == 40 * 56


@pytest.mark.parametrize("seed", range(3))
def test_kernel_matches_reference_coverage(seed):
    rng = np.random.default_rng(seed)
    width, height = 48, 40
    for _ in range(30):
        tri = rng.uniform(-8, 56, (3, 2))
        if rng.random() < 0.3:  # corners on pixel centres and edges through them
            tri = np.floor(tri) + 0.5
        kernel = coverage_counts([tri], width, height)
        reference = rasterization.coverage(rasterization.snap(tri), width, height)
        assert np.array_equal(kernel, reference.astype(int))


def test_is_top_left_agrees_with_coverage_of_edge_pixels():
    # A right triangle with a vertical left edge and a horizontal top edge through centres.
    tri = np.array([[1.5, 1.5], [1.5, 6.5], [6.5, 1.5]])
    cov = rasterization.coverage(rasterization.snap(tri), 10, 10)
    assert cov[1, 1] and cov[5, 1] and cov[1, 5]  # top and left edges owned
    assert not cov[6, 1] and not cov[1, 6]  # the far corners are not


def test_depth_planes_reproduce_corner_depths():
    rng = np.random.default_rng(7)
    xy = rng.uniform(0, 100, (20, 3, 2))
    z = rng.uniform(0, 1, (20, 3))
    planes = rasterization.depth_planes(xy, z)
    for k in range(3):
        p = xy[:, k] - xy[:, 0]
        assert np.allclose(planes[:, 0] + p[:, 0] * planes[:, 1] + p[:, 1] * planes[:, 2], z[:, k])


CAMERAS = [
    Camera(eye=(1.0, 2.0, 6.0), target=(0.0, 0.0, 0.0), fov_y_deg=50, near=0.5, far=40,
           width=120, height=90),
    Camera(eye=(1.0, 2.0, 6.0), target=(0.0, 0.0, 0.0), projection="orthographic", ortho_height=5,
           near=0.5, far=40, width=120, height=90),
]


@pytest.mark.parametrize("cam", CAMERAS, ids=["perspective", "orthographic"])
def test_depth_is_exact_on_the_triangle_plane(cam):
    """Rasterized depth = the analytic distance of the plane along each pixel's ray."""
    corners = np.array([[-3.0, -1.0, -4.0], [3.5, -1.5, 1.0], [-0.5, 2.5, -1.0]])
    scene = Scene(camera=cam, objects=(Mesh(corners, [[0, 1, 2]]),))
    depth = render_raster(scene).depth
    covered = np.isfinite(depth)
    assert covered.mean() > 0.1
    origins, directions = cam.primary_rays()
    normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    t = ((corners[0] - origins) @ normal) / (directions @ normal)
    hits = origins + t[..., None] * directions
    analytic = (hits - np.asarray(cam.eye)) @ cam.forward  # distance along the viewing axis
    assert np.allclose(depth[covered], analytic[covered], rtol=1e-9, atol=0)


def test_window_coordinates_map_the_frustum_corners_to_the_image_corners():
    cam = Camera(width=200, height=100)
    clip = (cam.clip_from_world @ np.c_[cam.frustum_corners(), np.ones(8)].T).T
    xy, z = rasterization.window_coordinates(clip, 200, 100)
    assert np.allclose(xy[:4], [[0, 100], [200, 100], [200, 0], [0, 0]])
    assert np.allclose(z, [0, 0, 0, 0, 1, 1, 1, 1])


def test_fan_triangles_keep_polygons_in_drawing_order():
    corners, position = rasterization.fan_triangles(np.array([0, 4, 7, 7]), np.array([2, 1, 0]))
    assert corners.tolist() == [[4, 5, 6], [0, 1, 2], [0, 2, 3]]
    assert position.tolist() == [1, 2, 2]
