"""Projection stages: world -> camera -> clip -> NDC -> pixels, checked by geometry."""

import math

import numpy as np
import pytest

from core import projection
from core.camera import Camera


def test_look_at_puts_eye_at_origin_and_target_down_minus_z():
    eye, target = np.array([3.0, 2.0, 5.0]), np.array([-1.0, 0.5, 0.0])
    m = projection.look_at(eye, target, (0, 1, 0))
    assert np.allclose(m @ [*eye, 1], [0, 0, 0, 1])
    dist = np.linalg.norm(target - eye)
    assert np.allclose(m @ [*target, 1], [0, 0, -dist, 1])
    rot = m[:3, :3]
    assert np.allclose(rot @ rot.T, np.eye(3))  # a rigid motion: no scaling, no shear
    assert np.linalg.det(rot) == pytest.approx(1.0)  # right-handed stays right-handed
    # A point straight above the eye stays "up" (+y) for the observer.
    assert (m @ [*(eye + [0, 1, 0]), 1])[1] > 0


@pytest.mark.parametrize("fov", [20.0, 60.0, 120.0])
def test_perspective_maps_frustum_edges_to_ndc_cube(fov):
    near, far, aspect = 0.5, 40.0, 1.5
    p = projection.perspective(fov, aspect, near, far)
    half = math.tan(math.radians(fov) / 2)  # similar triangles: top edge at y = depth * half
    for depth, ndc_z in ((near, -1.0), (far, 1.0)):
        top_right = [depth * half * aspect, depth * half, -depth, 1.0]
        clip = p @ top_right
        assert clip[3] == pytest.approx(depth)  # w is the depth along the viewing axis
        assert np.allclose(clip[:3] / clip[3], [1, 1, ndc_z])


def test_perspective_is_the_lecture_similar_triangles():
    # A point at depth z projects onto the plane at distance 1 at (x / z, y / z).
    p = projection.perspective(90.0, 1.0, 1.0, 100.0)  # tan(45°) = 1: NDC = x / depth
    clip = p @ [2.0, -3.0, -8.0, 1.0]
    assert np.allclose(clip[:2] / clip[3], [2 / 8, -3 / 8])


def test_orthographic_keeps_x_y_whatever_the_depth():
    o = projection.orthographic(4.0, 2.0, 1.0, 11.0)
    for depth in (1.0, 5.0, 11.0):
        ndc = o @ [4.0, 2.0, -depth, 1.0]
        assert ndc[3] == 1.0
        assert np.allclose(ndc[:2], [1.0, 1.0])  # half width 4, half height 2
    assert (o @ [0, 0, -1.0, 1])[2] == pytest.approx(-1.0)
    assert (o @ [0, 0, -11.0, 1])[2] == pytest.approx(1.0)


def test_lecture_perspective_projects_through_the_eye_onto_z0():
    d = 3.0
    point = np.array([2.0, 4.0, 6.0])
    h = projection.lecture_perspective(d) @ [*point, 1.0]
    projected = h[:3] / h[3]
    eye = np.array([0.0, 0.0, -d])
    # The projected point is on the screen plane and on the line from the eye through the point.
    assert projected[2] == 0.0
    assert np.allclose(np.cross(projected - eye, point - eye), 0.0)


def test_project_point_records_every_stage_and_pixel_convention():
    cam = Camera(eye=(0, 0, 10), target=(0, 0, 0), up=(0, 1, 0), fov_y_deg=90, near=1, far=100,
                 width=200, height=100)
    centre = cam.project((0, 0, 0))
    assert np.allclose(centre.view, [0, 0, -10])
    assert centre.depth == pytest.approx(10)
    assert np.allclose(centre.pixel, [100, 50])  # image centre
    # At depth 10 with alpha = 90°, the top edge is y = 10, the right edge x = 20.
    top_left = cam.project((-20, 10, 0))
    assert np.allclose(top_left.ndc[:2], [-1, 1])
    assert np.allclose(top_left.pixel, [0, 0])  # pixels: y grows downward from the top
    assert centre.inside and top_left.inside


def test_point_behind_the_eye_is_not_mirrored_into_the_image():
    cam = Camera(eye=(0, 0, 10), target=(0, 0, 0), up=(0, 1, 0))
    behind = cam.project((1, 1, 20))
    assert behind.clip[3] < 0
    assert behind.ndc is None and behind.pixel is None
    assert not behind.inside
