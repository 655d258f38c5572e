"""The three orthographic views of a scene: front, side and top.

Engineering drawings show an object by three parallel projections along the
coordinate axes; next to the perspective view they make the lecture's
four-view figure.  Each view here is an orthographic :class:`Camera` framing
the scene's objects.  A *backdrop* (a flat object far wider than the rest,
such as a ground plane) is left out of the framing, or the objects would be
specks on it; it stays in the views, reaching beyond their edges.  The
z-buffer draws nothing of a face seen edge-on, so the views are drawn with
their outlines (:mod:`core.object_order.outlines`).
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


MARGIN = 1.15
"""The framed objects take up 1 / MARGIN of a view's height or width."""
FLAT = 1e-3
"""An object thinner than this share of its width is flat."""
BACKDROP_WIDTH = 2.0
"""A flat object this many times wider than all the other objects together is a backdrop."""


def _bounds(obj) -> tuple[np.ndarray, np.ndarray]:
    if isinstance(obj, Sphere):
        c = np.asarray(obj.center, dtype=float)
        return c - obj.radius, c + obj.radius
    return obj.vertices.min(axis=0), obj.vertices.max(axis=0)


def _union(boxes) -> tuple[np.ndarray, np.ndarray]:
    if not boxes:
        return -np.ones(3), np.ones(3)
    return np.min([lo for lo, _ in boxes], axis=0), np.max([hi for _, hi in boxes], axis=0)


def scene_bounds(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """Lower and upper corner of a box around every object, (3,) each (world space)."""
    return _union([_bounds(obj) for obj in scene.objects])


def framing_bounds(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """The box the views frame: around every object but the backdrops (all, if only backdrops)."""
    boxes = [_bounds(obj) for obj in scene.objects]
    kept = []
    for i, (lo, hi) in enumerate(boxes):
        size = hi - lo
        others_lo, others_hi = _union(boxes[:i] + boxes[i + 1:])
        backdrop = (len(boxes) > 1 and size.min() <= FLAT * size.max()
                    and size.max() >= BACKDROP_WIDTH * (others_hi - others_lo).max())
        if not backdrop:
            kept.append((lo, hi))
    return _union(kept or boxes)


def orthographic_views(scene: Scene, width: int = 320, height: int = 240) -> dict[str, Camera]:
    """Front, side and top orthographic cameras that frame the scene's objects (without backdrops).

    Examples
    --------
    >>> from core.presets import lecture_scene
    >>> views = orthographic_views(lecture_scene())
    >>> views["top"].projection, (views["top"].forward.round(6) + 0.0).tolist()   # + 0.0: no -0.0
    ('orthographic', [0.0, -1.0, 0.0])
    """
    low, high = framing_bounds(scene)
    center = (low + high) / 2
    size = np.maximum(high - low, 1e-3)
    all_low, all_high = scene_bounds(scene)
    # Eye and far plane clear of every object, backdrops too, so that none is cut away.
    reach = float(np.linalg.norm(np.maximum(np.abs(all_high - center), np.abs(all_low - center)))) + 1.0
    aspect = width / height
    cameras = {}
    for name, (direction, up) in VIEWS.items():
        direction = np.asarray(direction)
        right = np.cross(-direction, up)
        horizontal, vertical = np.abs(right) @ size, np.abs(up) @ size  # extents across the view
        ortho_height = MARGIN * max(vertical, horizontal / aspect)
        cameras[name] = Camera(
            eye=tuple(float(v) for v in center + direction * reach),
            target=tuple(float(v) for v in center), up=up,
            near=0.5, far=2 * reach, projection="orthographic",
            ortho_height=float(ortho_height), width=width, height=height,
        )
    return cameras
