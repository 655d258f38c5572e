"""The scene flattened into arrays for the compiled tracer, built once and reused.

Ray tracing tests rays against *primitives*: analytic spheres and triangles.
:func:`trace_scene` lays them out as the kernels want them
(:class:`Geometry`) together with the materials (:class:`TraceScene`).

Primitive numbering: the analytic spheres first, in object order, then the
triangles of every mesh, mesh after mesh in object order.  Each primitive is
one row of nine numbers (see :mod:`core.image_order.kernels.primitives`).

Caching: moving the observer or changing a light or a material must not
rebuild the acceleration structures.  Geometry is therefore cached by its
*content* (a hash of every sphere and mesh, in order), with a fast path when
``scene.objects`` is the very tuple seen last time; acceleration structures
are built on first use per method and kept with the geometry.
"""

from __future__ import annotations

import hashlib
import threading
import time
from collections import OrderedDict
from dataclasses import dataclass, field

import numpy as np

from core.image_order import flat_layout
from core.image_order.bounding_spheres import PAD, bounding_sphere
from core.image_order.bvh import Bvh, build_bvh
from core.image_order.bvh import empty_kernel_tuple as no_bvh
from core.image_order.effects_plan import MODES, EffectsPlan
from core.image_order.grid_of_cuboids import UniformGrid, build_grid
from core.image_order.grid_of_cuboids import empty_kernel_tuple as no_grid
from core.image_order.ray_casting import camera_array
from core.scene import Scene, Sphere

#: How many distinct geometries stay cached.
CACHE_SIZE = 4


@dataclass(eq=False)
class Geometry:
    """Every primitive of a scene, flattened (world space, scene units).

    Attributes
    ----------
    key : bytes, hash of the geometry's content.
    n_spheres : int, primitives ``0 .. n_spheres - 1`` are analytic spheres.
    rows : (P, 9) float64, one row per primitive (sphere ``cx, cy, cz, r``, or
        triangle corners ``A, B, C``).
    prim_object : (P,) int64, the scene object each primitive belongs to.
    object_prims : (O, 2) int64, first primitive and number of primitives of
        every object (a mesh's triangles are consecutive).
    object_is_sphere : (O,) bool, the object is an analytic sphere.
    bounding : (O, 4) float64, padded bounding sphere of every object
        (:mod:`core.image_order.bounding_spheres`).
    normals : (T, 3) float64, outward unit normal of triangle ``p - n_spheres``.
    magnitude : (P,) float64, largest coordinate magnitude of each primitive
        (the corners; a sphere's ``max |c| + r``), for the ray offset.
    lo, hi : (P, 3) float64, padded bounding box of each primitive.
    """

    key: bytes
    n_spheres: int
    rows: np.ndarray
    prim_object: np.ndarray
    object_prims: np.ndarray
    object_is_sphere: np.ndarray
    bounding: np.ndarray
    normals: np.ndarray
    magnitude: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    _accel: dict = field(default_factory=dict, repr=False)
    _lock: threading.Lock = field(default_factory=threading.Lock, repr=False)

    @property
    def n_prims(self) -> int:
        return self.rows.shape[0]

    def kernel_tuple(self) -> tuple:
        """The arrays the kernels read, at the positions ``GEO_*`` of :mod:`.flat_layout`."""
        return (self.rows, self.n_spheres, self.prim_object, self.object_prims,
                self.bounding, self.normals, self.magnitude)

    def accel(self, method: str):
        """The acceleration structure for ``method``, built on first use.

        Returns
        -------
        (structure, build_seconds, cached)
            ``structure`` is a :class:`core.image_order.grid_of_cuboids.UniformGrid` for the grid
            methods, a :class:`core.image_order.bvh.Bvh` for ``"bvh"`` and ``None`` otherwise;
            ``cached`` tells whether it already existed.
        """
        kind = {"grid": "grid", "grid+spheres": "grid", "bvh": "bvh"}.get(method)
        if method not in flat_layout.ACCEL_CODES:
            raise ValueError(f"unknown acceleration method {method!r}, "
                             f"expected one of {flat_layout.ACCEL_CODES}")
        if kind is None:
            return None, 0.0, True
        with self._lock:
            if kind in self._accel:
                structure, seconds = self._accel[kind]
                return structure, seconds, True
            start = time.perf_counter()
            structure = build_grid(self) if kind == "grid" else build_bvh(self)
            seconds = time.perf_counter() - start
            self._accel[kind] = (structure, seconds)
            return structure, seconds, False


@dataclass(frozen=True, eq=False)
class TraceScene:
    """A scene ready for the tracer: its geometry, materials and names.

    Attributes
    ----------
    geometry : Geometry, shared by every scene with the same objects' shapes.
    materials : (O, MAT_SIZE) float64, see :mod:`core.image_order.flat_layout`.
    names : tuple of str, the objects' names.
    """

    geometry: Geometry
    materials: np.ndarray
    names: tuple[str, ...]


