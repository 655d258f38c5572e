"""The 3D pane's objects and light markers, built without pyvista's add_mesh, look as add_mesh drew them.

A lesson step builds every object of its scene on the GUI thread; the pane builds
each surface's mapper, property and actor itself (a fifth of add_mesh's time).
The reference is pyvista's own ``add_mesh`` with the same look, off screen.
"""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest
import pyvista as pv

from core import presets
from core.scene import Sphere
from views.scene3d import vtk_convert
from views.scene3d.scene_view import SceneView

pytestmark = pytest.mark.gui


def _picture(build) -> np.ndarray:
    plotter = pv.Plotter(off_screen=True, window_size=(320, 240))
    try:
        plotter.disable_anti_aliasing()
        build(plotter)
        plotter.camera_position = [(6.0, 5.0, 8.0), (0.0, 0.5, 0.0), (0.0, 1.0, 0.0)]
        return plotter.screenshot(return_img=True)
    finally:
        plotter.close()


def _looks(scene):
    """(polydata, name, look) of every object (one half see-through) and a light marker."""
    parts = []
    for i, obj in enumerate([*scene.objects, Sphere(center=(1.5, 0.8, 1.0), radius=0.6)]):
        m = obj.material
        parts.append((vtk_convert.object_polydata(obj), f"object:{i}",
                      {"color": m.color, "opacity": 0.5 if i == 1 else m.opacity, "specular": m.specular}))
    parts.append((pv.Sphere(radius=0.2, center=(-1.0, 2.0, 0.5)), "light:0",
                  {"color": "#fff6a0", "lighting": False}))
    return parts


def test_objects_and_light_markers_are_drawn_as_add_mesh_draws_them():
    parts = _looks(presets.lecture_scene())

    def with_add_mesh(plotter):
        for poly, name, look in parts:
            plotter.add_mesh(poly, smooth_shading=False, show_edges=False, name=name, render=False, **look)

    def as_the_pane_does(plotter):
        pane = SimpleNamespace(plotter=plotter)
        for poly, name, look in parts:
            SceneView._add_surface(pane, poly, name, **look)

    expected, drawn = _picture(with_add_mesh), _picture(as_the_pane_does)
    assert len(np.unique(expected.reshape(-1, 3), axis=0)) > 20  # the scene, not an empty picture
    assert np.array_equal(drawn, expected)


def _overlay_parts(scene):
    """(polydata, name, style) of overlays of every kind of style the pane is given: translucent wire
    spheres and grid cells, thick outlines, the frustum's translucent planes, projector dots drawn as
    spheres, a lesson's wire-frame object and a normal's arrow."""
    from app.lessons.runner import NORMAL_COLOR, OBJECT_STYLE
    from core.image_order.flat_scene import trace_scene
    from views.scene3d import scene_overlays
    from views.scene3d.projector_lines import projector_parts

    camera = scene.camera
    cube = scene.objects[1]
    parts = [*scene_overlays.sphere_parts(scene),
             *scene_overlays.grid_cell_parts(trace_scene(scene).geometry.accel("grid")[0]),
             *scene_overlays.polygon_parts(cube.vertices[cube.triangles[0]]),
             *[p for p in scene_overlays.frustum_parts(camera) if "label_size" not in p[1]],
             *[p for p in projector_parts(camera, cube.vertices[0]) if "label_size" not in p[1]],
             (vtk_convert.object_polydata(scene.objects[2]), OBJECT_STYLE),
             (pv.Arrow(start=(0.0, 1.0, 0.0), direction=(0.0, 1.0, 0.0), scale=1.5), {"color": NORMAL_COLOR})]
    return [(poly, f"overlay:{i}", style) for i, (poly, style) in enumerate(parts)]


def test_overlays_are_drawn_as_add_mesh_draws_them():
    """Lesson steps put overlays in the pane on the GUI thread; built without add_mesh they look the same."""
    parts = _overlay_parts(presets.lecture_scene())
    styles = {key for _, _, style in parts for key in style}
    assert {"opacity", "line_width", "point_size", "render_points_as_spheres", "style"} <= styles

    def with_add_mesh(plotter):
        for poly, name, style in parts:
            plotter.add_mesh(poly, name=name, render=False, **style)

    def as_the_pane_does(plotter):
        pane = SimpleNamespace(plotter=plotter)
        for poly, name, style in parts:
            SceneView._add_surface(pane, poly, name, **style)

    expected, drawn = _picture(with_add_mesh), _picture(as_the_pane_does)
    assert len(np.unique(expected.reshape(-1, 3), axis=0)) > 20
    assert np.array_equal(drawn, expected)
