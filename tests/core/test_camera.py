"""The observer's frustum, planes, rays and orbit controls."""

import math

import numpy as np
import pytest

from core.camera import MIN_NEAR_RATIO, MIN_PIXEL, Camera, camera_problems
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.object_order.pipeline import render_raster
from core.scene import Scene
from core.shapes import box

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


@pytest.mark.parametrize(
    ("changes", "field"),
    [
        # closer than ~1e-162 the squared distance underflows: once a NaN camera was accepted
        ({"eye": (0, 0, 1e-170), "target": (0, 0, 0)}, "target"),
        ({"eye": (1e5, 0, 0), "target": (1e5, 0, 1e-6)}, "target"),
        ({"near": 1e-15}, "near"),
        ({"fov_y_deg": 1e-15}, "fov_y_deg"),
        ({"ortho_height": 1e-20}, "ortho_height"),
        ({"eye": (float("nan"), 0, 0)}, "eye"),
        ({"far": float("inf")}, "far"),
    ],
)
def test_cameras_are_judged_by_what_they_compute(changes, field):
    problems = camera_problems(Camera().replace(**changes))
    assert [f for f, _ in problems] == [field]
    assert "nan" not in problems[0][1].lower() or field == "eye"


def _extreme(projection: str, **changes) -> Scene:
    """A box seen head-on, with one camera setting pushed towards its limit."""
    cam = Camera(eye=(0, 0, 5), target=(0, 0, 0), width=48, height=36, projection=projection)
    scene = Scene(camera=cam.replace(**changes), objects=(box((0, 0, 0), 1.0),))
    assert camera_problems(scene.camera) == []
    return scene


@pytest.mark.parametrize(
    "projection, changes",
    [
        # just above each limit: both renderers must still agree
        ("perspective", {"near": 3 * MIN_NEAR_RATIO * 30.0}),
        ("perspective", {"fov_y_deg": 3 * math.degrees(MIN_PIXEL * 36), "eye": (0, 0, 5)}),
        ("orthographic", {"ortho_height": 3 * MIN_PIXEL * 36 * 30.0}),
    ],
)
def test_rasterizer_and_ray_caster_agree_at_the_accepted_extremes(projection, changes):
    scene = _extreme(projection, **changes)
    raster = render_raster(scene)
    traced = render_trace(scene, TraceSettings(mode="raycast"))
    # Each camera sees only the box's front face (z = 0.5) or all of it: the same either way.
    seen_r, seen_t = np.isfinite(raster.depth), np.isfinite(traced.depth)
    assert np.mean(seen_r == seen_t) > 0.97
    assert np.allclose(raster.depth[seen_r & seen_t], 4.5, rtol=1e-6)
