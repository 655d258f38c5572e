"""A first look at the scene in plain numpy, for the seconds before the compiled kernels are ready.

The first render on a machine compiles the renderers' kernels (a minute or
more on a small machine; :mod:`core.compiling.kernel_cache` keeps them afterwards).  So
that the window shows the scene at once, it first casts one ray per block of
pixels with numpy: the lecture's ray "from the eye through the pixel"
(:meth:`core.camera.Camera.primary_rays`), its first crossing with a triangle
(spheres as their triangles), and the lights' cosine at that point, with no
shadows, reflection or refraction.  The window marks the picture as such.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from core.scene import Mesh, Scene, Sphere
from core.shapes import uv_sphere

#: Rays per chunk of the crossing test (each chunk holds rays x triangles numbers).
CHUNK_TESTS = 2_000_000
#: Sphere tessellation of the first look: coarse, it is a first look.
SPHERE_RINGS, SPHERE_SEGMENTS = 12, 24


def first_crossings(origins: np.ndarray, directions: np.ndarray, triangles: np.ndarray,
                    t_min: float = 0.0, t_max: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
    """The first triangle each ray crosses with ``t_min <= t <= t_max``, and its ``t``.

    The crossing solves ``o + t d = A + u (B - A) + v (C - A)`` (the lecture's
    barycentric test, by Cramer's rule in the Möller–Trumbore arrangement) for
    every ray and triangle at once; a ray crosses a triangle where ``u, v >= 0``
    and ``u + v <= 1``.  A ray through an edge counts for either triangle.

    Parameters
    ----------
    origins, directions : (R, 3) float64, world space.
    triangles : (T, 3, 3) float64, world space.
    t_min, t_max : the part of the ray searched (the frustum's depth range, say).

    Returns
    -------
    index : (R,) int64, the nearest triangle, -1 where the ray crosses none.
    t : (R,) float64, its ``t`` (``inf`` where none).

    Examples
    --------
    >>> tri = np.array([[[-1.0, -1.0, -5.0], [1.0, -1.0, -5.0], [0.0, 1.0, -5.0]]])
    >>> first_crossings(np.zeros((2, 3)), np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]), tri)
    (array([ 0, -1]), array([ 5., inf]))
    """
    n = len(origins)
    index = np.full(n, -1, dtype=np.int64)
    nearest = np.full(n, np.inf)
    if len(triangles) == 0:
        return index, nearest
    A, e1, e2 = triangles[:, 0], triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0]
    step = max(1, CHUNK_TESTS // len(triangles))
    for first in range(0, n, step):
        o, d = origins[first:first + step], directions[first:first + step]
        h = np.cross(d[:, None, :], e2[None])
        det = np.einsum("rtk,tk->rt", h, e1)
        with np.errstate(divide="ignore", invalid="ignore"):
            s = o[:, None, :] - A[None]
            u = np.einsum("rtk,rtk->rt", s, h) / det
            q = np.cross(s, e1[None])
            v = np.einsum("rk,rtk->rt", d, q) / det
            t = np.einsum("tk,rtk->rt", e2, q) / det
        crossed = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= t_min) & (t <= t_max)
        t = np.where(crossed, t, np.inf)
        best = np.argmin(t, axis=1)
        t_best = t[np.arange(len(t)), best]
        found = np.isfinite(t_best)
        index[first:first + step] = np.where(found, best, -1)
        nearest[first:first + step] = t_best
    return index, nearest


def scene_triangles(scene: Scene) -> tuple[np.ndarray, np.ndarray]:
    """Every object's triangles, (T, 3, 3), and the object each belongs to, (T,)."""
    parts, owners = [], []
    for k, obj in enumerate(scene.objects):
        if isinstance(obj, Sphere):
            obj = uv_sphere(obj.center, obj.radius, SPHERE_RINGS, SPHERE_SEGMENTS)
        if isinstance(obj, Mesh) and len(obj.triangles):
            parts.append(np.asarray(obj.vertices, float)[np.asarray(obj.triangles)])
            owners.append(np.full(len(obj.triangles), k))
    if not parts:
        return np.zeros((0, 3, 3)), np.zeros(0, dtype=np.int64)
    return np.concatenate(parts), np.concatenate(owners)


def first_look(scene: Scene, step: int = 4) -> np.ndarray:
    """The scene from its observer, one ray per ``step`` x ``step`` block, as a full-size linear RGB image.

    A hit is coloured ``color * (ambient + diffuse * sum of the lights' N . L)``, the
    normal turned towards the eye; a miss shows the background.
    """
    cam = scene.camera
    coarse = cam.replace(width=max(1, -(-cam.width // step)), height=max(1, -(-cam.height // step)))
    origins, directions = coarse.primary_rays()
    o, d = origins.reshape(-1, 3), directions.reshape(-1, 3)
    triangles, owners = scene_triangles(replace(scene, camera=coarse))
    index, t = first_crossings(o, d, triangles)
    rgb = np.empty((len(o), 3))
    rgb[:] = scene.background
    hit = index >= 0
    if hit.any():
        tri = triangles[index[hit]]
        normal = np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0])
        normal /= np.maximum(np.linalg.norm(normal, axis=1, keepdims=True), 1e-300)
        normal *= -np.sign(np.einsum("rk,rk->r", normal, d[hit]))[:, None]  # towards the eye
        point = o[hit] + t[hit, None] * d[hit]
        light = np.zeros(len(point))
        for lamp in scene.lights:
            to_light = np.asarray(lamp.position, float) - point
            to_light /= np.maximum(np.linalg.norm(to_light, axis=1, keepdims=True), 1e-300)
            light += lamp.intensity * np.maximum(0.0, np.einsum("rk,rk->r", normal, to_light))
        materials = [scene.objects[k].material for k in owners[index[hit]]]
        color = np.array([m.color for m in materials])
        ambient = np.array([m.ambient for m in materials])
        diffuse = np.array([m.diffuse for m in materials])
        rgb[hit] = color * (ambient + diffuse * light)[:, None]
    image = np.clip(rgb.reshape(coarse.height, coarse.width, 3), 0.0, 1.0)
    rows = np.minimum(np.arange(cam.height) // step, coarse.height - 1)
    cols = np.minimum(np.arange(cam.width) // step, coarse.width - 1)
    return image[rows][:, cols]
