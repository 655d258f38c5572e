"""The scene: objects with materials, point lights, the observer and a background.

Everything here is an immutable value.  Colours are linear RGB triples in
``[0, 1]``; positions are world-space scene units (see :mod:`core.projection`).
"""

from __future__ import annotations

from dataclasses import dataclass, field
from functools import cached_property

import numpy as np

from core.camera import Camera

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class Material:
    """How a surface looks and what light does at it.

    Attributes
    ----------
    color : surface colour, RGB in [0, 1].
    opacity : the lecture's transparency coefficient alpha_s in [0, 1] for
        object-order blending ``c0 = alpha_s cs + (1 - alpha_s) cd``; 1 is opaque.
    reflectivity : fraction of light mirrored, [0, 1]; 0 means no reflection rays.
    transparency : fraction of light transmitted by refraction, [0, 1];
        0 means no refraction rays.
    ior : index of refraction (>= 1) of a transparent material.
    ambient, diffuse, specular : Phong coefficients k_a, k_d, k_s in [0, 1].
    shininess : Phong exponent n (> 0).
    """

    color: Vec3 = (0.8, 0.8, 0.8)
    opacity: float = 1.0
    reflectivity: float = 0.0
    transparency: float = 0.0
    ior: float = 1.5
    ambient: float = 0.1
    diffuse: float = 0.8
    specular: float = 0.2
    shininess: float = 32.0


@dataclass(frozen=True)
class Sphere:
    """A true sphere (no tessellation): ``|x - center| = radius``."""

    center: Vec3
    radius: float
    material: Material = field(default_factory=Material)
    name: str = "sphere"

    def bounding_sphere(self) -> tuple[np.ndarray, float]:
        """Centre (3,) and radius: the sphere is its own bounding sphere."""
        return np.asarray(self.center, dtype=float), float(self.radius)


@dataclass(frozen=True, eq=False)
class Mesh:
    """A triangle mesh with outward normals from counter-clockwise winding.

    Attributes
    ----------
    vertices : (N, 3) float64, world space.
    triangles : (M, 3) int64 indices into ``vertices``; each triangle's corners
        run counter-clockwise when seen from outside.
    material, name : as for :class:`Sphere`.
    source : how the scene file described it, kept so that saving writes it back
        the same way: ``{"type": "box", ...}`` for a primitive,
        ``{"type": "mesh_file", "path": ...}`` for a file, ``None`` for inline.
    """

    vertices: np.ndarray
    triangles: np.ndarray
    material: Material = field(default_factory=Material)
    name: str = "mesh"
    source: dict | None = None

    def __post_init__(self):
        v = np.ascontiguousarray(self.vertices, dtype=np.float64).reshape(-1, 3)
        t = np.ascontiguousarray(self.triangles, dtype=np.int64).reshape(-1, 3)
        v.flags.writeable = False
        t.flags.writeable = False
        object.__setattr__(self, "vertices", v)
        object.__setattr__(self, "triangles", t)

    def __eq__(self, other):
        if not isinstance(other, Mesh):
            return NotImplemented
        return (
            self.name == other.name
            and self.material == other.material
            and self.source == other.source
            and np.array_equal(self.vertices, other.vertices)
            and np.array_equal(self.triangles, other.triangles)
        )

    __hash__ = None

    @property
    def corners(self) -> np.ndarray:
        """(M, 3, 3): the three corner positions of every triangle."""
        return self.vertices[self.triangles]

    @property
    def normals(self) -> np.ndarray:
        """(M, 3) outward unit face normals, ``(B - A) x (C - A)`` normalised."""
        c = self.corners
        n = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
        return n / np.linalg.norm(n, axis=1, keepdims=True)

    def bounding_sphere(self) -> tuple[np.ndarray, float]:
        """Centre (3,) and radius of a sphere around all vertices (:func:`bounding_sphere_of`).

        Found once per mesh (the vertices never change): a million-triangle mesh's
        takes tens of milliseconds, and every frame's frustum culling asks for it.
        The centre is read-only.
        """
        return self._bounding_sphere

    @cached_property
    def _bounding_sphere(self) -> tuple[np.ndarray, float]:
        center, radius = bounding_sphere_of(self.vertices)
        center.flags.writeable = False
        return center, radius


@dataclass(frozen=True)
class PointLight:
    """A point light: position (world space), RGB colour, intensity (>= 0), and a name to list it by."""

    position: Vec3
    color: Vec3 = (1.0, 1.0, 1.0)
    intensity: float = 1.0
    name: str = "light"


SceneObject = Sphere | Mesh


@dataclass(frozen=True)
class Scene:
    """The observer, the lights, the objects and the background colour."""

    camera: Camera = field(default_factory=Camera)
    objects: tuple[SceneObject, ...] = ()
    lights: tuple[PointLight, ...] = ()
    background: Vec3 = (0.05, 0.07, 0.12)


def bounding_sphere_of(points: np.ndarray) -> tuple[np.ndarray, float]:
    """A sphere around points: centred on their bounding box, out to the farthest one.

    The one bounding-sphere formula of the app (:meth:`Mesh.bounding_sphere`; an analytic
    :class:`Sphere` is its own): object-order culling tests it against the frustum,
    image order tests rays against it before the object.

    Parameters
    ----------
    points : (N, 3) float64, N >= 1.

    Returns
    -------
    center : (3,) float64 and radius : float, in the points' frame and units.

    Examples
    --------
    >>> c, r = bounding_sphere_of(np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]]))
    >>> c.tolist(), r
    ([1.0, 0.5, 0.0], 1.118033988749895)
    """
    coords = np.ascontiguousarray(np.asarray(points, dtype=float).T)  # (3, N): fast reductions
    center = (coords.min(axis=1) + coords.max(axis=1)) / 2.0
    offset = coords - center[:, None]
    return center, float(np.sqrt((offset * offset).sum(axis=0).max()))
