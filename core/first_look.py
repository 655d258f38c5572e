"""A first look at the scene in plain numpy, for the seconds before the compiled kernels are ready.

The first render on a machine compiles the renderers' kernels (a minute or
more on a small machine; :mod:`core.compiling.kernel_cache` keeps them afterwards).  So
that the window shows the scene at once, it first casts one ray per block of
pixels with numpy: the lecture's ray "from the eye through the pixel"
(:meth:`core.camera.Camera.primary_rays`), its first crossing with a triangle
(spheres as their triangles; :func:`core.barycentric_crossings.first_crossings`),
and the lights' cosine at that point, with no shadows, reflection or
refraction.  The window marks the picture as such.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from core.barycentric_crossings import first_crossings
from core.scene import Mesh, Scene, Sphere
from core.shapes import uv_sphere

#: Sphere tessellation of the first look: coarse, it is a first look.
SPHERE_RINGS, SPHERE_SEGMENTS = 12, 24


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
