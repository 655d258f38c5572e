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

from core.barycentric_crossings import first_crossings
from core.camera import Camera, pixel_ray

#: Distance (pixels) of the four extra samples from the pixel centre.
JITTER = 1.0 / 64.0


def _rays(camera: Camera, dx: float, dy: float) -> tuple[np.ndarray, np.ndarray]:
    """The rays of :func:`core.camera.pixel_ray` through pixel positions ``(i + 0.5 + dx, j + 0.5 + dy)``,
    (H*W, 3) each, each direction scaled to length 1 along the viewing axis (so ``t`` is depth)."""
    x, y = np.meshgrid(np.arange(camera.width) + dx, np.arange(camera.height) + dy)
    eye, forward = tuple(map(float, camera.eye)), tuple(camera.forward.tolist())
    _, direction, _, _ = pixel_ray(
        x, y, float(camera.width), float(camera.height), *camera.half_extent(1.0), eye,
        tuple(camera.world_from_view[:3, :3].ravel().tolist()), forward, camera.near, camera.far, False)
    d = np.stack(direction, axis=-1).reshape(-1, 3)
    d /= (d @ camera.forward)[:, None]
    return np.broadcast_to(np.asarray(eye), d.shape), d


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
    The ray direction is scaled to length 1 along the viewing axis, so the
    crossing's ``t`` is its depth and the near/far test is ``near <= t <= far``.
    The crossing is solved in float64 with barycentric weights
    (:func:`core.barycentric_crossings.first_crossings`; a sample on an edge is
    decided either way, :func:`reference` discards such pixels).
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
