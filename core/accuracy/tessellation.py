"""Tessellation: the object-order pipeline's stand-in for a true sphere.

The rasterizer draws triangles only, so an analytic sphere becomes a mesh of
``rings`` bands of latitude by ``segments`` of longitude
(:func:`core.shapes.uv_sphere`).  Its corners lie on the sphere and its flat
faces inside it: the silhouette is a polygon and the depth is slightly too
far, by at most ``r (1 - cos(pi / segments))`` scene units at a face's middle.
Flat shading gives each face one colour, so the facets show until they are
smaller than a pixel.
"""

from __future__ import annotations

from dataclasses import replace

from core import shapes
from core.scene import Mesh, Scene, Sphere


def has_spheres(scene: Scene) -> bool:
    """Whether the scene holds any analytic sphere to tessellate."""
    return any(isinstance(obj, Sphere) for obj in scene.objects)


def tessellated(scene: Scene, rings: int, segments: int) -> Scene:
    """``scene`` with every analytic sphere replaced by a ``rings x segments`` triangle mesh."""
    objects = tuple(
        shapes.uv_sphere(obj.center, obj.radius, rings, segments, material=obj.material, name=obj.name)
        if isinstance(obj, Sphere) else obj
        for obj in scene.objects)
    return replace(scene, objects=objects)


def mesh_bytes(scene: Scene) -> int:
    """Bytes the scene's triangle meshes take (vertex positions and triangle indices)."""
    return sum(obj.vertices.nbytes + obj.triangles.nbytes for obj in scene.objects if isinstance(obj, Mesh))
