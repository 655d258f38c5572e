"""Back-face culling by the normal, frustum culling by bounding spheres."""

from __future__ import annotations

import math

import numpy as np
import pytest

from core import shapes
from core.camera import Camera
from core.object_order import culling, stages

CORNER_VIEW = [
    Camera(eye=(5.0, 4.0, 6.0), target=(0.0, 0.0, 0.0)),
    Camera(eye=(5.0, 4.0, 6.0), target=(0.0, 0.0, 0.0), projection="orthographic"),
]


def _view_space(cam, mesh):
    m = cam.view_from_world
    return mesh.vertices @ m[:3, :3].T + m[:3, 3]


@pytest.mark.parametrize("cam", CORNER_VIEW, ids=["perspective", "orthographic"])
def test_cube_seen_from_a_corner_shows_exactly_three_faces(cam):
    cube = shapes.box((0.0, 0.0, 0.0), 2.0)
    ortho = cam.projection == "orthographic"
    result = stages.back_face_culling(_view_space(cam, cube), cube.triangles, ortho)
    visible_normals = {tuple(n) for n in cube.normals[result.visible].round(9).tolist()}
    assert visible_normals == {(1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)}
    assert result.visible.sum() == 6  # two triangles per square face
    # The recorded normals are the world normals turned into view space.
    assert np.allclose(result.normal, cube.normals @ cam.view_from_world[:3, :3].T)
    assert np.array_equal(result.nz, result.normal[:, 2])


def test_perspective_test_uses_the_vector_to_the_eye_not_nz():
    # A wall to the right of the eye, facing the viewing axis and turned slightly away
    # from the observer along z: Nz < 0 (the parallel projection's test would cull it),
    # yet the eye, at the origin, is in front of it.
    wall = np.array([[3.0, -1.0, -4.0], [3.0, 1.0, -4.0], [3.2, 0.0, -6.0]])
    result = stages.back_face_culling(wall, np.array([[0, 1, 2]]), orthographic=False)
    assert result.nz[0] < 0
    assert result.visible[0]
    assert not culling.is_back_facing(wall)
    assert culling.is_back_facing(wall, orthographic=True)


def test_perspective_culling_agrees_with_the_winding_on_screen():
    """Property: a face passes exactly when its projection runs counter-clockwise on screen."""
    rng = np.random.default_rng(3)
    cam = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=70)
    tris = rng.uniform(-2, 2, (300, 3, 3)) + [0, 0, -5]
    result = stages.back_face_culling(tris.reshape(-1, 3), np.arange(900).reshape(-1, 3), False)
    ndc = np.array([[cam.project(p).ndc[:2] for p in tri] for tri in tris])
    e1, e2 = ndc[:, 1] - ndc[:, 0], ndc[:, 2] - ndc[:, 0]
    ccw = e1[:, 0] * e2[:, 1] - e1[:, 1] * e2[:, 0] > 0  # NDC has y up
    assert np.array_equal(result.visible, ccw)


def test_frustum_culling_of_spheres_around_the_default_camera():
    cam = Camera()
    planes = cam.frustum_planes()
    forward = cam.forward
    eye = np.asarray(cam.eye)
    hw, hh = cam.half_extent(10.0)
    on_right_plane = cam.world_from_view @ [hw, 0.0, -10.0, 1.0]
    centers = np.array([
        cam.target,  # inside
        eye - 3 * forward,  # behind the observer
        on_right_plane[:3],  # straddling the right plane
        eye + (cam.far + 2) * forward,  # beyond the far plane
        eye + 0.5 * cam.near * forward,  # around the near plane
    ])
    result = culling.frustum_culling(centers, np.full(5, 1.0), planes)
    assert result.state == ("inside", "outside", "crossing", "outside", "crossing")
    assert result.count("outside") == 2
    assert result.distance.shape == (5, 6)


@pytest.mark.parametrize("seed", range(3))
def test_frustum_classification_is_conservative(seed):
    """Property: "outside" spheres have no point inside the frustum, "inside" ones no point outside."""
    rng = np.random.default_rng(seed)
    cam = Camera(near=1.0, far=12.0)
    planes = cam.frustum_planes()
    centers = rng.uniform(-10, 14, (200, 3))
    radii = rng.uniform(0.2, 3.0, 200)
    result = culling.frustum_culling(centers, radii, planes)
    directions = rng.normal(size=(400, 3))
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    for c, r, state in zip(centers, radii, result.state, strict=True):
        points = c + r * rng.uniform(0, 1, (400, 1)) ** (1 / 3) * directions
        inside = np.all(points @ planes[:, :3].T + planes[:, 3] >= 0, axis=1)
        if state == "outside":
            assert not inside.any()
        elif state == "inside":
            assert inside.all()


def test_bounding_sphere_is_centred_on_the_box_and_reaches_the_farthest_vertex():
    mesh = shapes.cone((1.0, 2.0, 3.0), 1.5, 2.0, segments=17)
    center, radius = mesh.bounding_sphere()
    # The cone stands on y = 2 and rises 2, so the box's middle is at y = 3; in x and z the
    # 17-gon's box is not symmetric about the axis, so take its middle from the corners.
    corners = mesh.vertices.tolist()
    box_middle = [(min(v[k] for v in corners) + max(v[k] for v in corners)) / 2 for k in range(3)]
    assert center[1] == 3.0 and np.allclose(center, box_middle, rtol=0, atol=1e-15)
    farthest = max(math.dist(v, center) for v in mesh.vertices.tolist())
    assert radius == pytest.approx(farthest, rel=1e-15)


def test_frustum_culling_tests_each_object_by_its_one_bounding_sphere():
    """The render's frustum culling and the image order's sphere test use the same sphere: a
    cube's around its box, an analytic sphere itself (padded in image order for meshes only)."""
    from core.image_order.bounding_spheres import PAD, bounding_spheres
    from core.object_order.pipeline import render_raster
    from core.scene import Scene, Sphere

    # A cube of edge 2 centred on (1, 2, -6): its box's middle is the centre, and every corner
    # is sqrt(1 + 1 + 1) = sqrt(3) from it.
    cube = shapes.box((1.0, 2.0, -6.0), 2.0)
    ball = Sphere((-1.5, 0.0, -8.0), 1.25)
    scene = Scene(camera=Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), width=40, height=30),
                  objects=(cube, ball))
    objects = render_raster(scene).objects
    assert objects.center.tolist() == [[1.0, 2.0, -6.0], [-1.5, 0.0, -8.0]]
    assert objects.radius[0] == pytest.approx(math.sqrt(3), rel=1e-15) and objects.radius[1] == 1.25
    cube_sphere, ball_sphere = bounding_spheres(scene)
    assert cube_sphere.center.tolist() == [1.0, 2.0, -6.0] and not cube_sphere.exact
    assert cube_sphere.radius == objects.radius[0] * (1 + PAD) + PAD * 6.0
    assert ball_sphere.radius == 1.25 and ball_sphere.exact
    # A mesh's sphere is found once: asked again, the same (read-only) centre comes back.
    assert cube.bounding_sphere()[0] is cube.bounding_sphere()[0]
    assert not cube.bounding_sphere()[0].flags.writeable
