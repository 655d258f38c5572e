"""Selecting and moving objects in the 3D pane: click one to select it, drag its handle to move it.

- A left click that does not drag (the mouse moves at most :data:`CLICK_SLOP_PX`
  between press and release) casts one ray from the overview camera through
  the clicked point; the first object it meets becomes the model's selection
  (:func:`core.image_order.picking.first_object_hit`), or a light whose small
  sphere it meets nearer, and a click on empty space selects nothing.  A drag
  still turns the overview, and the observer's eye and target keep their own drags
  (:class:`views.scene3d.scene_view.SceneView`).
- The selected object or light is outlined by its bounding box, and a handle
  (a small sphere) floats just above it.  It is dragged like the eye and the
  target: in the plane through it that faces the overview camera.  The item,
  its handle and its outline follow the mouse; on release ``move_requested(item, position)``
  asks once for the new position, so a whole drag is one edit.
"""

from __future__ import annotations

import numpy as np
import pyvista as pv
from PySide6.QtCore import QEvent, QObject, QPointF, Qt, Signal

from core import checked_edits
from core.image_order.intersect_sphere import intersect_sphere
from core.image_order.picking import first_object_hit
from core.scene import Mesh
from views.scene3d import vtk_convert
from views.scene3d.scene_view import GRAB_RADIUS_PX, LIGHT_MARKER, glyph_size

SELECTION_COLOR = "#00e5c0"
CLICK_SLOP_PX = 4
POSITION_DECIMALS = 3
"""A dragged position is rounded to this many decimals (scene units), so the file stays readable."""


def _translation(offset, scale: float = 1.0) -> np.ndarray:
    m = np.diag([scale, scale, scale, 1.0])
    m[:3, 3] = offset
    return m


