"""Bounding spheres: the lecture's cheap stand-in tested before a complex object.

"The complex objects present in the scene are surrounded by solids for which
it is easy to find the crossing point with a ray ... only if the ray crosses
the sphere do we proceed to the time consuming procedure of finding crossing
points with the object."

Every mesh gets the sphere of :meth:`core.scene.Mesh.bounding_sphere` (centred
on its bounding box), padded by a relative ``PAD`` so that rounding in the
ray-sphere test can never miss a triangle that touches the sphere.  An
analytic sphere is its own bounding sphere.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.scene import Scene, Sphere

#: Relative padding of bounding volumes (about 1e-9): far below anything visible, far
#: above the rounding error of the tests.
PAD = 2.0**-30


@dataclass(frozen=True)
class BoundingSphere:
    """The bounding sphere of one scene object.

    Attributes
    ----------
    object_index : int, index into ``scene.objects``.
    name : str, the object's name.
    center : (3,) float64, world space.
    radius : float, scene units.
    exact : bool, the object *is* this sphere (an analytic sphere).
    """

    object_index: int
    name: str
    center: np.ndarray
    radius: float
    exact: bool


def bounding_sphere(obj) -> tuple[np.ndarray, float]:
    """Centre (3,) and radius of the sphere around one scene object: exact for an analytic
    sphere, padded for a mesh."""
    center, radius = obj.bounding_sphere()
    if isinstance(obj, Sphere):
        return center, radius
    return center, radius * (1.0 + PAD) + PAD * float(np.abs(center).max())


def bounding_spheres(scene: Scene) -> tuple[BoundingSphere, ...]:
    """The bounding sphere of every object of ``scene``, in object order."""
    result = []
    for index, obj in enumerate(scene.objects):
        center, radius = bounding_sphere(obj)
        result.append(BoundingSphere(index, obj.name, center, radius, isinstance(obj, Sphere)))
    return tuple(result)