_cache: OrderedDict[bytes, Geometry] = OrderedDict()
_last: list = [None, None]  # (objects tuple, TraceScene) of the last call
_cache_lock = threading.Lock()


def trace_scene(scene: Scene) -> TraceScene:
    """The flattened form of ``scene``, reusing cached geometry whenever possible."""
    objects = scene.objects
    with _cache_lock:
        if _last[0] is objects:
            return _last[1]
        key = geometry_key(objects)
        geometry = _cache.get(key)
        if geometry is None:
            geometry = _flatten(objects, key)
            _cache[key] = geometry
            while len(_cache) > CACHE_SIZE:
                _cache.popitem(last=False)
        _cache.move_to_end(key)
        result = TraceScene(geometry, _materials(objects), tuple(o.name for o in objects))
        _last[0], _last[1] = objects, result
        return result


def geometry_key(objects) -> bytes:
    """Hash of the shapes of ``objects`` (not their materials or names)."""
    h = hashlib.blake2b(digest_size=16)
    for obj in objects:
        if isinstance(obj, Sphere):
            h.update(b"S" + np.array([*obj.center, obj.radius], dtype=np.float64).tobytes())
        else:
            h.update(b"M" + np.int64(len(obj.vertices)).tobytes() + obj.vertices.tobytes())
            h.update(obj.triangles.tobytes())
    return h.digest()


def _materials(objects) -> np.ndarray:
    table = np.zeros((len(objects), flat_layout.MAT_SIZE))
    for i, obj in enumerate(objects):
        m = obj.material
        table[i, flat_layout.MAT_COLOR:flat_layout.MAT_COLOR + 3] = m.color
        table[i, flat_layout.MAT_REFLECTIVITY] = m.reflectivity
        table[i, flat_layout.MAT_TRANSPARENCY] = m.transparency
        table[i, flat_layout.MAT_IOR] = m.ior
        table[i, flat_layout.MAT_AMBIENT] = m.ambient
        table[i, flat_layout.MAT_DIFFUSE] = m.diffuse
        table[i, flat_layout.MAT_SPECULAR] = m.specular
        table[i, flat_layout.MAT_SHININESS] = m.shininess
    return table


def _flatten(objects, key: bytes) -> Geometry:
    spheres = [(i, o) for i, o in enumerate(objects) if isinstance(o, Sphere)]
    meshes = [(i, o) for i, o in enumerate(objects) if not isinstance(o, Sphere)]
    n_spheres = len(spheres)
    sphere_rows = np.zeros((n_spheres, flat_layout.ROW_SIZE))
    for k, (_, s) in enumerate(spheres):
        sphere_rows[k, flat_layout.ROW_CENTER:flat_layout.ROW_CENTER + 3] = s.center
        sphere_rows[k, flat_layout.ROW_RADIUS] = s.radius
    tri_rows = [m.corners.reshape(-1, flat_layout.ROW_SIZE) for _, m in meshes]  # corners A, B, C
    rows = np.ascontiguousarray(np.vstack([sphere_rows, *tri_rows]))
    counts = [len(t) for t in tri_rows]
    prim_object = np.concatenate(
        [np.array([i for i, _ in spheres], dtype=np.int64)]
        + [np.full(c, i, dtype=np.int64) for (i, _), c in zip(meshes, counts, strict=True)]
    )
    object_prims = np.zeros((len(objects), 2), dtype=np.int64)
    for k, (i, _) in enumerate(spheres):
        object_prims[i] = (k, 1)
    first = n_spheres
    for (i, _), c in zip(meshes, counts, strict=True):
        object_prims[i] = (first, c)
        first += c
    bounding = np.zeros((len(objects), 4))
    for i, obj in enumerate(objects):
        center, radius = bounding_sphere(obj)
        bounding[i, :3], bounding[i, 3] = center, radius

    corners = rows[n_spheres:].reshape(-1, 3, 3)
    centers = sphere_rows[:, flat_layout.ROW_CENTER:flat_layout.ROW_CENTER + 3]
    radii = sphere_rows[:, flat_layout.ROW_RADIUS:flat_layout.ROW_RADIUS + 1]
    magnitude = np.concatenate([np.abs(centers).max(axis=1, initial=0.0) + radii[:, 0],
                                np.abs(corners).max(axis=(1, 2), initial=0.0)])
    lo = np.vstack([centers - radii, corners.min(axis=1)])
    hi = np.vstack([centers + radii, corners.max(axis=1)])
    pad = PAD * magnitude[:, None]
    normals = (np.vstack([m.normals for _, m in meshes]) if meshes else np.zeros((0, 3)))
    return Geometry(
        key=key,
        n_spheres=n_spheres,
        rows=rows,
        prim_object=prim_object,
        object_prims=object_prims,
        object_is_sphere=np.array([isinstance(o, Sphere) for o in objects], dtype=bool),
        bounding=bounding,
        normals=np.ascontiguousarray(normals),
        magnitude=magnitude,
        lo=lo - pad,
        hi=hi + pad,
    )


OFFSETS = ("scaled", "fixed")


