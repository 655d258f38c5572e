"""Ready-made scenes for ray casting and ray tracing.

Each shows one thing the image-order renderer does:

- :func:`mirror_and_glass` - a mirror ball and a glass ball beside a cube and a
  cone on a ground plane: reflection, refraction, Fresnel, shadows, ray trees.
- :func:`no_lights` - the same objects without a light: no shadow rays at all,
  ambient light only.
- :func:`lone_sphere` - one sphere and one light: nothing can block the light,
  so the effects plan drops its shadow rays.
- :func:`facing_mirrors` - two parallel mirrors: ray trees as deep as the depth
  limit allows, and the minimum weight cutting them short.
- :func:`far_from_origin` - :func:`mirror_and_glass` moved 10^4 units away:
  the fixed epsilon offset shows shadow acne there, the scaled one does not.
- :func:`big_mesh` - a bumpy ball of about 100,000 triangles: compare the
  acceleration methods' work.

:data:`PRESETS_TRACE` maps a short key to a title and the builder.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import replace

import numpy as np

from core import shapes
from core.camera import Camera
from core.scene import Material, Mesh, PointLight, Scene, Sphere

MIRROR = Material(color=(0.9, 0.9, 0.92), reflectivity=0.85, ambient=0.05, diffuse=0.3, specular=0.8,
                  shininess=200.0)
GLASS = Material(color=(0.95, 0.97, 1.0), opacity=0.3, transparency=0.9, reflectivity=0.0, ior=1.5,
                 ambient=0.02, diffuse=0.1, specular=0.8, shininess=200.0)
GROUND = Material(color=(0.82, 0.82, 0.8), specular=0.05)
#: The observer of :func:`big_mesh`: the bumpy ball fills most of the view.
BIG_MESH_CAMERA = Camera(eye=(0.0, 3.0, 6.5), target=(0.0, 0.8, 0.0))


def _objects_of_the_lecture():
    cube = shapes.box((-1.7, 0.8, -1.6), 1.6, Material(color=(0.95, 0.55, 0.2), specular=0.3), name="cube")
    cone = shapes.cone((1.6, 0.0, -1.2), 0.9, 2.0, segments=48,
                       material=Material(color=(0.15, 0.55, 0.75), specular=0.4), name="cone")
    ground = shapes.quad((0.0, 0.0, 0.0), 14.0, GROUND, name="ground")
    return cube, cone, ground


def mirror_and_glass() -> Scene:
    """A mirror ball and a glass ball in front of a cube and a cone, on a ground plane, one light."""
    cube, cone, ground = _objects_of_the_lecture()
    mirror = Sphere((-0.6, 0.9, 0.9), 0.9, MIRROR, name="mirror ball")
    glass = Sphere((1.3, 0.75, 1.4), 0.75, GLASS, name="glass ball")
    return Scene(
        camera=Camera(eye=(0.5, 2.6, 8.0), target=(0.0, 0.8, 0.0)),
        objects=(cube, cone, ground, mirror, glass),
        lights=(PointLight((4.0, 8.0, 6.0)),),
    )


def no_lights() -> Scene:
    """:func:`mirror_and_glass` without its light: ambient light only, no shadow rays."""
    return replace(mirror_and_glass(), lights=())


def lone_sphere() -> Scene:
    """One sphere and one light: nothing can cast a shadow, so no shadow rays are traced."""
    return Scene(
        camera=Camera(eye=(0.0, 1.0, 6.0), target=(0.0, 0.0, 0.0)),
        objects=(Sphere((0.0, 0.0, 0.0), 1.5, Material(color=(0.8, 0.3, 0.3), specular=0.5), name="ball"),),
        lights=(PointLight((3.0, 4.0, 5.0)),),
    )


def facing_mirrors() -> Scene:
    """Two long parallel mirrors with a ball between them: rays bounce to and fro until the depth limit."""
    wall = Material(color=(0.85, 0.9, 0.85), reflectivity=0.9, ambient=0.05, diffuse=0.1, specular=0.3)
    left = shapes.box((-2.0, 1.5, -6.0), (0.1, 3.0, 24.0), wall, name="left mirror")
    right = shapes.box((2.0, 1.5, -6.0), (0.1, 3.0, 24.0), wall, name="right mirror")
    ball = Sphere((0.0, 0.8, 2.0), 0.6, Material(color=(0.9, 0.3, 0.2), specular=0.5), name="ball")
    ground = shapes.quad((0.0, 0.0, -6.0), 30.0, GROUND, name="ground")
    return Scene(
        camera=Camera(eye=(1.2, 1.6, 5.0), target=(-2.0, 1.2, 3.6)),
        objects=(left, right, ball, ground),
        lights=(PointLight((0.0, 6.0, 3.0)),),
    )


def translated(scene: Scene, offset) -> Scene:
    """``scene`` with its objects, lights and camera moved by ``offset`` (3,), scene units."""
    off = np.asarray(offset, dtype=float)

    def move(obj):
        if isinstance(obj, Sphere):
            return replace(obj, center=tuple(np.add(obj.center, off)))
        return Mesh(obj.vertices + off, obj.triangles, obj.material, obj.name)

    cam = scene.camera
    return replace(
        scene,
        camera=cam.replace(eye=np.add(cam.eye, off), target=np.add(cam.target, off)),
        objects=tuple(move(o) for o in scene.objects),
        lights=tuple(replace(light, position=tuple(np.add(light.position, off))) for light in scene.lights),
    )


def far_from_origin() -> Scene:
    """:func:`mirror_and_glass` translated by (10^4, 0, 10^4): try the fixed ray offset here."""
    return translated(mirror_and_glass(), (1e4, 0.0, 1e4))


def bumpy_ball(triangles: int = 100_000, seed: int = 0) -> Mesh:
    """A tessellated ball of about ``triangles`` triangles with a randomly bumpy surface.

    A uv-sphere of radius 2 around ``(0, 0.8, 0)`` whose vertices are moved in or
    out by up to a few percent (seeded, so always the same mesh).
    """
    n = max(3, int(round((triangles / 2) ** 0.5)))
    ball = shapes.uv_sphere((0.0, 0.8, 0.0), 2.0, rings=n, segments=n)
    rng = np.random.default_rng(seed)
    center = np.array([0.0, 0.8, 0.0])
    bump = 1.0 + 0.03 * rng.standard_normal((len(ball.vertices), 1))
    return Mesh(center + (ball.vertices - center) * bump, ball.triangles,
                Material(color=(0.75, 0.7, 0.6), specular=0.3), name="bumpy ball")


def big_mesh() -> Scene:
    """:func:`bumpy_ball` (about 100,000 triangles) on a ground plane, filling most of the view."""
    return Scene(
        camera=BIG_MESH_CAMERA,
        objects=(bumpy_ball(), shapes.quad((0.0, -1.2, 0.0), 14.0, GROUND, name="ground")),
        lights=(PointLight((4.0, 8.0, 6.0)),),
    )


def warm_up_scene() -> Scene:
    """The smallest scene that runs every kernel: a glass ball, a mirror triangle, a light."""
    tri = Mesh(np.array([[-1.0, -1.0, -2.0], [1.0, -1.0, -2.0], [0.0, 1.0, -2.0]]), np.array([[0, 1, 2]]),
               MIRROR, name="mirror")
    return Scene(
        camera=Camera(eye=(0.0, 0.0, 3.0), target=(0.0, 0.0, 0.0), width=2, height=2),
        objects=(Sphere((0.0, 0.0, 0.0), 0.5, GLASS, name="glass"), tri),
        lights=(PointLight((0.0, 3.0, 3.0)),),
    )


PRESETS_TRACE: dict[str, tuple[str, Callable[[], Scene]]] = {
    "mirror_and_glass": ("Mirror and glass balls", mirror_and_glass),
    "no_lights": ("No lights (ambient only)", no_lights),
    "lone_sphere": ("A lone sphere (no shadow rays needed)", lone_sphere),
    "facing_mirrors": ("Facing mirrors (deep ray trees)", facing_mirrors),
    "far_from_origin": ("Far from the origin (shadow acne test)", far_from_origin),
    "big_mesh": ("A mesh of 100,000 triangles", big_mesh),
}
"""Preset key -> (title, builder)."""
