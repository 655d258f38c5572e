"""Our camera against VTK's: the same frustum, and the same pixels covered."""

import brute_force
import numpy as np
import pytest
import pyvista as pv

from core.camera import Camera
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.scene import Mesh, Scene, Sphere
from views.scene3d import vtk_convert

pytestmark = pytest.mark.gui

CAMERAS = [
    Camera(eye=(6, 4, 9), target=(0, 0.8, 0), fov_y_deg=40, near=1, far=30, width=320, height=240),
    Camera(eye=(-3, 1, 4), target=(0.5, 0, 0), fov_y_deg=70, near=0.5, far=12, width=200,
           height=150),
    Camera(eye=(6, 4, 9), target=(0, 0.8, 0), projection="orthographic", ortho_height=6,
           near=1, far=30, width=320, height=240),
]


def _sorted_rows(points):
    return points[np.lexsort(np.round(points, 6).T)]


@pytest.mark.parametrize("cam", CAMERAS[:2])
def test_frustum_matches_vtk_view_frustum(cam):
    vtk_cam = pv.Camera()
    vtk_convert.apply_camera(vtk_cam, cam)
    theirs = np.asarray(vtk_cam.view_frustum(cam.aspect).points)
    assert np.allclose(_sorted_rows(cam.frustum_corners()), _sorted_rows(theirs), atol=1e-6)


def _corner_pairs(poly: pv.PolyData, corners: np.ndarray) -> set[frozenset[int]]:
    """``poly``'s edges as pairs of indices of the nearest of ``corners``."""
    edges = poly.extract_all_edges()
    nearest = [int(np.argmin(np.linalg.norm(corners - p, axis=1))) for p in np.asarray(edges.points)]
    lines = edges.lines.reshape(-1, 3)[:, 1:]
    return {frozenset((nearest[a], nearest[b])) for a, b in lines}


@pytest.mark.parametrize("cam", CAMERAS)
def test_the_drawn_frustum_edges_and_sides_are_vtks(cam):
    """The 3D pane's and the frustum overlay's edges join the corners VTK's own frustum joins."""
    vtk_cam = pv.Camera()
    vtk_convert.apply_camera(vtk_cam, cam)
    corners = cam.frustum_corners()
    theirs = _corner_pairs(vtk_cam.view_frustum(cam.aspect), corners)
    assert len(theirs) == 12
    assert _corner_pairs(vtk_convert.frustum_edges_polydata(corners), corners) == theirs
    assert _corner_pairs(vtk_convert.frustum_polydata(corners), corners) == theirs


def _scene(cam):
    box = Mesh(
        vertices=[[x, y, z] for x in (-1, 1) for y in (0, 2) for z in (-1, 1)],
        triangles=[[0, 1, 3], [0, 3, 2], [4, 6, 7], [4, 7, 5], [0, 4, 5], [0, 5, 1],
                   [2, 3, 7], [2, 7, 6], [0, 2, 6], [0, 6, 4], [1, 5, 7], [1, 7, 3]],
    )
    return Scene(camera=cam, objects=(box, Sphere(center=(2.2, 0.8, 1.5), radius=0.8)))


@pytest.mark.parametrize("cam", CAMERAS)
@pytest.mark.parametrize("caster", ["brute force", "compiled tracer"])
def test_ray_cast_coverage_matches_vtk_render(cam, caster):
    """Which pixels show an object: our ray casters against VTK's rasterizer."""
    scene = _scene(cam)
    if caster == "brute force":
        ours = brute_force.cast(scene).object_index >= 0
    else:
        ours = render_trace(scene, TraceSettings(mode="raycast")).object_index >= 0
    plotter = pv.Plotter(off_screen=True, window_size=(cam.width, cam.height))
    plotter.disable_anti_aliasing()
    plotter.set_background("black")
    for obj in scene.objects:
        poly = vtk_convert.object_polydata(obj)
        if isinstance(obj, Sphere):  # a finely tessellated sphere, close to the true one
            poly = pv.Sphere(radius=obj.radius, center=obj.center,
                             theta_resolution=256, phi_resolution=256)
        plotter.add_mesh(poly, color="white", lighting=False)
    vtk_convert.apply_camera(plotter.camera, cam)
    theirs = plotter.screenshot(return_img=True).sum(axis=2) > 0
    plotter.close()
    assert ours.sum() > 0.05 * ours.size
    agreement = np.mean(ours == theirs)
    assert agreement > 0.995, f"coverage agrees on only {agreement:.4f} of pixels"


def test_outlines_are_each_polygons_edges_and_no_others():
    triangle = [(0, 0, 0), (1, 0, 0), (0, 1, 0)]
    square = [(0, 0, 2), (1, 0, 2), (1, 1, 2), (0, 1, 2)]
    edges = vtk_convert.outlines_polydata([triangle, square]).extract_all_edges()
    points = edges.points
    segments = edges.lines.reshape(-1, 3)[:, 1:]
    found = {frozenset(tuple(points[i]) for i in pair) for pair in segments}
    expected = {frozenset((tuple(map(float, p[k])), tuple(map(float, p[(k + 1) % len(p)]))))
                for p in (triangle, square) for k in range(len(p))}
    assert found == expected  # 3 + 4 edges, none across a polygon or between the two


@pytest.mark.parametrize("center, radius", [((0.0, 0.0, 0.0), 1.0), ((1.5, -0.25, 4.0), 0.3),
                                            ((-20.0, 7.0, 0.5), 12.0)])
def test_a_sphere_is_pyvistas_sphere_of_that_centre_and_radius(center, radius):
    """The pane's spheres (objects, light markers) are scaled and moved from one tessellation made
    once: the points, faces and normals of the sphere pyvista makes for that centre and radius (points
    to float32's precision), and for a bounding sphere's wire frame the edges pyvista extracts from it."""
    near = 1e-6 * (radius + np.abs(center).max())
    ours = vtk_convert.sphere_polydata(Sphere(center, radius))
    theirs = pv.Sphere(radius=radius, center=center, theta_resolution=48, phi_resolution=32)
    assert np.allclose(ours.points, theirs.points, rtol=0, atol=near)
    assert np.array_equal(ours.faces, theirs.faces)
    assert np.allclose(ours.point_normals, theirs.point_normals, atol=1e-6)
    assert np.allclose(np.linalg.norm(ours.points - np.asarray(center), axis=1), radius, rtol=1e-3)
    marker = vtk_convert.placed_sphere(center, radius, 30, 30)  # a light's, at pyvista's own resolution
    assert np.allclose(marker.points, pv.Sphere(radius=radius, center=center).points, rtol=0, atol=near)
    wire = vtk_convert.placed_sphere(center, radius, 24, 16, edges=True)
    edges = pv.Sphere(radius=radius, center=center, theta_resolution=24, phi_resolution=16)
    edges = edges.extract_all_edges()
    assert np.allclose(wire.points, edges.points, rtol=0, atol=near)
    assert np.array_equal(wire.lines, edges.lines) and len(wire.faces) == 0
    # Each call gives its own points: an overlay that takes new points into a drawn sphere changes no other.
    again = vtk_convert.sphere_polydata(Sphere(center, radius))
    again.points[:] = 0.0
    fresh = vtk_convert.sphere_polydata(Sphere(center, radius))
    assert np.allclose(fresh.points, theirs.points, rtol=0, atol=near)
