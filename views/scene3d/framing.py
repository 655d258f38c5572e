"""Framing a perspective view camera on points, some of which carry labels.

The 3D pane's overview camera looks along a chosen direction; :func:`fit_view`
finds where it must stand (sideways and back) so that every point appears
inside the pane, each with room around it: a plain point a small margin
inside the edges, a label's anchor far enough in that its whole text (centred
above the anchor) shows.  It is plain geometry, free of VTK, so it can be
checked by hand.

For a camera at ``e`` looking along ``d`` (up ``u``, right ``r``), a point
``p`` lands at ``x = (p − e)·r / ((p − e)·d · tan_x)`` on the pane's ``[-1, 1]``
width (and likewise ``y`` with ``u`` and ``tan_y``).  Keeping ``x`` between
``lo`` and ``hi`` is linear in ``e`` once the distance along ``d`` is fixed;
stepping back only loosens it, so the nearest position that keeps every point
inside is found by bisection on that distance, and the sideways offset is
then the middle of what remains allowed.
"""

from __future__ import annotations

import numpy as np

MARGIN = 0.04
"""Room left between a point and the pane's edge, as a share of the pane's half-width (or height)."""
LEAST_ROOM = 0.1
"""A label's anchor may move at least this far either way, in pane units, however large the label."""


def label_bounds(width_px: float, height_px: float, pane_px: tuple[float, float],
                 margin: float = MARGIN) -> np.ndarray:
    """Where a label's anchor may go, ``[[x_lo, x_hi], [y_lo, y_hi]]`` in ``[-1, 1]`` pane units,
    for a text ``width_px`` × ``height_px`` centred above its anchor in a pane ``pane_px`` (w, h)."""
    # A text (nearly) as wide or tall as the pane keeps a little room to move, so a framing exists.
    half_w = min(width_px / pane_px[0], 1.0 - margin - LEAST_ROOM)
    tall = min(2.0 * height_px / pane_px[1], 2.0 - 2 * margin - 2 * LEAST_ROOM)
    return np.array([[-1 + margin + half_w, 1 - margin - half_w], [-1 + margin, 1 - margin - tall]])


def fit_view(points, direction, up, view_angle_deg: float, aspect: float, bounds=None,
             margin: float = MARGIN) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Camera ``(position, focal_point, up)`` looking along ``direction`` that shows every point.

    ``points`` (N, 3) world points; ``view_angle_deg`` the camera's vertical
    view angle; ``aspect`` the pane's width / height; ``bounds`` (N, 2, 2) for
    each point the ``[[x_lo, x_hi], [y_lo, y_hi]]`` range it must land in
    (:func:`label_bounds`), default the whole pane less ``margin``.  The focal
    point is the points' middle, seen straight ahead.
    """
    points = np.asarray(points, float).reshape(-1, 3)
    d = np.asarray(direction, float)
    d = d / np.linalg.norm(d)
    u = np.asarray(up, float) - np.dot(up, d) * d
    if np.linalg.norm(u) < 1e-9:  # up along the view: any perpendicular will do
        u = np.cross(d, (1.0, 0.0, 0.0) if abs(d[0]) < 0.9 else (0.0, 1.0, 0.0))
    u = u / np.linalg.norm(u)
    r = np.cross(d, u)
    if bounds is None:
        bounds = np.tile([[-1 + margin, 1 - margin], [-1 + margin, 1 - margin]], (len(points), 1, 1))
    bounds = np.asarray(bounds, float)
    tan_y = np.tan(np.radians(view_angle_deg) / 2)
    tans = np.array([tan_y * aspect, tan_y])
    across = np.stack([points @ r, points @ u], axis=1)  # (N, 2)
    along = points @ d

    def allowed(back: float) -> tuple[np.ndarray, np.ndarray]:
        """Lowest and highest sideways eye offsets (right, up) with the eye at ``back`` along d."""
        depth = (along - back)[:, None]
        low = (across - bounds[:, :, 1] * tans * depth).max(axis=0)
        high = (across - bounds[:, :, 0] * tans * depth).min(axis=0)
        return low, high

    size = float(np.ptp(points, axis=0).max()) + 1.0
    near, far = along.min() - 1e-6 * size, along.min() - size  # too close, surely far enough
    while np.any(np.subtract(*allowed(far)) > 0):
        far -= 2 * (near - far)
    for _ in range(60):
        middle = (near + far) / 2
        if np.all(np.subtract(*allowed(middle)) <= 0):
            far = middle
        else:
            near = middle
    low, high = allowed(far)
    sideways = (low + high) / 2
    position = sideways[0] * r + sideways[1] * u + far * d
    focal = position + (along.mean() - far) * d
    return position, focal, u
