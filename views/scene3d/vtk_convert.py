"""The one place where core's plain data becomes pyvista/VTK geometry.

core describes cameras and objects with numpy arrays in its own conventions
(:mod:`core.projection`); VTK wants ``PolyData`` with padded face arrays and
a ``vtkCamera``.  Every conversion between the two lives here.
"""

from __future__ import annotations

import functools

import numpy as np
import pyvista as pv
from vtkmodules.vtkCommonCore import vtkStringArray

from core.camera import Camera
from core.scene import Mesh, Sphere


def set_labels(poly: pv.PolyData, labels) -> pv.PolyData:
    """Give ``poly``'s points the texts ``labels`` (its ``"labels"`` array); returns ``poly``.

    The strings go to VTK as they are (UTF-8), so a label may say A′ or Δ: pyvista's own
    conversion of a string array takes ASCII only.
    """
    array = vtkStringArray()
    array.SetName("labels")
    for label in labels:
        array.InsertNextValue(str(label))
    poly.GetPointData().AddArray(array)
    return poly


def _faces(triangles: np.ndarray) -> np.ndarray:
    """VTK's padded face array: ``[3, i0, i1, i2, 3, ...]``."""
    triangles = np.asarray(triangles, dtype=np.int64)
    return np.hstack([np.full((len(triangles), 1), 3), triangles]).ravel()


def mesh_polydata(mesh: Mesh) -> pv.PolyData:
    """A core :class:`Mesh` as a triangle ``PolyData`` (flat faces)."""
    return pv.PolyData(np.array(mesh.vertices), _faces(mesh.triangles))


@functools.cache
def _unit_sphere(theta_resolution: int, phi_resolution: int, edges: bool) -> pv.PolyData:
    """pyvista's sphere of radius 1 at the origin (its edges only if ``edges``), made once."""
    sphere = pv.Sphere(radius=1.0, center=(0.0, 0.0, 0.0), theta_resolution=theta_resolution,
                       phi_resolution=phi_resolution)
    return sphere.extract_all_edges() if edges else sphere


def placed_sphere(center, radius: float, theta_resolution: int = 48, phi_resolution: int = 32,
                  edges: bool = False) -> pv.PolyData:
    """pyvista's ``Sphere`` of that centre, radius and resolution (or its edges, as
    ``extract_all_edges`` gives them), scaled and moved from one made once: making it anew took
    5-10 ms of the GUI thread per sphere, and a lesson step shows its scene's spheres and the
    bounding spheres of its other objects.  Each call gives a polydata of its own."""
    unit = _unit_sphere(theta_resolution, phi_resolution, edges)
    poly = unit.copy(deep=True)  # the normals too: the same wherever and however large
    poly.points = (unit.points * float(radius) + np.asarray(center, dtype=float)).astype(unit.points.dtype)
    return poly


def sphere_polydata(sphere: Sphere) -> pv.PolyData:
    """A smooth tessellation of an analytic sphere, for display only."""
    return placed_sphere(sphere.center, sphere.radius)


def object_polydata(obj: Mesh | Sphere) -> pv.PolyData:
    return sphere_polydata(obj) if isinstance(obj, Sphere) else mesh_polydata(obj)


def outlines_polydata(polygons) -> pv.PolyData:
    """The edges of planar polygons, each (N_i, 3) world-space vertices in order, as closed lines
    in one PolyData: one actor however many polygons (an actor each cost about a millisecond to
    add and slowed every draw after)."""
    polygons = [np.asarray(p, dtype=float).reshape(-1, 3) for p in polygons]
    sizes = [len(p) for p in polygons]
    starts = np.cumsum([0, *sizes[:-1]])
    lines = [np.array([n + 1, *range(s, s + n), s]) for s, n in zip(starts, sizes, strict=True)]
    return pv.PolyData(np.vstack(polygons), lines=np.concatenate(lines))


