"""Applying a lesson step to the window: its scene, panes, settings, view and highlight.

A :class:`core.lessons.lesson_file.LessonStep` says what the room should see; the
:class:`LessonRunner` makes the window show it.  Everything it changes goes
through the window's one model (scene, settings, step, picks, overlays) or
through the panes' own setters, so afterwards the window behaves as if the
user had made the same choices by hand.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from core.lessons.lesson_file import LessonStep
from core.lessons.naming import named_objects, step_words
from core.scene import Mesh, Scene
from views.scene3d.projector_lines import ProjectorLines
from views.scene3d.scene_overlays import polygon_parts

SCENE_PANE = "scene 3D"
"""The lesson name of the 3D pane (the others are tab titles)."""
LESSON_OVERLAY = "lesson"
"""The 3D overlay that marks a step's highlighted object or face; shown with every tab."""
FACE_SIDE_OVERLAY = "lesson: face side"
"""The words on a highlighted face's normal, "N: front face" or "N: back face": the culling test's
result, kept apart from :data:`LESSON_OVERLAY` so that the window can withhold them while an exercise
asks for that result."""
MODEL_OVERLAYS = {"bounding spheres": "spheres", "grid cells": "grid", "cells the ray walks": "walk",
                  "frustum": "frustum"}
"""Lesson overlay names and the model's names for them."""
OBJECT_STYLE = {"color": "#ffd400", "style": "wireframe", "line_width": 3}
NORMAL_COLOR = "#ff2bd6"
"""The highlighted face's outward normal, drawn as an arrow (the colour of its outline)."""


def _bounds(obj) -> tuple[np.ndarray, np.ndarray]:
    """The lowest and highest corner of the box around a mesh's vertices (a sphere: its centre twice)."""
    points = np.asarray(obj.vertices if isinstance(obj, Mesh) else [obj.center], dtype=float)
    return points.min(axis=0), points.max(axis=0)


def _top(obj) -> np.ndarray:
    """A point just above the object, where its name is written."""
    low, high = _bounds(obj)
    lift = getattr(obj, "radius", 0.0) + 0.08 * float(np.linalg.norm(high - low) + 1.0)
    return np.array([(low[0] + high[0]) / 2, high[1] + lift, (low[2] + high[2]) / 2])


def _normal_parts(corners: np.ndarray, eye) -> tuple[list, list]:
    """The face's outward normal as an arrow from its centroid, and its label saying where it points
    (for :data:`FACE_SIDE_OVERLAY`)."""
    import pyvista as pv

    from views.scene3d.scene_overlays import LABEL_PT
    from views.scene3d.vtk_convert import set_labels

    centroid = corners.mean(axis=0)
    normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    normal /= np.linalg.norm(normal)
    size = 0.6 * float(np.max(np.linalg.norm(corners - centroid, axis=1)))
    toward = float(np.dot(normal, np.asarray(eye, dtype=float) - centroid)) > 0  # the culling test
    words = "N: front face" if toward else "N: back face"  # short: it must fit the pane at x2
    tip = pv.PolyData(np.array([centroid + 1.15 * size * normal]))
    return ([(pv.Arrow(start=centroid, direction=normal, scale=size), {"color": NORMAL_COLOR})],
            [(set_labels(tip, [words]), {"label_size": LABEL_PT, "color": NORMAL_COLOR})])


FLAT = 0.1
"""An object this many times as high as it is wide (a ground, a wall lying down) is *flat*."""
FLAT_INSET = 0.2
"""A flat object's name is written this share of its width in from its edges (see :func:`_label_point`)."""


def _label_point(obj, others) -> np.ndarray:
    """Where ``obj``'s name is written: just above it (:func:`_top`), or, for a flat object such as
    the ground, on it where it is farthest from the ``others`` (above its middle, the ground's name
    stood beside the cube and the cone that stand there)."""
    low, high = _bounds(obj)
    width = float(max(high[0] - low[0], high[2] - low[2]))
    if not isinstance(obj, Mesh) or high[1] - low[1] > FLAT * width or not others:
        return _top(obj)
    inset = FLAT_INSET * (high - low)
    xs, zs = (low[0] + inset[0], (low[0] + high[0]) / 2, high[0] - inset[0]), \
        (low[2] + inset[2], (low[2] + high[2]) / 2, high[2] - inset[2])
    centres = np.array([np.add(*_bounds(other))[[0, 2]] / 2 for other in others])
    spots = [np.array([x, z]) for x in xs for z in zs]
    best = max(spots, key=lambda spot: np.linalg.norm(centres - spot, axis=1).min())
    return np.array([best[0], high[1] + 0.08 * (high[1] - low[1] + 1.0), best[1]])


def _name_parts(objects, scene: Scene) -> list:
    """The objects' names written above them (on them, when flat)."""
    if not objects:
        return []
    import pyvista as pv

    from views.scene3d.scene_overlays import LABEL_PT
    from views.scene3d.vtk_convert import set_labels

    points = pv.PolyData(np.array([_label_point(obj, [o for o in scene.objects if o is not obj])
                                   for obj in objects]))
    return [(set_labels(points, [obj.name for obj in objects]), {"label_size": LABEL_PT, "color": "white"})]


def _find(scene: Scene, name: str):
    for obj in scene.objects:
        if obj.name == name:
            return obj
    raise KeyError(f"the scene has no object named {name!r}")


