"""The projector of a point: the line along which the observer projects it onto the screen.

The lecture projects a point A to A′, where the projecting ray through A
meets the screen: the ray from A to the eye (perspective), or the ray
through A parallel to the viewing direction (orthographic).  Here the screen
is the near plane, and A′ is found with the camera's own projection: A goes
to normalised device coordinates through :meth:`core.camera.Camera.project`,
and the point of the near plane (NDC depth -1) with the same x and y comes
back through the inverse of the same matrix.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera


def screen_image(camera: Camera, point) -> np.ndarray | None:
    """A′, where the projector of world point ``point`` meets the screen (near plane), world
    space; ``None`` for a point the projection cannot show (not in front of the eye)."""
    ndc = camera.project(point).ndc
    if ndc is None:
        return None
    back = np.linalg.inv(camera.clip_from_world) @ np.array([ndc[0], ndc[1], -1.0, 1.0])
    return back[:3] / back[3]

