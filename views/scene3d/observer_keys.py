"""Moving the observer from the keyboard: orbit around the target, step closer, walk.

Two ways of moving, as in the lecture's figure of observers A and B:

- *orbit*: the eye moves on a sphere around the target and keeps looking at
  it (arrow keys, :data:`ORBIT_STEP_DEG` per press; the pitch stays within
  ±:data:`core.camera.PITCH_LIMIT_DEG`); ``+`` / ``-`` change the distance
  by :data:`ZOOM_FACTOR`;
- *walk*: the eye and the target move together, so the observer keeps its
  viewing direction (W/S forward and back along it, A/D left and right,
  Q/E down and up along the world's vertical), by :data:`WALK_FRACTION` of
  the eye-to-target distance per press.

:data:`OBSERVER_KEYS` lists every key with its description and its move; the
window builds its menu and its Help → Keys list from it.  These keys belong
to the window and the 3D pane, never to a focused number box, which takes
the arrow keys for itself.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QEvent, QObject, Qt
from PySide6.QtGui import QKeySequence
from PySide6.QtWidgets import (
    QAbstractSlider,
    QAbstractSpinBox,
    QComboBox,
    QLineEdit,
    QPlainTextEdit,
    QTextEdit,
)

from core.camera import PITCH_LIMIT_DEG, Camera

ORBIT_STEP_DEG = 5.0
ZOOM_FACTOR = 1.15
WALK_FRACTION = 0.1
"""A walking step, as a share of the eye-to-target distance (which walking keeps)."""


def orbit(camera: Camera, d_yaw_deg: float, d_pitch_deg: float) -> Camera:
    """``camera`` moved around its target by the given yaw and pitch (degrees)."""
    pitch = max(-PITCH_LIMIT_DEG, min(PITCH_LIMIT_DEG, camera.pitch_deg + d_pitch_deg))
    return camera.orbit(camera.yaw_deg + d_yaw_deg, pitch)


def zoom(camera: Camera, factor: float) -> Camera:
    """``camera`` with its eye ``factor`` times as far from the target."""
    return camera.orbit(camera.yaw_deg, camera.pitch_deg, camera.distance * factor)


def walk_offset(camera: Camera, forward: float, right: float, up: float) -> np.ndarray:
    """World-space displacement of a walk of the given steps (each ±1 or 0)."""
    ahead = camera.forward
    side = np.cross(ahead, (0.0, 1.0, 0.0))
    side = side / (np.linalg.norm(side) or 1.0)
    step = WALK_FRACTION * camera.distance
    return step * (forward * ahead + right * side + up * np.array([0.0, 1.0, 0.0]))


def walk(camera: Camera, forward: float = 0.0, right: float = 0.0, up: float = 0.0) -> Camera:
    """``camera`` walked: eye and target moved together by :func:`walk_offset`."""
    offset = walk_offset(camera, forward, right, up)
    return camera.replace(eye=np.add(camera.eye, offset), target=np.add(camera.target, offset))


def toggle_projection(camera: Camera) -> Camera:
    other = "orthographic" if camera.projection == "perspective" else "perspective"
    return camera.replace(projection=other)


OBSERVER_KEYS = [
    ("Left", "Orbit left around the target", lambda c: orbit(c, -ORBIT_STEP_DEG, 0)),
    ("Right", "Orbit right around the target", lambda c: orbit(c, ORBIT_STEP_DEG, 0)),
    ("Up", "Look from higher", lambda c: orbit(c, 0, ORBIT_STEP_DEG)),
    ("Down", "Look from lower", lambda c: orbit(c, 0, -ORBIT_STEP_DEG)),
    ("+", "Step closer to the target", lambda c: zoom(c, 1 / ZOOM_FACTOR)),
    ("-", "Step back from the target", lambda c: zoom(c, ZOOM_FACTOR)),
    ("W", "Walk forward", lambda c: walk(c, forward=1)),
    ("S", "Walk back", lambda c: walk(c, forward=-1)),
    ("A", "Walk left", lambda c: walk(c, right=-1)),
    ("D", "Walk right", lambda c: walk(c, right=1)),
    ("Q", "Walk down", lambda c: walk(c, up=-1)),
    ("E", "Walk up", lambda c: walk(c, up=1)),
    ("P", "Toggle perspective / orthographic", toggle_projection),
]
"""(key, description, move) for every key that moves the observer."""

MOUSE_GESTURES = [
    ("Drag the camera glyph", "move the eye; the observer keeps looking at its target"),
    ("Drag the orange target", "move the point the observer looks at"),
    ("Scroll over the glyph", "narrow or widen the viewing angle α"),
    ("Drag elsewhere in the 3D pane", "turn the overview (not the observer)"),
    ("Click an object in the 3D pane", "select it in the scene editor"),
    ("Drag the handle above the selection", "move it (one undo step)"),
]

EDITORS = (QAbstractSpinBox, QLineEdit, QAbstractSlider, QComboBox, QTextEdit, QPlainTextEdit)
"""Widgets that keep their keys: a focused one edits itself instead of moving the observer."""


class EditorsKeepTheirKeys(QObject):
    """A key filter for the focused widget (:func:`views.keyboard_focus.follow_focus`): a focused
    editor takes the observer keys before the shortcuts do.

    Qt asks the focused widget first (a ShortcutOverride event) whether it
    wants a key that is also a shortcut; accepting it there keeps, say, the
    arrow keys in a number box instead of orbiting the observer.
    """

    def __init__(self, parent: QObject | None = None):
        super().__init__(parent)
        self.keys = {QKeySequence(key)[0].key() for key, _, _ in OBSERVER_KEYS}

    def eventFilter(self, obj, event):
        if (event.type() == QEvent.Type.ShortcutOverride and isinstance(obj, EDITORS)
                and event.key() in self.keys
                and not event.modifiers() & (Qt.KeyboardModifier.ControlModifier
                                             | Qt.KeyboardModifier.AltModifier)):
            event.accept()
            return True
        return False