class LessonRunner:
    """Shows lesson steps in ``window`` (a :class:`app.window.main_window.MainWindow`).

    Attributes
    ----------
    step : the step applied last, or None.
    highlighted : what that step marks, in words (``"object 'cube'"``), or "".
    """

    def __init__(self, window):
        self.window = window
        self.step: LessonStep | None = None
        self.highlighted = ""
        self.asked = None  # the question and choices of the exercise asked about the step shown
        self.projector = ProjectorLines(window.model, window.scene_view)  # A, A′ of a highlighted vertex

    def leave(self) -> None:
        """The window no longer shows the step: its marks leave the 3D pane (a new scene may not have
        the object they named, and a mark left over would point at something the words no longer say)."""
        self.step = None
        self.highlighted = ""
        self.window.scene_view.set_overlay(LESSON_OVERLAY, [])
        self.window.scene_view.set_overlay(FACE_SIDE_OVERLAY, [])
        self.projector.show_point(None)
        if self.window.statusBar().currentMessage().startswith("Look at "):
            self.window.statusBar().clearMessage()

    def apply(self, step: LessonStep) -> None:
        """Load ``step``'s scene and settings, show its panes, set its view, picks and highlight.
        The 3D pane follows a turn later (:meth:`views.scene3d.scene_view.SceneView.held`)."""
        with self.window.scene_view.held():
            self._apply(step)

    def _apply(self, step: LessonStep) -> None:
        w, model = self.window, self.window.model
        self.step = step
        w.show_pictures_whole()  # (also where the scene is the last step's)
        w.scene_path = None
        w.setWindowTitle(f"Render Explorer — lesson: {step.title}")
        model.set_trace_settings(step.image_order)
        model.set_raster_settings(replace(step.object_order, record_steps=True))
        model.set_scene(step.scene)
        for lesson_name, name in MODEL_OVERLAYS.items():
            model.set_overlay(name, lesson_name in step.overlays)
        self._show_panes(step.panes)
        self._show_heat_map(step.heat_map)
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

    def ask(self, asked: tuple[str, tuple[str, ...]] | None) -> None:
        """An exercise asks about the step shown (``asked``: its question and the choices it offers),
        or nothing is asked (None): the 3D pane marks what those words name (:meth:`_mark`)."""
        if asked != self.asked:
            self.asked = asked
            if self.step is not None:
                self._mark()

    def _mark(self) -> None:
        """Mark in the 3D pane the step's highlighted object or face and write the names of the objects
        its words name.  While an exercise is :attr:`asked`, its words take the step's place: a mark
        stays only on an object its question names and does not offer as an answer (the step that
        outlined the box behind the observer answered "Which object is dropped before any pixel
        work?"; an outline on one of the objects offered would single it out), a face's mark and its
        normal go (a question names its own face, by its corners: the step's face would pass for it,
        and the normal's direction answers a back-face question), and the names written are those of
        the objects the question and its choices name, each alike."""
        step, scene = self.step, self.step.scene
        if self.asked is None:
            named = named_objects(scene, step_words(step))
            marked = scene.objects  # every mark the step makes
        else:
            question, choices = self.asked
            named = named_objects(scene, "\n".join((question, *choices)))
            offered = named_objects(scene, "\n".join(choices))
            marked = [o for o in named_objects(scene, question) if not any(o is c for c in offered)]
        parts, side = [], []
        if "object" in step.highlight:
            obj = _find(scene, step.highlight["object"])
            if any(o is obj for o in marked):
                from views.scene3d.vtk_convert import (
                    object_polydata,  # pyvista loads with the 3D pane, not before
                )

                parts.append((object_polydata(obj), OBJECT_STYLE))
        if "face" in step.highlight and self.asked is None:
            face = step.highlight["face"]
            mesh = _find(scene, face["object"])
            corners = mesh.vertices[mesh.triangles[face["triangle"]]]
            arrow, side = _normal_parts(np.asarray(corners, dtype=float), scene.camera.eye)
            parts += polygon_parts(corners) + arrow
        parts += _name_parts(named, scene)
        self.window.scene_view.set_overlay(LESSON_OVERLAY, parts)
        self.window.scene_view.set_overlay(FACE_SIDE_OVERLAY, side)

    def _show_panes(self, panes) -> None:
        w = self.window
        w.scene_pane.setVisible(SCENE_PANE in panes)
        titles = [p for p in panes if p != SCENE_PANE]
        if titles:
            w.show_tab(titles[0])
            for tab in w.tabs:
                index = w.tab_widget.indexOf(tab.widget)
                w.tab_widget.setTabVisible(index, tab.title.lower() in titles)

    def _show_heat_map(self, name: str) -> None:
        """Choose the image-order pane's heat map named ``name`` (its choice's text, in lower case)."""
        choice = self.window.tab("image order").widget.heat
        choice.setCurrentIndex(next(k for k in range(choice.count()) if choice.itemText(k).lower() == name))

    def _highlight(self, scene: Scene, highlight) -> None:
        w = self.window
        words, vertex_point = [], None
        image_order = w.tab("image order").widget
        image_order.ray_kind = highlight.get("ray")
        image_order.tree.select_kind(image_order.ray_kind)
        if "ray" in highlight:
            image_order.show_ray_tree()  # where that ray is selected
            words.append(f"the {highlight['ray']} ray")
        if "object" in highlight:
            words.append(f"object {highlight['object']!r}")
        if "face" in highlight:
            face = highlight["face"]
            words.append(f"triangle {face['triangle']} of {face['object']!r}")
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
        else:  # the vertex an earlier step followed is not one these words speak of
            w.tab("object order").widget.clear_vertex()
        if "polygon_step" in highlight:
            words.append(f"the polygon drawn at step {highlight['polygon_step'] + 1}")
        if "pixel" in highlight:
            words.append(f"pixel {tuple(highlight['pixel'])}")
        self._mark()
        self.projector.show_point(vertex_point)
        self.highlighted = ", ".join(words)
        if self.highlighted:
            w.statusBar().showMessage(f"Look at {self.highlighted}", 15000)
        else:
            w.statusBar().clearMessage()  # the previous step's pointer no longer applies
