"""Frustum culling with the bounding spheres the pipeline keeps from frame to frame.

A mesh drawn again reuses its bounding sphere; what the frustum culling
reports must still be what the mesh's vertices give now (the middle of their
box and the farthest vertex from it, worked out here with numpy), whichever
meshes were drawn before, and a mesh whose numbers can still be changed
through the array they view is measured afresh.
"""

from __future__ import annotations

import numpy as np

from core import shapes
from core.camera import Camera
from core.object_order.pipeline import render_raster
from core.scene import Mesh, PointLight, Scene


def _scene(mesh: Mesh) -> Scene:
    camera = Camera(eye=(0.0, 0.0, 6.0), target=(0.0, 0.0, 0.0), fov_y_deg=40, near=0.5, far=20.0,
                    width=64, height=48)
    return Scene(camera=camera, objects=(mesh,), lights=(PointLight((3.0, 5.0, 6.0)),))


def _sphere_of(vertices: np.ndarray) -> tuple[np.ndarray, float]:
    center = (vertices.min(axis=0) + vertices.max(axis=0)) / 2
    return center, float(np.sqrt(((vertices - center) ** 2).sum(axis=1).max()))


def test_meshes_drawn_in_turn_keep_their_own_spheres():
    small = shapes.uv_sphere((0.5, 0.0, 0.0), 0.4, 8, 16)
    large = shapes.uv_sphere((-1.0, 0.5, 0.0), 1.5, 10, 20)
    for mesh in (small, large, small, large):
        objects = render_raster(_scene(mesh)).objects
        center, radius = _sphere_of(mesh.vertices)
        assert np.allclose(objects.center[0], center) and np.isclose(objects.radius[0], radius)


def test_a_mesh_moved_through_the_array_it_views_is_culled_where_it_is_now():
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 0.5, 8, 16)
    storage = np.vstack([np.zeros((1, 3)), ball.vertices])  # writeable; the mesh views its rows
    mesh = Mesh(storage[1:], ball.triangles)
    assert render_raster(_scene(mesh)).stats["objects_inside"] == 1
    storage[1:, 0] += 100.0  # far to the right of the view
    moved = render_raster(_scene(mesh))
    assert moved.stats["objects_outside"] == 1 and moved.stats["fragments_generated"] == 0
    assert np.allclose(moved.objects.center[0], _sphere_of(mesh.vertices)[0])
