"""Ready-made scenes.

:func:`lecture_scene` is the scene of the lecture's second question: "a cube
and a cone placed on an opaque plane, wherein the cone partially obscures the
cube from the observer's point of view".
"""

from __future__ import annotations

from core import shapes
from core.camera import Camera
from core.scene import Material, PointLight, Scene

CUBE_CENTER = (-1.7, 0.8, -1.1)
CUBE_SIZE = 1.6
CONE_BASE = (0.6, 0.0, 1.0)
CONE_RADIUS = 1.0
CONE_HEIGHT = 2.2


def lecture_scene() -> Scene:
    """A cube and a cone on an opaque ground plane; the cone partly hides the cube.

    Seen from the default :class:`~core.camera.Camera` (eye ``(6, 4, 9)``
    looking at ``(0, 0.8, 0)``) the cube stands behind the cone, shifted to the
    left, so part of the cube is hidden by the cone and part of it is seen.
    The ground is a 14 x 14 quad at ``y = 0``; one point light shines from
    above, in front of the objects.
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
        lights=(PointLight((4.0, 8.0, 6.0)),),
    )
