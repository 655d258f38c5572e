"""What the tabs add to the 3D pane: acceleration structures, a ray tree, polygons.

- Image order: the objects' *bounding spheres* and the occupied cells of the
  *grid of cuboids* (as the model's overlay switches say), the picked pixel's
  ray tree, and the cells its primary ray walks through.
- Object order: the polygon drawn at the current step, and the polygons the
  frustum's planes cut (clipping).
- With every tab (:data:`SCENE_OVERLAYS`), when the model's ``"frustum"``
  switch is on: the frustum emphasised, its near plane (the screen) and far
  plane filled and labelled with their distances.

:class:`SceneOverlays` builds these shapes and hands them to the
:class:`views.scene3d.scene_view.SceneView` under fixed names, so the window only
connects signals to it.  pyvista (and VTK) load when a first shape is
built, not with the window (see :mod:`views.scene3d.deferred_scene_view`).
"""

from __future__ import annotations

import functools
import importlib.util
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from core.image_order.bounding_spheres import bounding_spheres
from core.image_order.flat_scene import trace_scene
from core.image_order.grid_of_cuboids import cells_on_ray
from core.image_order.ray_tree import RayNode
from core.object_order import three_views
from views.panels import raytree_view
from views.panels.raytree_view import KIND_COLORS
from views.scene3d.scene_colors import FRUSTUM_COLOR, SCREEN_COLOR

if TYPE_CHECKING:
    import pyvista as pv

IMAGE_ORDER_OVERLAYS = ("ray-tree", "spheres", "grid", "walk")
OBJECT_ORDER_OVERLAYS = ("polygon", "clipped")
SCENE_OVERLAYS = ("frustum",)
"""Overlays of the scene itself, shown whatever the tab."""
LABEL_PT = 13
"""Size of the 3D pane's labels at text scale 1, points."""


@functools.cache
def label_font_file() -> str | None:
    """The 3D pane's label font: DejaVu Sans Bold, the file matplotlib ships (None if it is missing).

    VTK's own Arial has no glyph for many characters the lessons name, the prime of A′ among
    them; DejaVu Sans has them and is the font the window's own text uses on Debian.  The path
    is found without importing matplotlib, which the window loads only for its plots, and
    once: each label actor asks for it, and a drag of the observer makes new ones.
    """
    spec = importlib.util.find_spec("matplotlib")
    if spec is None or not spec.submodule_search_locations:
        return None
    path = Path(spec.submodule_search_locations[0], "mpl-data", "fonts", "ttf", "DejaVuSans-Bold.ttf")
    return str(path) if path.is_file() else None


def sphere_parts(scene) -> list[tuple[pv.PolyData, dict]]:
    """Wire-frame bounding spheres of the objects that are not spheres themselves."""
    from views.scene3d.vtk_convert import placed_sphere

    return [(placed_sphere(b.center, b.radius, 24, 16, edges=True),
             {"color": "#9fd3ff", "opacity": 0.35, "line_width": 1})
            for b in bounding_spheres(scene) if not b.exact]


def grid_cell_parts(grid) -> list[tuple[pv.PolyData, dict]]:
    """Outlines of the grid cells that hold at least one object."""
    from views.scene3d import vtk_convert

    return [(vtk_convert.boxes_polydata(grid.cell_boxes(grid.occupied_cells())),
             {"color": "#b0b0b0", "opacity": 0.25, "line_width": 1})]


def walked_cell_parts(grid, root: RayNode) -> list[tuple[pv.PolyData, dict]]:
    """The cells the primary ray ``root`` passes through, up to its hit."""
    from views.scene3d import vtk_convert

    t_max = root.t if root.t is not None else np.inf
    walked = cells_on_ray(grid, root.origin, root.direction, root.t_min, t_max)
    if not len(walked):
        return []
    return [(vtk_convert.boxes_polydata(grid.cell_boxes(walked)),
             {"color": KIND_COLORS["primary"], "line_width": 3})]


