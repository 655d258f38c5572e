"""A point A, its projection A′ on the screen and the projector between them, in the 3D pane.

The lesson on perspective (and the one on parallel projection) is about one
picture: a point A of the scene, the line along which the observer projects
it, and A′ where that line meets the screen.  :class:`ProjectorLines` draws it
for the point a lesson step highlights: A and A′ as dots with their labels,
the line from A to the eye (perspective) or from A to the screen along the
viewing direction (orthographic).  A′ comes from the camera's own projection
(:func:`core.projection_ray.screen_image`).  It is drawn while the model's
``"frustum"`` overlay is on (the screen it lands on is then shown), and it
follows the observer when the camera moves.
"""

from __future__ import annotations

import numpy as np

from core.projection_ray import screen_image
from views.scene3d.scene_overlays import LABEL_PT

PROJECTOR_OVERLAY = "projector"
"""The 3D pane's overlay of the projection marks; shown with the frustum."""
PROJECTOR_COLOR = "#ff3030"
"""Red: apart from the yellow frustum, the blue screen, the magenta polygon of the object-order step
and the scene's own colours."""


def projector_parts(camera, point) -> list[tuple]:
    """A, A′ and the projector of world point ``point`` for ``camera`` (empty if A′ is not defined)."""
    import pyvista as pv

    from views.scene3d import vtk_convert

    image = screen_image(camera, point)
    if image is None:
        return []
    a = np.asarray(point, float)
    source = image if camera.projection == "orthographic" else np.asarray(camera.eye, float)
    line = pv.PolyData(np.array([a, image, source]), lines=np.array([2, 0, 1, 2, 1, 2]))
    dots = pv.PolyData(np.array([a, image]))
    labels = vtk_convert.set_labels(pv.PolyData(np.array([a, image])), ["A", "A′"])
    return [(line, {"color": PROJECTOR_COLOR, "line_width": 3}),
            (dots, {"color": PROJECTOR_COLOR, "point_size": 10, "render_points_as_spheres": True}),
            (labels, {"label_size": LABEL_PT + 3, "color": PROJECTOR_COLOR})]


class ProjectorLines:
    """Keeps the projection marks of one point in the 3D pane ``view`` in step with ``model``.

    Attributes
    ----------
    point : the world point A marked, or None.
    """

    def __init__(self, model, view):
        self.model, self.view = model, view
        self.point: np.ndarray | None = None
        self._drawn = False  # marks are in the pane
        model.camera_changed.connect(self._draw)
        model.overlays_changed.connect(self._draw)

    def show_point(self, point) -> None:
        """Mark ``point`` (world space) and its projection; ``None`` removes the marks."""
        self.point = None if point is None else np.asarray(point, float)
        self._draw()

    def _draw(self, *_) -> None:
        shown = self.point is not None and "frustum" in self.model.overlays
        parts = projector_parts(self.model.camera, self.point) if shown else []
        if parts or self._drawn:  # nothing to draw and nothing to take away: the pane is left alone
            self.view.set_overlay(PROJECTOR_OVERLAY, parts)
        self._drawn = bool(parts)
