"""Ready-made scenes.

:func:`lecture_scene` is the scene of the lecture's second question: "a cube
and a cone placed on an opaque plane, wherein the cone partially obscures the
cube from the observer's point of view".  The others illustrate the object
order pipeline (:mod:`core.object_order.pipeline`): the z-buffer figure, piercing
polygons, back-face culling on a convex and a non-convex solid, frustum
culling, and transparency.  :data:`PRESETS` lists them all for a menu.
"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np

from core import shapes
from core.camera import Camera
from core.scene import Material, Mesh, PointLight, Scene, Sphere

CUBE_CENTER = (-1.7, 0.8, -1.1)
CUBE_SIZE = 1.6
CONE_BASE = (0.6, 0.0, 1.0)
CONE_RADIUS = 1.0
CONE_HEIGHT = 2.2
#: Upper left and in front of the objects: seen from the default observer, the
#: cone's and the cube's shadows fall to their right on the ground.
LECTURE_LIGHT = (-10.0, 12.0, 8.0)


def lecture_scene() -> Scene:
    """A cube and a cone on an opaque ground plane; the cone partly hides the cube.

    Seen from the default :class:`~core.camera.Camera` (eye ``(6, 4, 9)``
    looking at ``(0, 0.8, 0)``) the cube stands behind the cone, shifted to the
    left, so part of the cube is hidden by the cone and part of it is seen.
    The ground is a 14 x 14 quad at ``y = 0``; one point light shines from
    the upper left, in front of the objects, so both shadows fall to the right
    on the ground, where the observer sees them.
    """
    cube = shapes.box(
        CUBE_CENTER,
        CUBE_SIZE,
        Material(color=(0.95, 0.55, 0.2), specular=0.3),
        name="cube",
    )
    cone = shapes.cone(
        CONE_BASE,
        CONE_RADIUS,
        CONE_HEIGHT,
        segments=48,
        material=Material(color=(0.15, 0.55, 0.75), specular=0.4),
        name="cone",
    )
    ground = shapes.quad(
        (0.0, 0.0, 0.0),
        14.0,
        Material(color=(0.82, 0.82, 0.8), specular=0.05),
        name="ground",
    )
    return Scene(
        camera=Camera(),
        objects=(cube, cone, ground),
        lights=(PointLight(LECTURE_LIGHT),),
    )


def _flat(color) -> Material:
    """A material shown in exactly its colour when the scene has no lights (k_a + k_d = 1)."""
    return Material(color=color, ambient=0.2, diffuse=0.8)


def _triangle(corners, material: Material, name: str) -> Mesh:
    return Mesh(vertices=corners, triangles=[[0, 1, 2]], material=material, name=name)


GREEN, BLUE, YELLOW = (0.2, 0.75, 0.3), (0.2, 0.4, 0.9), (0.95, 0.85, 0.2)
ZBUFFER_CAMERA = Camera(eye=(0.0, 0.0, 6.0), target=(0.0, 0.0, 0.0), near=1.0, far=12.0,
                        width=160, height=120)


def zbuffer_three_polygons() -> Scene:
    """The lecture's z-buffer figure: three overlapping polygons drawn green, blue, yellow.

    Seen straight on, each one a single tilted triangle.  Green is farthest;
    blue is nearest; yellow, drawn last, lies between them: its fragments pass
    over green and fail behind blue.  No lights, so each keeps its flat colour.
    """
    green = _triangle([(-2.0, -1.4, -1.5), (1.2, -1.4, -0.5), (-0.6, 1.6, -1.0)], _flat(GREEN), "green")
    blue = _triangle([(-0.6, -0.9, 0.8), (2.2, -0.6, 0.2), (1.0, 1.8, 0.5)], _flat(BLUE), "blue")
    yellow = _triangle([(-1.6, -1.9, 0.2), (1.8, -1.7, 0.0), (0.0, 0.6, -0.2)], _flat(YELLOW), "yellow")
    return Scene(camera=ZBUFFER_CAMERA, objects=(green, blue, yellow))


def zbuffer_piercing() -> Scene:
    """Two polygons that pierce each other along the line x = 0.

    Green rises toward the observer to the right (z = 0.6 x), blue to the left
    (z = -0.6 x): each is in front on one side of the crossing line, which the
    z-buffer settles pixel by pixel, whatever the drawing order.
    """
    green = _triangle([(-2.0, -1.3, -1.2), (2.0, -1.3, 1.2), (0.0, 1.7, 0.0)], _flat(GREEN), "green")
    blue = _triangle([(-2.0, -1.1, 1.2), (2.0, -1.1, -1.2), (0.2, 1.5, -0.12)], _flat(BLUE), "blue")
    return Scene(camera=ZBUFFER_CAMERA, objects=(green, blue))


def zbuffer_piercing_blue_first() -> Scene:
    """:func:`zbuffer_piercing` drawn in the other order: blue first, then green (the same final picture)."""
    scene = zbuffer_piercing()
    return Scene(camera=scene.camera, objects=scene.objects[::-1])


CULLING_CAMERA = Camera(eye=(2.5, 3.2, 6.5), target=(0.0, 0.7, 0.0), near=1.0, far=20.0)


def culling_pyramid() -> Scene:
    """A convex pyramid (Fig. VII.4a): back-face culling alone decides what is seen."""
    pyramid = shapes.pyramid((0.0, 0.0, 0.0), 2.4, 2.2, Material(color=(0.9, 0.6, 0.25)), "pyramid")
    return Scene(camera=CULLING_CAMERA, objects=(pyramid,), lights=(PointLight((3.0, 6.0, 5.0)),))


def culling_notched() -> Scene:
    """The non-convex notched prism (Fig. VII.4b): a front face partly hidden by the solid itself.

    The notch's inner wall facing +z passes back-face culling, yet the L's
    other arm hides part of it; the z-buffer resolves the rest.
    """
    prism = shapes.notched_prism((0.0, 0.0, 0.0), (2.6, 1.6, 2.2), (1.2, 1.0),
                                 Material(color=(0.35, 0.75, 0.4)), "notched prism")
    return Scene(camera=CULLING_CAMERA, objects=(prism,), lights=(PointLight((3.0, 6.0, 5.0)),))


def frustum_cases() -> Scene:
    """The lecture's cube and cone, plus a sphere half outside the frustum and a box behind the observer.

    From the default camera: the cube and the cone lie inside the frustum, the
    sphere straddles its right plane (crossing), the box is behind the eye
    (outside) and the large ground plane reaches behind the eye (crossing: its
    polygons are clipped at the near plane).
    """
    base = lecture_scene()
    cube, cone, _ = base.objects
    ground = shapes.quad((0.0, 0.0, 0.0), 26.0, Material(color=(0.82, 0.82, 0.8)), "ground")
    half_out = Sphere((4.9, 1.0, -0.5), 1.0, Material(color=(0.8, 0.3, 0.5)), "sphere")
    behind = shapes.box((7.5, 0.6, 12.0), 1.2, Material(color=(0.6, 0.6, 0.9)), "box")
    return Scene(camera=base.camera, objects=(cube, cone, ground, half_out, behind), lights=base.lights)


def _pane(x0: float, x1: float, y0: float, y1: float, z: float, material: Material, name: str) -> Mesh:
    """A vertical rectangle in the plane ``z``, facing +z."""
    return Mesh(vertices=np.array([(x0, y0, z), (x1, y0, z), (x1, y1, z), (x0, y1, z)]),
                triangles=[[0, 1, 2], [0, 2, 3]], material=material, name=name)


def transparent_panes() -> Scene:
    """Three half-transparent panes in front of an opaque box, listed nearest first.

    Drawn in the listed order, the nearest pane is blended first and writes its
    depth, so the panes behind it fail the depth test there and vanish; sorted
    from the farthest to the closest (the lecture's rule), all three show.
    """
    box = shapes.box((-0.2, 0.9, -2.8), 1.8, Material(color=(0.9, 0.55, 0.2)), "opaque box")
    red = _pane(-1.6, 0.4, 0.7, 2.1, 1.4, Material(color=(0.95, 0.2, 0.2), opacity=0.5), "red pane")
    green = _pane(-1.0, 1.0, 0.1, 1.5, 0.2, Material(color=(0.2, 0.85, 0.3), opacity=0.5), "green pane")
    blue = _pane(-0.4, 1.6, 0.6, 2.0, -1.0, Material(color=(0.2, 0.4, 0.95), opacity=0.5), "blue pane")
    camera = Camera(eye=(1.2, 2.0, 5.2), target=(0.0, 1.0, -0.6), near=1.0, far=20.0)
    return Scene(camera=camera, objects=(red, green, blue, box), lights=(PointLight((2.0, 6.0, 8.0)),),
                 background=(0.8, 0.82, 0.85))


#: Observers A and B of :func:`observers_top_view`.
OBSERVER_A = Camera(eye=(0.0, 1.0, 8.0), target=(0.0, 1.0, 0.0), near=0.5, far=20.0)
OBSERVER_B = Camera(eye=(8.0, 1.5, 7.0), target=(0.0, 1.0, -1.5), near=0.5, far=20.0)


def observers_top_view() -> Scene:
    """Fig. VII.1: objects 1 to 5 on the ground, seen by observer A (observer B in :data:`OBSERVER_B`).

    From A, object 5 lies outside the viewing angle, object 3 is hidden behind
    object 2, and objects 1, 2 and 4 are seen in part (1 and 4 cross the edges
    of the view).  From B, object 5 is again outside and 1 to 4 are seen in part.
    Flat colours and no lights, so each object keeps its colour.
    """
    def block(center, size, color, number):
        return shapes.box(center, size, _flat(color), f"object {number}")

    objects = (
        block((-2.7, 0.8, 2.0), (1.2, 1.6, 1.2), (0.85, 0.3, 0.3), 1),
        block((0.9, 0.9, 3.0), (1.8, 1.8, 1.0), (0.3, 0.7, 0.35), 2),
        block((0.8, 0.6, -2.0), (1.0, 1.2, 1.0), (0.3, 0.45, 0.9), 3),
        block((4.0, 0.7, 0.0), (1.4, 1.4, 1.4), (0.9, 0.75, 0.2), 4),
        block((-5.5, 0.7, 6.5), (1.2, 1.4, 1.2), (0.7, 0.35, 0.8), 5),
        shapes.quad((0.0, 0.0, 1.0), 18.0, _flat((0.75, 0.75, 0.72)), "ground"),
    )
    return Scene(camera=OBSERVER_A, objects=objects, background=(0.85, 0.88, 0.92))


def flat_cuboids_scene() -> Scene:
    """Fig. VII.12 in (nearly) two dimensions: low objects scattered on a plane, one lit.

    All objects are at most 0.5 high, so a grid of cuboids over them is one
    layer deep and reads like the lecture's 2D drawing when seen from above.
    The observer stands low at the left edge, so its rays run almost level
    across the grid's cells.
    """
    objects = (
        Sphere((-2.5, 0.25, -1.5), 0.25, Material(color=(0.85, 0.3, 0.3)), "ball 1"),
        shapes.box((-0.8, 0.2, 1.6), (1.4, 0.4, 0.6), Material(color=(0.3, 0.7, 0.35)), "slab 1"),
        Sphere((0.6, 0.3, -0.4), 0.3, Material(color=(0.3, 0.45, 0.9)), "ball 2"),
        shapes.pyramid((2.4, 0.0, 1.2), 0.9, 0.5, Material(color=(0.9, 0.75, 0.2)), "pyramid"),
        shapes.box((3.0, 0.15, -2.2), (0.8, 0.3, 1.2), Material(color=(0.7, 0.35, 0.8)), "slab 2"),
        Sphere((-1.0, 0.2, -3.0), 0.2, Material(color=(0.3, 0.75, 0.75)), "ball 3"),
    )
    camera = Camera(eye=(-6.0, 0.6, 0.5), target=(4.0, 0.1, -0.5), near=0.5, far=30.0)
    return Scene(camera=camera, objects=objects, lights=(PointLight((-3.0, 5.0, 3.0)),),
                 background=(0.85, 0.88, 0.92))


PRESETS: dict[str, tuple[str, Callable[[], Scene]]] = {
    "lecture": ("Cube and cone on a plane (the lecture's scene)", lecture_scene),
    "zbuffer_three_polygons": ("Z-buffer: three polygons drawn green, blue, yellow",
                               zbuffer_three_polygons),
    "zbuffer_piercing": ("Z-buffer: two polygons piercing each other", zbuffer_piercing),
    "zbuffer_piercing_blue_first": ("Z-buffer: the piercing polygons drawn blue first",
                                    zbuffer_piercing_blue_first),
    "culling_pyramid": ("Back-face culling: a convex pyramid", culling_pyramid),
    "culling_notched": ("Back-face culling: a non-convex notched prism", culling_notched),
    "frustum_cases": ("Frustum culling: inside, crossing, outside, behind the observer", frustum_cases),
    "transparent_panes": ("Transparency: panes in front of an opaque box", transparent_panes),
    "observers_top_view": ("Observers A and B and objects 1 to 5 (Fig. VII.1)", observers_top_view),
    "flat_cuboids": ("Low objects on a plane: the grid of cuboids in 2D (Fig. VII.12)", flat_cuboids_scene),
}
"""Preset key -> (title for a menu, builder)."""
