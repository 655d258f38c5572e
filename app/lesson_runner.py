"""Applying a lesson step to the window: its scene, panes, settings, view and highlight.

A :class:`core.lessons.LessonStep` says what the room should see; the
:class:`LessonRunner` makes the window show it.  Everything it changes goes
through the window's one model (scene, settings, step, picks, overlays) or
through the panes' own setters, so afterwards the window behaves as if the
user had made the same choices by hand.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from core.lessons import LessonStep
from core.scene import Mesh, Scene
from views.projector_lines import ProjectorLines
from views.scene_overlays import polygon_parts

SCENE_PANE = "scene 3D"
"""The lesson name of the 3D pane (the others are tab titles)."""
LESSON_OVERLAY = "lesson"
"""The 3D overlay that marks a step's highlighted object or face; shown with every tab."""
MODEL_OVERLAYS = {"bounding spheres": "spheres", "grid cells": "grid", "frustum": "frustum"}
"""Lesson overlay names and the model's names for them."""
OBJECT_STYLE = {"color": "#ffd400", "style": "wireframe", "line_width": 3}


def _find(scene: Scene, name: str):
    for obj in scene.objects:
        if obj.name == name:
            return obj
    raise KeyError(f"the scene has no object named {name!r}")


class LessonRunner:
    """Shows lesson steps in ``window`` (a :class:`app.main_window.MainWindow`).

    Attributes
    ----------
    step : the step applied last, or None.
    highlighted : what that step marks, in words (``"object 'cube'"``), or "".
    """

    def __init__(self, window):
        self.window = window
        self.step: LessonStep | None = None
        self.highlighted = ""
        self.projector = ProjectorLines(window.model, window.scene_view)  # A, A′ of a highlighted vertex

    def apply(self, step: LessonStep) -> None:
        """Load ``step``'s scene and settings, show its panes, set its view, picks and highlight."""
        w, model = self.window, self.window.model
        self.step = step
        w.scene_path = None
        w.setWindowTitle(f"Render Explorer — lesson: {step.title}")
        model.set_trace_settings(step.image_order)
        model.set_raster_settings(replace(step.object_order, record_steps=True))
        model.set_scene(step.scene)
        for lesson_name, name in MODEL_OVERLAYS.items():
            model.set_overlay(name, lesson_name in step.overlays)
        self._show_panes(step.panes)
        highlight = step.highlight
        zbuffer_step = step.zbuffer_step
        if zbuffer_step is None and "polygon_step" in highlight:
            zbuffer_step = highlight["polygon_step"] + 1  # the step at which that polygon is drawn
        model.set_step(zbuffer_step)
        pixel = step.pixel if step.pixel is not None else highlight.get("pixel")
        if pixel is not None:
            model.set_ray_pixel(tuple(pixel))
            model.set_buffer_pixel(tuple(pixel))
        self._highlight(step.scene, highlight)
        w.scene_view.look_from({**step.view, "frame": step.frame})  # after the highlight it may frame

    def _show_panes(self, panes) -> None:
        w = self.window
        w.scene_pane.setVisible(SCENE_PANE in panes)
        titles = [p for p in panes if p != SCENE_PANE]
        if titles:
            w.show_tab(titles[0])
            for tab in w.tabs:
                index = w.tab_widget.indexOf(tab.widget)
                w.tab_widget.setTabVisible(index, tab.title.lower() in titles)

    def _highlight(self, scene: Scene, highlight) -> None:
        w = self.window
        parts, words, vertex_point = [], [], None
        image_order = w.tab("image order").widget
        image_order.ray_kind = highlight.get("ray")
        image_order.tree.select_kind(image_order.ray_kind)
        if "ray" in highlight:
            image_order.show_ray_tree()  # where that ray is selected
            words.append(f"the {highlight['ray']} ray")
        if "object" in highlight:
            from views.vtk_convert import object_polydata  # pyvista loads with the 3D pane, not before

            obj = _find(scene, highlight["object"])
            parts.append((object_polydata(obj), OBJECT_STYLE))
            words.append(f"object {obj.name!r}")
        if "face" in highlight:
            face = highlight["face"]
            mesh = _find(scene, face["object"])
            corners = mesh.vertices[mesh.triangles[face["triangle"]]]
            parts += polygon_parts(corners)
            words.append(f"triangle {face['triangle']} of {mesh.name!r}")
        if "vertex" in highlight:
            vertex = highlight["vertex"]
            mesh = _find(scene, vertex["object"])
            point = vertex_point = np.asarray(mesh.vertices[vertex["index"]] if isinstance(mesh, Mesh)
                                              else mesh.center)
            panel = w.tab("object order").widget
            name = f"vertex {vertex['index']} of {mesh.name!r}"
            panel.show_vertex(point, scene, name)
            panel.details.setCurrentWidget(panel.vertex_math)
            words.append(name)
        if "polygon_step" in highlight:
            words.append(f"the polygon drawn at step {highlight['polygon_step'] + 1}")
        if "pixel" in highlight:
            words.append(f"pixel {tuple(highlight['pixel'])}")
        w.scene_view.set_overlay(LESSON_OVERLAY, parts)
        self.projector.show_point(vertex_point)
        self.highlighted = ", ".join(words)
        if self.highlighted:
            w.statusBar().showMessage(f"Look at {self.highlighted}", 15000)
        else:
            w.statusBar().clearMessage()  # the previous step's pointer no longer applies