def polygon_parts(vertices) -> list[tuple[pv.PolyData, dict]]:
    """One world-space polygon outlined, its colours left true (``None``: nothing)."""
    if vertices is None:
        return []
    from views.scene3d import vtk_convert

    return [(vtk_convert.outlines_polydata([vertices]), {"color": "#ff2bd6", "line_width": 4})]


def clipped_parts(polygons) -> list[tuple[pv.PolyData, dict]]:
    """Outlines of the polygons the frustum's planes cut."""
    if not len(polygons):
        return []
    from views.scene3d import vtk_convert

    return [(vtk_convert.outlines_polydata(polygons), {"color": "#7cff6b", "line_width": 3})]


def frustum_parts(camera) -> list[tuple[pv.PolyData, dict]]:
    """The viewing frustum emphasised: near and far planes filled, thick edges, labels."""
    import pyvista as pv

    from views.scene3d import vtk_convert

    corners = camera.frustum_corners()
    near, far = corners[:4], corners[4:]
    edges = vtk_convert.frustum_edges_polydata(corners)
    labels = vtk_convert.set_labels(
        pv.PolyData(np.array([(near[2] + near[3]) / 2, (far[2] + far[3]) / 2], float)),  # top edges
        [f"near plane (the screen), n = {camera.near:g}", f"far plane, f = {camera.far:g}"])
    return [(pv.PolyData(far.copy(), np.array([4, 0, 1, 2, 3])), {"color": FRUSTUM_COLOR, "opacity": 0.3}),
            (pv.PolyData(near.copy(), np.array([4, 0, 1, 2, 3])), {"color": SCREEN_COLOR, "opacity": 0.6}),
            (edges, {"color": FRUSTUM_COLOR, "line_width": 4}),
            (labels, {"label_size": LABEL_PT, "color": "white"})]


class SceneOverlays:
    """Keeps the 3D pane's overlays in step with the model and the tabs' results.

    Parameters
    ----------
    model : the window's state (``scene``, ``overlays`` and their signals).
    view : the :class:`views.scene3d.scene_view.SceneView` to draw in.
    """

    def __init__(self, model, view):
        self.model, self.view = model, view
        self.ray_tree: RayNode | None = None
        model.overlays_changed.connect(self._accel_changed)
        model.scene_changed.connect(self._accel_changed)
        model.camera_changed.connect(self._frustum)

    def _grid(self):
        return trace_scene(self.model.scene).geometry.accel("grid")[0]

    def _accel_changed(self, *_) -> None:
        """Bounding spheres and grid cells, as the model's switches say."""
        shown = self.model.overlays
        scene = self.model.scene
        self.view.set_overlay("spheres", sphere_parts(scene) if "spheres" in shown else [])
        self.view.set_overlay("grid", grid_cell_parts(self._grid()) if "grid" in shown else [])
        self._walk()
        self._frustum()

    def _frustum(self, *_) -> None:
        shown = "frustum" in self.model.overlays
        self.view.set_overlay("frustum", frustum_parts(self.model.camera) if shown else [])

    def _walk(self) -> None:
        want = "walk" in self.model.overlays and self.ray_tree is not None
        self.view.set_overlay("walk", walked_cell_parts(self._grid(), self.ray_tree) if want else [])

    def show_ray_tree(self, root: RayNode | None) -> None:
        """Draw the picked pixel's ray tree (``None`` removes it) and the cells its ray walks."""
        self.ray_tree = root
        parts = []
        if root is not None:
            low, high = three_views.scene_bounds(self.model.scene)
            miss_length = 0.6 * float(np.linalg.norm(high - low)) + 1.0
            parts = raytree_view.ray_tree_parts(root, miss_length)
        self.view.set_overlay("ray-tree", parts)
        self._walk()

    def show_polygon(self, vertices) -> None:
        """Highlight the polygon the object-order scrubber is at (``None``: none)."""
        self.view.set_overlay("polygon", polygon_parts(vertices))

    def show_clipped(self, polygons) -> None:
        """Outline the polygons the frustum's planes cut."""
        self.view.set_overlay("clipped", clipped_parts(polygons))
