"""The lesson exercises' independent references: a camera built by hand, and brute-force crossings.

The camera's frame, a pixel's ray, a point's pixel and the frustum's sides are
written here from the lecture's definitions (the eye looks at the target, +y of
the image is up, pixels counted from the top left, rays through pixel centres),
with none of :mod:`core.camera` or :mod:`core.projection`.  Crossings are
found by testing every triangle and sphere of the scene
(:func:`brute_force.hit_triangle`, :func:`brute_force.hit_spheres`), with no
bounding volume, grid or compiled kernel.
"""

from __future__ import annotations

import math

import numpy as np
from brute_force import hit_spheres, hit_triangle

from core.scene import Sphere


def frame(camera):
    """``(right, up, forward)``: the observer's unit axes in world space."""
    forward = np.subtract(camera.target, camera.eye, dtype=float)
    forward /= np.linalg.norm(forward)
    right = np.cross(forward, camera.up)
    right /= np.linalg.norm(right)
    return right, np.cross(right, forward), forward


def half_size(camera):
    """Half width and half height of the image plane at distance 1 (perspective) or of the view
    volume (orthographic), scene units."""
    half_h = camera.ortho_height / 2 if camera.projection == "orthographic" else math.tan(
        math.radians(camera.fov_y_deg) / 2)
    return half_h * camera.width / camera.height, half_h


def rays(camera, xs, ys):
    """Origins and unit directions, (N, 3) each, of the rays through the centres of pixels
    ``(xs[i], ys[i])``."""
    right, up, forward = frame(camera)
    hw, hh = half_size(camera)
    u = ((np.asarray(xs, float) + 0.5) / camera.width * 2 - 1) * hw
    v = (1 - (np.asarray(ys, float) + 0.5) / camera.height * 2) * hh
    if camera.projection == "orthographic":
        origins = np.asarray(camera.eye) + u[:, None] * right + v[:, None] * up
        return origins, np.broadcast_to(forward, origins.shape).copy()
    d = forward + u[:, None] * right + v[:, None] * up
    return np.broadcast_to(np.asarray(camera.eye, float), d.shape).copy(), d / np.linalg.norm(
        d, axis=1, keepdims=True)


def pixel_ray(camera, x, y):
    """Origin and unit direction, (3,) each, of the ray through the centre of pixel ``(x, y)``."""
    o, d = rays(camera, [x], [y])
    return o[0], d[0]


def view_coordinates(camera, points):
    """``(N, 3)``: each point's offset from the eye along right, up and forward (its depth)."""
    offset = np.atleast_2d(np.asarray(points, float)) - np.asarray(camera.eye, float)
    return np.stack([offset @ axis for axis in frame(camera)], axis=1)


def pixel_of(camera, point):
    """The pixel ``(column, row)`` whose square holds the point's image."""
    x, y, depth = view_coordinates(camera, point)[0]
    hw, hh = half_size(camera)
    if camera.projection != "orthographic":
        x, y = x / depth, y / depth
    return (math.floor((x / hw + 1) / 2 * camera.width), math.floor((1 - y / hh) / 2 * camera.height))


def frustum_distances(camera, points):
    """Signed distances (N, 6) of perspective-view points from the frustum's planes, left, right,
    bottom, top, near, far: positive inside.  A side plane through the eye with slope ``h`` holds
    ``x = h·depth``; its inward unit normal is ``(1, 0, h) / √(1 + h²)`` in (right, up, forward)."""
    x, y, depth = view_coordinates(camera, points).T
    hw, hh = half_size(camera)
    sides = [(hw * depth + x) / math.hypot(1, hw), (hw * depth - x) / math.hypot(1, hw),
             (hh * depth + y) / math.hypot(1, hh), (hh * depth - y) / math.hypot(1, hh)]
    return np.stack([*sides, depth - camera.near, camera.far - depth], axis=1)


def crossings(obj, origins, directions):
    """Nearest t >= 0 of each unit ray on ``obj`` (every triangle tested), +inf on a miss; (N,)."""
    if isinstance(obj, Sphere):
        return hit_spheres(origins, directions, obj.center, obj.radius)
    t = np.full(len(origins), np.inf)
    for corners in obj.corners:
        t = np.minimum(t, hit_triangle(origins, directions, *corners))
    return t


def hits(scene, origin, direction, t_min=0.0):
    """Every object the ray meets beyond ``t_min``, nearest first: ``[(t, name), ...]``."""
    o, d = np.asarray(origin, float)[None], np.asarray(direction, float)[None]
    o = o + t_min * d
    found = [(float(crossings(obj, o, d)[0]) + t_min, obj.name) for obj in scene.objects]
    return sorted(hit for hit in found if math.isfinite(hit[0]))


def shadow_blockers(scene, x, y, light=0):
    """Pixel ``(x, y)``'s first hit and the objects between it and the light, nearest first (the
    shadow ray p + s (l - p), 0 < s < 1): ``(name hit, [blockers])``; ``(None, [])`` on a miss."""
    origin, direction = pixel_ray(scene.camera, x, y)
    found = hits(scene, origin, direction)
    if not found:
        return None, []
    t, name = found[0]
    point = origin + t * direction
    to_light = np.asarray(scene.lights[light].position) - point
    distance = np.linalg.norm(to_light)
    return name, [n for s, n in hits(scene, point, to_light / distance, t_min=1e-6) if s < distance]


def image_hits(scene, camera=None):
    """Every object's nearest t at every pixel of ``camera``'s image (the scene's by default):
    ``{name: (H, W) array}``, +inf where the object's crossing is missed."""
    camera = camera or scene.camera
    ys, xs = np.mgrid[0:camera.height, 0:camera.width]
    o, d = rays(camera, xs.ravel(), ys.ravel())
    return {obj.name: crossings(obj, o, d).reshape(camera.height, camera.width) for obj in scene.objects}


def nearest(maps):
    """``(H, W)`` name of the nearest object at each pixel of :func:`image_hits`, ``""`` for none."""
    names = list(maps)
    stack = np.stack([maps[n] for n in names])
    first = np.argmin(stack, axis=0)
    return np.where(np.isfinite(stack.min(axis=0)), np.array(names, dtype=object)[first], "")


def inner_pixel(mask):
    """A pixel ``(x, y)`` of ``mask`` whose 5 × 5 neighbourhood is all in ``mask`` (away from any
    edge, so no rounding decides it), the one nearest the mask's centre of mass; None if none."""
    m = np.asarray(mask, bool)
    inner = m.copy()
    for dy in range(-2, 3):
        for dx in range(-2, 3):
            inner &= np.roll(np.roll(m, dy, axis=0), dx, axis=1)
    inner[:2], inner[-2:], inner[:, :2], inner[:, -2:] = False, False, False, False
    ys, xs = np.nonzero(inner)
    if not len(xs):
        return None
    k = np.argmin((xs - xs.mean()) ** 2 + (ys - ys.mean()) ** 2)
    return int(xs[k]), int(ys[k])
