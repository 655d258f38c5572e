"""The ray caster as the reference for what a rasterizer should cover.

The lecture notes that image order "automatically solves the problems of
clipping, projections, obscuring and rasterisation".  So a ray per pixel
centre, crossed with every triangle, says which surface each pixel should
show; the object-order cases (clipping, culling) are compared with it.

A pixel whose centre lies within a tiny distance of an edge may fairly go
either way (the rasterizer snaps corners to 1/256 pixel).  Each pixel is
therefore also sampled at four points ``JITTER`` pixels from its centre; it
is *certain* when all five samples see the same triangle, and comparisons
count certain pixels only.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.first_look import first_crossings

#: Distance (pixels) of the four extra samples from the pixel centre.
JITTER = 1.0 / 64.0


def _rays(camera: Camera, dx: float, dy: float) -> tuple[np.ndarray, np.ndarray]:
    """Perspective rays through pixel positions ``(i + 0.5 + dx, j + 0.5 + dy)``, (H*W, 3) each."""
    w, h = camera.width, camera.height
    hw, hh = camera.half_extent(1.0)
    xs = ((np.arange(w) + 0.5 + dx) / w * 2.0 - 1.0) * hw
    ys = (1.0 - (np.arange(h) + 0.5 + dy) / h * 2.0) * hh
    px, py = np.meshgrid(xs, ys)
    view = np.stack([px, py, -np.ones_like(px)], axis=-1).reshape(-1, 3)
    directions = view @ camera.world_from_view[:3, :3].T
    return np.broadcast_to(np.asarray(camera.eye, float), directions.shape), directions


def nearest_triangle(camera: Camera, triangles: np.ndarray, dx: float = 0.0, dy: float = 0.0) -> np.ndarray:
    """Index of the nearest triangle each pixel's ray crosses between the near and far planes.

    Parameters
    ----------
    camera : a perspective observer.
    triangles : (T, 3, 3) float64, world space.
    dx, dy : offset of the sample from the pixel centre, pixels.

    Returns
    -------
    (H, W) int64, -1 where the ray crosses nothing in the frustum's depth range.

    Notes
    -----
    The ray direction's view-space z is -1, so the crossing's ``t`` is its
    depth along the viewing axis and the near/far test is ``near <= t <= far``.
    The crossing is solved in float64 with barycentric weights (a sample on an
    edge is decided either way; :func:`reference` discards such pixels).
    """
    o, d = _rays(camera, dx, dy)
    first, _ = first_crossings(np.ascontiguousarray(o), d, triangles, camera.near, camera.far)
    return first.reshape(camera.height, camera.width)


def reference(camera: Camera, triangles: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The triangle each pixel should show, and whether that is certain.

    Returns
    -------
    seen : (H, W) int64, nearest triangle at the pixel centre (-1: none).
    certain : (H, W) bool, the four samples ``JITTER`` pixels away agree.
    """
    seen = nearest_triangle(camera, triangles)
    certain = np.ones_like(seen, dtype=bool)
    for dx, dy in ((JITTER, 0.0), (-JITTER, 0.0), (0.0, JITTER), (0.0, -JITTER)):
        certain &= nearest_triangle(camera, triangles, dx, dy) == seen
    return seen, certain