class ScenePicker(QObject):
    """Click selection, the selection's outline and its move handle in ``view`` (a SceneView).

    Signals
    -------
    picked(object item) : a click selected ``item`` (``("object", i)``) or nothing (``None``).
    move_requested(object item, object position) : the handle was dragged; move ``item`` so that
        its position (:func:`core.checked_edits.position_of`) is ``position``.
    """

    picked = Signal(object)
    move_requested = Signal(object, object)

    def __init__(self, model, view):
        super().__init__(view)
        self.model, self.view = model, view
        add = view.plotter.add_mesh
        self._outline = pv.PolyData(np.zeros((8, 3)))
        self._outline_actor = add(self._outline, color=SELECTION_COLOR, line_width=3, lighting=False,
                                  name="selection", render=False)
        self._handle = add(pv.Sphere(radius=1.0, theta_resolution=16, phi_resolution=12),
                           color=SELECTION_COLOR, name="selection-handle", render=False)
        self.handle_center: np.ndarray | None = None  # world space; None: no handle shown
        self._position = np.zeros(3)  # of the selected item, where the handle's drag starts
        self._radius = 0.0
        self._pressed_at: QPointF | None = None
        self._drag: tuple[np.ndarray, np.ndarray] | None = None  # (handle centre, grab offset) at press
        view.plotter.installEventFilter(self)
        model.selection_changed.connect(lambda _: self.follow())
        model.scene_changed.connect(lambda _: self.follow())
        self.follow()

    def follow(self) -> None:
        """Outline the selection and put the handle above it (or hide both)."""
        item, scene = self.model.selection, self.model.scene
        box = _bounds(scene, item)
        self._drag = None
        self.handle_center = None
        if box is not None:
            self._outline.copy_from(vtk_convert.boxes_polydata(box))
            self._radius = 0.35 * glyph_size(scene.camera)
            (x0, _, z0), (x1, y1, z1) = box
            self.handle_center = np.array([(x0 + x1) / 2, y1 + 2.0 * self._radius, (z0 + z1) / 2])
            self._position = checked_edits.position_of(scene, item)
            self._show_moved(np.zeros(3))
        self._outline_actor.SetVisibility(box is not None)
        self._handle.SetVisibility(box is not None)
        self.view.request_render()

    def _show_moved(self, offset) -> None:
        """Draw the item, its outline and the handle ``offset`` (world space) away from where it is."""
        self._outline_actor.user_matrix = _translation(offset)
        self._handle.user_matrix = _translation(self.handle_center + offset, self._radius)
        actor = self.view.actor_of(self.model.selection)
        if actor is not None:
            actor.user_matrix = _translation(offset)

    # ------------------------------------------------------------- mouse
    def _on_handle(self, pos: QPointF) -> bool:
        if self.handle_center is None:
            return False
        p = self.view.widget_pos(self.handle_center)
        return bool(np.hypot(p.x() - pos.x(), p.y() - pos.y()) <= GRAB_RADIUS_PX)

    def eventFilter(self, obj, event):
        kind = event.type()
        left = kind in (QEvent.Type.MouseButtonPress, QEvent.Type.MouseButtonRelease) and (
            event.button() == Qt.MouseButton.LeftButton)
        if kind == QEvent.Type.MouseButtonPress and left:
            self._pressed_at = event.position()
            if self._on_handle(event.position()):
                under = self.view.world_point_under(event.position(), self.handle_center)
                self._drag = (self.handle_center, self.handle_center - under)
                return True  # the overview does not turn
        elif kind == QEvent.Type.MouseMove and self._drag is not None:
            self._show_moved(self._dragged_to(event.position()) - self._drag[0])
            self.view.request_render()
            return True
        elif kind == QEvent.Type.MouseButtonRelease and left and self._pressed_at is not None:
            pressed, self._pressed_at = self._pressed_at, None
            if self._drag is not None:
                self._released(self._dragged_to(event.position()) - self._drag[0])
                return True
            moved = event.position() - pressed
            if max(abs(moved.x()), abs(moved.y())) <= CLICK_SLOP_PX:
                self.click(event.position())
        return False

    def _dragged_to(self, pos: QPointF) -> np.ndarray:
        start, offset = self._drag
        return self.view.world_point_under(pos, start) + offset

    def _released(self, offset) -> None:
        item, self._drag = self.model.selection, None
        position = np.round(self._position + offset, POSITION_DECIMALS)
        if np.allclose(position, self._position):
            self._show_moved(np.zeros(3))
            self.view.request_render()
        else:
            self.move_requested.emit(item, position.tolist())

    def click(self, pos: QPointF) -> None:
        """Select the object or light under the widget position ``pos`` (nothing if none); the
        eye and the target are not objects."""
        if self.view.grabbable_at(pos) is not None:
            return
        origin, direction = self.ray_under(pos)
        scene = self.model.scene
        hit = first_object_hit(scene.objects, origin, direction)
        item, nearest = (("object", hit[0]), hit[1]) if hit is not None else (None, np.inf)
        for index, light in enumerate(scene.lights):  # a light is drawn as a small sphere
            crossing = intersect_sphere(origin, direction, light.position, LIGHT_MARKER)
            if crossing.hit and crossing.t < nearest:
                item, nearest = ("light", index), crossing.t
        self.model.set_selection(item)
        self.picked.emit(item)

    def ray_under(self, pos: QPointF) -> tuple[np.ndarray, np.ndarray]:
        """The overview camera's ray through widget position ``pos`` (see :meth:`SceneView.ray_under`)."""
        return self.view.ray_under(pos)

def _bounds(scene, item):
    """(2, 3) lower and upper corners of the item's box in the 3D pane, or None."""
    if item is None or item[0] == "background":
        return None
    kind, index = item
    if kind == "light":
        p = np.asarray(scene.lights[index].position, float)
        return np.array([p - LIGHT_MARKER, p + LIGHT_MARKER])
    obj = scene.objects[index]
    if isinstance(obj, Mesh):
        return np.array([obj.vertices.min(axis=0), obj.vertices.max(axis=0)])
    return np.array([np.subtract(obj.center, obj.radius), np.add(obj.center, obj.radius)])