@dataclass(frozen=True)
class TraceSettings:
    """How to render in image order.

    Attributes
    ----------
    mode : ``"raycast"`` (first hits and shadow rays) or ``"raytrace"`` (Whitted).
    max_depth : int >= 0, deepest generation of reflected/refracted rays.
    min_weight : float >= 0, rays whose weight in the pixel is below this are not traced.
    accel : one of ``"none"``, ``"spheres"``, ``"grid"``, ``"grid+spheres"``, ``"bvh"``.
    offset : ``"scaled"`` (pbrt-style origin offset, robust at any scale) or
        ``"fixed"`` (ignore crossings closer than ``epsilon``), see :mod:`core.image_order.ray_offset`.
    epsilon : float >= 0, scene units, used when ``offset == "fixed"``.
    """

    mode: str = "raytrace"
    max_depth: int = 5
    min_weight: float = 0.01
    accel: str = "bvh"
    offset: str = "scaled"
    epsilon: float = 1e-4

    def __post_init__(self):
        problems = []
        if self.mode not in MODES:
            problems.append(f"mode must be one of {list(MODES)}, got {self.mode!r}")
        if self.accel not in flat_layout.ACCEL_CODES:
            problems.append(f"accel must be one of {list(flat_layout.ACCEL_CODES)}, got {self.accel!r}")
        if self.offset not in OFFSETS:
            problems.append(f"offset must be one of {list(OFFSETS)}, got {self.offset!r}")
        if not (isinstance(self.max_depth, int) and 0 <= self.max_depth <= 64):
            problems.append(f"max_depth must be a whole number in [0, 64], got {self.max_depth!r}")
        if not self.min_weight >= 0:
            problems.append(f"min_weight must be >= 0, got {self.min_weight!r}")
        if not self.epsilon >= 0:
            problems.append(f"epsilon must be >= 0, got {self.epsilon!r}")
        if problems:
            raise ValueError("; ".join(problems))


@dataclass(frozen=True, eq=False)
class KernelInputs:
    """Everything the compiled passes read, as arrays (see :mod:`.flat_layout`)."""

    cam: np.ndarray
    opts: np.ndarray
    lights: np.ndarray
    materials: np.ndarray
    geo: tuple
    grid: tuple
    bvh: tuple
    bvh_depth: int
    method: int


def kernel_inputs(scene: Scene, settings: TraceSettings, plan: EffectsPlan, flat, structure) -> KernelInputs:
    """Lay out camera, settings, lights and structures for the kernels."""
    opts = np.zeros(flat_layout.OPT_SIZE)
    opts[flat_layout.OPT_ACCEL] = flat_layout.ACCEL_CODES.index(settings.accel)
    opts[flat_layout.OPT_MAX_DEPTH] = settings.max_depth
    opts[flat_layout.OPT_MIN_WEIGHT] = settings.min_weight
    opts[flat_layout.OPT_SCALED_OFFSET] = settings.offset == "scaled"
    opts[flat_layout.OPT_EPSILON] = settings.epsilon
    opts[flat_layout.OPT_REFLECTION] = plan.reflection_rays
    opts[flat_layout.OPT_REFRACTION] = plan.refraction_rays
    opts[flat_layout.OPT_BACKGROUND:flat_layout.OPT_BACKGROUND + 3] = scene.background
    opts[flat_layout.OPT_PACKETS] = isinstance(structure, Bvh) and structure.packets_pay(scene.camera)
    width = flat_layout.LIGHT_SIZE + len(scene.objects) * flat_layout.RECEIVER_SIZE
    lights = np.zeros((len(scene.lights), width))
    for i, (light, lp) in enumerate(zip(scene.lights, plan.lights, strict=True)):
        lights[i, flat_layout.LIGHT_POSITION:flat_layout.LIGHT_POSITION + 3] = light.position
        lights[i, flat_layout.LIGHT_RGB:flat_layout.LIGHT_RGB + 3] = np.multiply(light.color, light.intensity)
        lights[i, flat_layout.LIGHT_BLOCKABLE] = lp.blockable
        for receiver in range(len(scene.objects)):
            at = flat_layout.LIGHT_SIZE + receiver * flat_layout.RECEIVER_SIZE
            blockers = None if lp.blockers is None else lp.blockers[receiver]
            if blockers is None or len(blockers) >= flat_layout.RECEIVER_SIZE:
                lights[i, at] = flat_layout.BLOCKERS_UNKNOWN
            else:
                lights[i, at] = len(blockers)
                lights[i, at + 1:at + 1 + len(blockers)] = blockers
    grid = structure.kernel_tuple() if isinstance(structure, UniformGrid) else no_grid()
    bvh = structure.kernel_tuple() if isinstance(structure, Bvh) else no_bvh()
    depth = structure.depth if isinstance(structure, Bvh) else 0
    return KernelInputs(camera_array(scene.camera), opts, lights, flat.materials,
                        flat.geometry.kernel_tuple(), grid, bvh, depth, int(opts[flat_layout.OPT_ACCEL]))

