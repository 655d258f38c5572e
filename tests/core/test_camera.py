"""The observer's frustum, planes, rays and orbit controls."""

import numpy as np
import pytest

from core.camera import Camera, camera_problems

CAMERAS = [
    Camera(),
    Camera(eye=(1, 2, 3), target=(4, -1, 0), fov_y_deg=75, near=0.3, far=12, width=640, height=480),
    Camera(projection="orthographic", ortho_height=5, width=300, height=100),
]


@pytest.mark.parametrize("cam", CAMERAS)
def test_frustum_corners_are_the_ndc_cube_corners(cam):
    corners = cam.frustum_corners()
    clip = np.c_[corners, np.ones(8)] @ cam.clip_from_world.T
    ndc = clip[:, :3] / clip[:, 3:]
    expected = [(x, y, z) for z in (-1, 1) for x, y in ((-1, -1), (1, -1), (1, 1), (-1, 1))]
    assert np.allclose(ndc, expected)


@pytest.mark.parametrize("cam", CAMERAS)
def test_frustum_planes_contain_corners_and_face_inwards(cam):
    planes = cam.frustum_planes()
    corners = cam.frustum_corners()
    signed = corners @ planes[:, :3].T + planes[:, 3]
    assert np.all(signed > -1e-9)  # every corner is on or inside every plane
    assert np.all(np.sum(np.abs(signed) < 1e-9, axis=1) == 3)  # each corner touches 3 planes
    inside = corners.mean(axis=0)
    assert np.all(planes[:, :3] @ inside + planes[:, 3] > 0)
    behind = np.asarray(cam.eye) - cam.forward
    assert (planes[4, :3] @ behind + planes[4, 3]) < 0  # behind the eye: outside the near plane


@pytest.mark.parametrize("cam", CAMERAS)
def test_primary_ray_through_a_pixel_centre_projects_back_to_it(cam):
    origins, directions = cam.primary_rays()
    rng = np.random.default_rng(1)
    for _ in range(10):
        j, i = rng.integers(cam.height), rng.integers(cam.width)
        point = origins[j, i] + 7.0 * directions[j, i]
        assert np.allclose(cam.project(point).pixel, [i + 0.5, j + 0.5])
    assert np.allclose(np.linalg.norm(directions, axis=-1), 1.0)


def test_orbit_keeps_distance_and_target():
    cam = Camera()
    moved = cam.orbit(cam.yaw_deg + 30, 10)
    assert moved.distance == pytest.approx(cam.distance)
    assert moved.target == cam.target
    assert moved.yaw_deg == pytest.approx(cam.yaw_deg + 30)
    assert moved.pitch_deg == pytest.approx(10)


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        ({"eye": (0, 0.8, 0)}, "target"),
        ({"eye": (0, 5, 0), "target": (0, 0, 0)}, "up"),
        ({"fov_y_deg": 0}, "fov_y_deg"),
        ({"fov_y_deg": 180}, "fov_y_deg"),
        ({"near": 0}, "near"),
        ({"near": 5, "far": 5}, "far"),
        ({"projection": "fisheye"}, "projection"),
    ],
)
def test_degenerate_cameras_are_named(changes, field):
    problems = camera_problems(Camera().replace(**changes))
    assert [f for f, _ in problems] == [field]
