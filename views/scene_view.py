"""The 3D scene pane: the objects, the observer and its viewing pyramid.

It shows the scene from the outside, from a free overview camera the user
can rotate with the mouse, so the observer's own camera appears as an object:
a small camera glyph at the eye, the frustum (translucent, with its edges),
and the screen rectangle on the near plane.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv
from PySide6.QtWidgets import QVBoxLayout, QWidget
from pyvistaqt import QtInteractor

from core.camera import Camera
from core.scene import Scene
from views import vtk_convert

FRUSTUM_COLOR = "#ffd34d"
SCREEN_COLOR = "#6fd0ff"


class SceneView(QWidget):
    """A pyvistaqt view of a :class:`core.scene.Scene` with its observer."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.plotter = QtInteractor(self, auto_update=False)
        self.plotter.set_background("#1d2230", top="#3a4358")
        self.plotter.enable_anti_aliasing("fxaa")
        self.plotter.add_axes(line_width=3, labels_off=False)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.plotter)
        self._object_actors: list = []
        self._observer_actors: list = []
        self._overlays: dict[str, list] = {}
        self._scene: Scene | None = None
        self._framed_at = None  # the overview camera _frame chose, until the user moves it
        self.frustum: pv.PolyData | None = None
        self.screen: pv.PolyData | None = None

    def set_scene(self, scene: Scene) -> None:
        """Draw every object and light, then the observer; frame the whole."""
        for actor in self._object_actors:
            self.plotter.remove_actor(actor, render=False)
        self._object_actors = []
        for obj in scene.objects:
            m = obj.material
            actor = self.plotter.add_mesh(
                vtk_convert.object_polydata(obj),
                color=m.color,
                opacity=m.opacity,
                smooth_shading=False,
                show_edges=False,
                specular=m.specular,
                name=f"object:{id(obj)}",
                render=False,
            )
            self._object_actors.append(actor)
        for i, light in enumerate(scene.lights):
            actor = self.plotter.add_mesh(
                pv.Sphere(radius=0.18, center=light.position),
                color="#fff6a0",
                lighting=False,
                name=f"light:{i}",
                render=False,
            )
            self._object_actors.append(actor)
        self.set_camera(scene.camera, render=False)
        self._scene = scene
        self._frame(scene)
        self.plotter.render()

    def resizeEvent(self, event):
        """Frame the scene again for the new shape, unless the user has moved the view."""
        super().resizeEvent(event)
        if self._scene is not None and self.plotter.camera_position == self._framed_at:
            self._frame(self._scene)
            self.plotter.render()

    def set_camera(self, camera: Camera, render: bool = True) -> None:
        """Redraw the observer, its frustum and its screen for ``camera``."""
        for actor in self._observer_actors:
            self.plotter.remove_actor(actor, render=False)
        self.frustum = vtk_convert.frustum_polydata(camera)
        self.screen = vtk_convert.screen_polydata(camera)
        glyph_size = 0.07 * max(camera.distance, 1.0)
        add = self.plotter.add_mesh
        self._observer_actors = [
            add(self.frustum, color=FRUSTUM_COLOR, opacity=0.07, name="frustum", render=False),
            add(self.frustum.extract_all_edges(), color=FRUSTUM_COLOR, line_width=2,
                name="frustum-edges", render=False),
            add(self.screen, color=SCREEN_COLOR, opacity=0.35, name="screen", render=False),
            add(self.screen.extract_all_edges(), color=SCREEN_COLOR, line_width=3,
                name="screen-edges", render=False),
            add(vtk_convert.sight_line_polydata(camera), color="white", line_width=1,
                name="sight-line", render=False),
            add(vtk_convert.observer_glyph(camera, glyph_size), color="#e8e8e8",
                name="observer", render=False),
        ]
        if render:
            self.plotter.render()

    def set_overlay(self, name: str, parts: list[tuple[pv.PolyData, dict]]) -> None:
        """Show extra geometry under ``name`` (replacing what was there), e.g. a ray tree.

        ``parts`` are ``(polydata, add_mesh keyword arguments)`` pairs; an empty
        list removes the overlay.
        """
        for actor in self._overlays.pop(name, []):
            self.plotter.remove_actor(actor, render=False)
        actors = []
        for i, (poly, style) in enumerate(parts):
            if poly.n_points:
                actors.append(self.plotter.add_mesh(poly, name=f"{name}:{i}", render=False, **style))
        self._overlays[name] = actors
        self.plotter.render()

    def overlay_names(self) -> list[str]:
        """Names of the overlays currently drawn (with at least one part)."""
        return [name for name, actors in self._overlays.items() if actors]

    def _frame(self, scene: Scene) -> None:
        """Place the overview camera beside the observer, seeing it and the objects.

        The far part of the frustum may leave the view; the objects, the eye
        and the screen rectangle stay inside whatever the pane's shape.
        """
        cam = scene.camera
        points = [cam.eye, cam.target, *cam.screen_corners()]
        for obj in scene.objects:
            center, radius = vtk_convert.bounding_sphere(obj)
            points += [center - radius, center + radius]
        points = np.array(points)
        center = (points.min(axis=0) + points.max(axis=0)) / 2
        radius = np.linalg.norm(points - center, axis=1).max()
        side = np.cross(cam.forward, (0.0, 1.0, 0.0))
        side = side / (np.linalg.norm(side) or 1.0)
        direction = side + np.array([0.0, 0.7, 0.0]) - cam.forward * 0.6
        direction /= np.linalg.norm(direction)
        view_angle = np.radians(30.0)
        aspect = max(self.plotter.width(), 1) / max(self.plotter.height(), 1)
        half = min(view_angle / 2, np.arctan(np.tan(view_angle / 2) * aspect))
        distance = radius / np.sin(half) * 0.8  # the bounding sphere is loose: its box corners may leave
        self.plotter.camera_position = [
            tuple(center + direction * distance), tuple(center), (0.0, 1.0, 0.0)
        ]
        self.plotter.camera.view_angle = np.degrees(view_angle)
        self.plotter.reset_camera_clipping_range()
        self._framed_at = self.plotter.camera_position

    def close(self) -> bool:
        self.plotter.close()
        return super().close()