def boxes_polydata(boxes) -> pv.PolyData:
    """The edges of axis-aligned boxes, (K, 2, 3) world-space ``(lo, hi)`` corners, as lines."""
    boxes = np.asarray(boxes, dtype=float).reshape(-1, 2, 3)
    corner = np.array([[i, j, k] for k in (0, 1) for j in (0, 1) for i in (0, 1)])
    edges = [(0, 1), (2, 3), (4, 5), (6, 7), (0, 2), (1, 3), (4, 6), (5, 7), (0, 4), (1, 5), (2, 6), (3, 7)]
    points = (boxes[:, None, 0] + corner[None] * (boxes[:, None, 1] - boxes[:, None, 0])).reshape(-1, 3)
    base = 8 * np.arange(len(boxes))[:, None, None]
    lines = np.concatenate([np.full((len(boxes), 12, 1), 2), base + np.array(edges)], axis=2)
    return pv.PolyData(points, lines=lines.ravel())


FRUSTUM_QUADS = [[0, 1, 2, 3], [4, 7, 6, 5], [0, 4, 5, 1], [1, 5, 6, 2], [2, 6, 7, 3], [3, 7, 4, 0]]
"""The frustum's six sides (near, far, bottom, right, top, left) as indices into its eight corners,
ordered as :meth:`core.camera.Camera.frustum_corners` gives them (near plane, then far plane)."""
FRUSTUM_EDGES = [(0, 1), (1, 2), (2, 3), (3, 0), (4, 5), (5, 6), (6, 7), (7, 4),
                 (0, 4), (1, 5), (2, 6), (3, 7)]
"""The frustum's twelve edges: around the near plane, around the far plane, then near to far."""


def line_cells(pairs) -> np.ndarray:
    """The padded line array (``[2, a, b, 2, c, d, ...]``) of the point index pairs ``pairs``."""
    return np.hstack([[2, a, b] for a, b in pairs])


def frustum_polydata(corners: np.ndarray) -> pv.PolyData:
    """The viewing pyramid truncated by the near and far planes: the 8 ``corners``, 6 quads."""
    return pv.PolyData(corners, np.hstack([[4, *q] for q in FRUSTUM_QUADS]))


def frustum_edges_polydata(corners: np.ndarray) -> pv.PolyData:
    """The frustum's 12 edges, as lines between its 8 ``corners``."""
    return pv.PolyData(corners, lines=line_cells(FRUSTUM_EDGES))


def screen_polydata(camera: Camera) -> pv.PolyData:
    """The screen rectangle: the frustum's cross-section on the near plane."""
    return pv.PolyData(camera.screen_corners(), np.array([4, 0, 1, 2, 3]))


def sight_line_polydata(camera: Camera) -> pv.PolyData:
    """The viewing axis from the eye to the target."""
    return pv.Line(camera.eye, camera.target)


def observer_glyph(camera: Camera, size: float) -> pv.PolyData:
    """A small camera: a box body at the eye with a lens cone looking forward."""
    forward = camera.forward
    body = pv.Cube(center=camera.eye, x_length=size, y_length=size, z_length=size)
    rot = camera.world_from_view[:3, :3]
    body.points = (body.points - camera.eye) @ rot.T + camera.eye
    lens = pv.Cone(
        center=np.add(camera.eye, forward * size * 0.9),
        direction=-forward,
        height=size * 0.8,
        radius=size * 0.45,
        resolution=24,
    )
    return body.merge(lens)


def apply_camera(vtk_camera, camera: Camera) -> None:
    """Make a pyvista/VTK camera look exactly like ``camera`` (the same image)."""
    vtk_camera.position = camera.eye
    vtk_camera.focal_point = camera.target
    vtk_camera.up = camera.up
    vtk_camera.view_angle = camera.fov_y_deg
    vtk_camera.clipping_range = (camera.near, camera.far)
    vtk_camera.parallel_projection = camera.projection == "orthographic"
    vtk_camera.parallel_scale = camera.ortho_height / 2.0
