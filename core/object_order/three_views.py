"""The three orthographic views of a scene: front, side and top.

Engineering drawings show an object by three parallel projections along the
coordinate axes; next to the perspective view they make the lecture's
four-view figure.  Each view here is an orthographic :class:`Camera` framing
every object of the scene.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.scene import Scene, Sphere

# name -> (direction from the scene's centre to the eye, up vector)
VIEWS = {
    "front": ((0.0, 0.0, 1.0), (0.0, 1.0, 0.0)),
    "side": ((1.0, 0.0, 0.0), (0.0, 1.0, 0.0)),
    "top": ((0.0, 1.0, 0.0), (0.0, 0.0, -1.0)),
}


def scene_bounds(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper corner of a box around every object, (3,) each (world space)."""
    lows, highs = [], []
    for obj in scene.objects:
        if isinstance(obj, Sphere):
            c = np.asarray(obj.center, dtype=float)
            lows.append(c - obj.radius)
            highs.append(c + obj.radius)
        else:
            lows.append(obj.vertices.min(axis=0))
            highs.append(obj.vertices.max(axis=0))
    if not lows:
        return -np.ones(3), np.ones(3)
    return np.min(lows, axis=0), np.max(highs, axis=0)


def orthographic_views(scene: Scene, width: int = 320, height: int = 240) -> dict[str, Camera]:
    """Front, side and top orthographic cameras that frame the whole scene.

    Examples
    --------
    >>> from core.presets import lecture_scene
    >>> views = orthographic_views(lecture_scene())
    >>> views["top"].projection, (views["top"].forward.round(6) + 0.0).tolist()   # + 0.0: no -0.0
    ('orthographic', [0.0, -1.0, 0.0])
    """
    low, high = scene_bounds(scene)
    center = (low + high) / 2
    size = np.maximum(high - low, 1e-3)
    radius = float(np.linalg.norm(size) / 2)
    aspect = width / height
    cameras = {}
    for name, (direction, up) in VIEWS.items():
        direction = np.asarray(direction)
        right = np.cross(-direction, up)
        horizontal, vertical = np.abs(right) @ size, np.abs(up) @ size  # extents across the view
        ortho_height = 1.1 * max(vertical, horizontal / aspect)
        cameras[name] = Camera(
            eye=tuple(float(v) for v in center + direction * (radius + 1.0)),
            target=tuple(float(v) for v in center), up=up,
            near=0.5, far=2 * radius + 1.5, projection="orthographic",
            ortho_height=float(ortho_height), width=width, height=height,
        )
    return cameras
