"""Primitive solids as triangle meshes: box, cone, pyramid, quad, uv_sphere, notched_prism.

Every builder returns a :class:`core.scene.Mesh` whose ``source`` is the
primitive's description, ``{"type": "box", "center": [...], "size": [...]}``,
so that a scene file can save it back as the primitive it came from.

The closed solids are watertight (every edge is shared by exactly two
triangles, which run along it in opposite directions) and their triangles run
counter-clockwise when seen from outside, so :attr:`core.scene.Mesh.normals`
point outwards.  Solids stand on their base: ``base_center`` is the centre of
the bottom face and the solid rises along +y.

:data:`PRIMITIVES` maps each type name to its builder and parameters; the scene
file loader (:mod:`core.files.scene_file`) reads and checks parameters with it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np

from core.scene import Material, Mesh

REQUIRED = None
"""The ``default`` of a :class:`Param` that must be given."""


@dataclass(frozen=True)
class Param:
    """One parameter of a primitive.

    Attributes
    ----------
    name : the keyword of the builder and the field of the scene file.
    kind : ``"point"`` (3 numbers), ``"size3"`` (a number or 3 numbers, each
        > 0), ``"size2"`` (a number or 2 numbers, each > 0), ``"length"``
        (a number > 0) or ``"count"`` (a whole number >= ``minimum``).
    default : value used when the parameter is left out; ``REQUIRED`` (None)
        if it must be given.
    minimum, maximum : allowed range of a ``"count"``.
    doc : what it means, with its unit.
    """

    name: str
    kind: str
    default: object = REQUIRED
    minimum: int = 0
    maximum: int = 1000
    doc: str = ""


@dataclass(frozen=True)
class Primitive:
    """A builder and the parameters it takes (besides ``material`` and ``name``)."""

    builder: Callable[..., Mesh]
    params: tuple[Param, ...]
    doc: str


def _vector(value, n: int, name: str, scalar_ok: bool) -> tuple[float, ...]:
    arr = np.asarray(value, dtype=float)
    if scalar_ok and arr.ndim == 0:
        arr = np.full(n, float(arr))
    if arr.shape != (n,):
        raise ValueError(f"{name}: expected {n} numbers, got {value!r}")
    return tuple(float(x) for x in arr)


def canonical(kind: str, value, name: str = "value"):
    """Convert a parameter value to its canonical form (tuple of floats, float or int).

    Raises ``ValueError`` if ``value`` does not have the shape of ``kind``.
    """
    if kind == "point":
        return _vector(value, 3, name, scalar_ok=False)
    if kind == "size3":
        return _vector(value, 3, name, scalar_ok=True)
    if kind == "size2":
        return _vector(value, 2, name, scalar_ok=True)
    if kind == "length":
        return float(value)
    if kind == "count":
        if int(value) != value:
            raise ValueError(f"{name}: expected a whole number, got {value!r}")
        return int(value)
    raise ValueError(f"unknown parameter kind {kind!r}")


def param_problems(type_name: str, values: dict) -> list[tuple[str, str]]:
    """Range problems of canonical parameter values, as ``(name, message)`` pairs.

    Parameters missing from ``values`` are skipped, so a caller that could not
    read some parameter still learns what is wrong with the others.
    """
    problems = []
    for p in PRIMITIVES[type_name].params:
        if p.name not in values:
            continue
        v = values[p.name]
        if p.kind == "point" and not all(np.isfinite(v)):
            problems.append((p.name, f"must be finite, got {list(v)}"))
        elif p.kind in ("size3", "size2") and not all(np.isfinite(c) and c > 0 for c in v):
            problems.append((p.name, f"every size must be > 0, got {list(v)}"))
        elif p.kind == "length" and not (np.isfinite(v) and v > 0):
            problems.append((p.name, f"must be > 0, got {v}"))
        elif p.kind == "count" and not p.minimum <= v <= p.maximum:
            problems.append((p.name, f"must be in [{p.minimum}, {p.maximum}], got {v}"))
    if type_name == "notched_prism" and {"size", "notch"} <= values.keys():
        (sx, _, sz), (nx, nz) = values["size"], values["notch"]
        if not (nx < sx and nz < sz):
            problems.append(
                ("notch", f"must be smaller than size in x and z ({sx}, {sz}), got {nx}, {nz}")
            )
    return problems


def _parameters(type_name: str, **given) -> dict:
    """Canonical, checked parameter values; raises ``ValueError`` listing what is wrong."""
    values = {}
    for p in PRIMITIVES[type_name].params:
        value = given.get(p.name, p.default)
        if value is REQUIRED:
            raise ValueError(f"{type_name}: {p.name} is required")
        values[p.name] = canonical(p.kind, value, p.name)
    problems = param_problems(type_name, values)
    if problems:
        raise ValueError(f"{type_name}: " + "; ".join(f"{n} {m}" for n, m in problems))
    return values


def _mesh(vertices, triangles, type_name, values, material, name) -> Mesh:
    source = {"type": type_name}
    source.update({k: list(v) if isinstance(v, tuple) else v for k, v in values.items()})
    return Mesh(
        vertices=vertices,
        triangles=triangles,
        material=material if material is not None else Material(),
        name=name if name is not None else type_name,
        source=source,
    )


# --- building blocks ------------------------------------------------------
# Footprints are (n, 2) arrays of (x, z) offsets, counter-clockwise seen from
# above (+y).  Seen from above with x to the right, +z points down the page.


def _ring(n: int, radius: float) -> np.ndarray:
    angles = 2.0 * np.pi * np.arange(n) / n
    return np.stack([radius * np.cos(angles), -radius * np.sin(angles)], axis=1)


def _place(poly: np.ndarray, center, y: float) -> np.ndarray:
    """Footprint offsets to world points at height ``y`` around ``center``'s x and z."""
    return np.column_stack([center[0] + poly[:, 0], np.full(len(poly), y), center[2] + poly[:, 1]])


def _fan(n: int, start: int = 0) -> np.ndarray:
    """Triangles fanning from vertex ``start`` of an n-gon, same winding as the n-gon."""
    idx = (start + np.arange(n)) % n
    return np.stack([np.full(n - 2, idx[0]), idx[1:-1], idx[2:]], axis=1)


def _prism(poly: np.ndarray, center, height: float, fan_start: int = 0):
    """A footprint extruded from ``center``'s y up by ``height``.

    ``fan_start`` must be a footprint corner that sees every other corner (any
    corner of a convex footprint, the inner corner of an L).
    """
    n = len(poly)
    y0 = center[1]
    vertices = np.vstack([_place(poly, center, y0), _place(poly, center, y0 + height)])
    cap = _fan(n, fan_start)
    i = np.arange(n)
    j = (i + 1) % n
    sides = np.vstack([np.stack([i, j, j + n], 1), np.stack([i, j + n, i + n], 1)])
    triangles = np.vstack([cap[:, ::-1], cap + n, sides])
    return vertices, triangles


def _cone(poly: np.ndarray, center, height: float, center_fan: bool):
    """A footprint joined to an apex ``height`` above ``center``; base cap fanned
    from an added centre vertex (``center_fan``) or from corner 0."""
    n = len(poly)
    apex = np.array([[center[0], center[1] + height, center[2]]])
    vertices = np.vstack([_place(poly, center, center[1]), apex])
    i = np.arange(n)
    sides = np.stack([i, (i + 1) % n, np.full(n, n)], axis=1)
    if center_fan:
        vertices = np.vstack([vertices, [center]])
        base = np.stack([np.full(n, n + 1), (i + 1) % n, i], axis=1)
    else:
        base = _fan(n)[:, ::-1]
    return vertices, np.vstack([sides, base])


def _rectangle(sx: float, sz: float) -> np.ndarray:
    hx, hz = sx / 2.0, sz / 2.0
    return np.array([[-hx, hz], [hx, hz], [hx, -hz], [-hx, -hz]])


# --- builders -------------------------------------------------------------


def box(center, size, material: Material | None = None, name: str | None = None) -> Mesh:
    """An axis-aligned box (a cube when all sizes are equal), 12 triangles.

    Parameters
    ----------
    center : (3,) the box's centre.
    size : edge lengths along x, y, z, or one number for a cube (scene units).
    material, name : of the mesh; name defaults to ``"box"``.
    """
    p = _parameters("box", center=center, size=size)
    (sx, sy, sz), c = p["size"], p["center"]
    v, t = _prism(_rectangle(sx, sz), (c[0], c[1] - sy / 2.0, c[2]), sy)
    return _mesh(v, t, "box", p, material, name)


def cone(
    base_center,
    radius,
    height,
    segments: int = 32,
    material: Material | None = None,
    name: str | None = None,
) -> Mesh:
    """A cone standing along +y, its side made of ``segments`` triangles, closed by a base disk.

    Parameters
    ----------
    base_center : (3,) centre of the base disk.
    radius, height : of the cone (scene units).
    segments : corners of the base polygon (>= 3).
    """
    p = _parameters("cone", base_center=base_center, radius=radius, height=height,
                    segments=segments)
    v, t = _cone(_ring(p["segments"], p["radius"]), p["base_center"], p["height"], True)
    return _mesh(v, t, "cone", p, material, name)


def pyramid(
    base_center, base_size, height, material: Material | None = None, name: str | None = None
) -> Mesh:
    """A pyramid on an axis-aligned square base: 4 side triangles and 2 base triangles.

    Parameters
    ----------
    base_center : (3,) centre of the square base.
    base_size : edge length of the base (scene units).
    height : of the apex above the base (scene units).
    """
    p = _parameters("pyramid", base_center=base_center, base_size=base_size, height=height)
    s = p["base_size"]
    v, t = _cone(_rectangle(s, s), p["base_center"], p["height"], False)
    return _mesh(v, t, "pyramid", p, material, name)


def quad(center, size, material: Material | None = None, name: str | None = None) -> Mesh:
    """A horizontal rectangle in the plane ``y = center.y`` (a ground plane).

    Two triangles, normal +y, single-sided and not closed.

    Parameters
    ----------
    center : (3,) centre of the rectangle.
    size : its extent along x and z, or one number for a square (scene units).
    """
    p = _parameters("quad", center=center, size=size)
    c = p["center"]
    v = _place(_rectangle(*p["size"]), c, c[1])
    return _mesh(v, _fan(4), "quad", p, material, name)


def uv_sphere(
    center,
    radius,
    rings: int = 16,
    segments: int = 32,
    material: Material | None = None,
    name: str | None = None,
) -> Mesh:
    """A tessellated sphere: ``rings`` bands of latitude, ``segments`` of longitude.

    Unlike :class:`core.scene.Sphere` this is an ordinary triangle mesh
    (``2 * segments * (rings - 1)`` triangles), so its volume approaches the
    sphere's from below as ``rings`` and ``segments`` grow.

    Parameters
    ----------
    center : (3,) centre.
    radius : scene units.
    rings : bands between the poles (>= 2).
    segments : corners of each circle of latitude (>= 3).
    """
    p = _parameters("uv_sphere", center=center, radius=radius, rings=rings, segments=segments)
    c, r, nr, ns = np.array(p["center"]), p["radius"], p["rings"], p["segments"]
    phi = np.pi * np.arange(1, nr) / nr
    circles = [_place(_ring(ns, r * np.sin(f)), c, c[1] + r * np.cos(f)) for f in phi]
    top, bottom = c + [0.0, r, 0.0], c - [0.0, r, 0.0]
    vertices = np.vstack([top, *circles, bottom])
    i = np.arange(ns)
    j = (i + 1) % ns
    tris = [np.stack([np.zeros(ns, int), 1 + i, 1 + j], 1)]
    for k in range(nr - 2):
        a, b = 1 + k * ns, 1 + (k + 1) * ns  # upper and lower circle
        tris += [np.stack([b + i, b + j, a + j], 1), np.stack([b + i, a + j, a + i], 1)]
    last, s = 1 + (nr - 2) * ns, len(vertices) - 1
    tris.append(np.stack([np.full(ns, s), last + j, last + i], 1))
    return _mesh(vertices, np.vstack(tris), "uv_sphere", p, material, name)


def notched_prism(
    base_center, size, notch, material: Material | None = None, name: str | None = None
) -> Mesh:
    """A non-convex solid: a box with a full-height notch cut from one vertical edge.

    Its footprint is an L: the rectangle ``size[0] x size[2]`` minus the
    ``notch[0] x notch[1]`` rectangle at its (-x, +z) corner, extruded up by
    ``size[1]``.  The inner wall facing +z is front-facing for an observer
    in front and to the right (like the default camera), yet the L's other arm
    hides part of it: the lecture's case where back-face culling alone is not
    enough (Fig. VII.4b).

    Parameters
    ----------
    base_center : (3,) centre of the bounding box's bottom face.
    size : bounding box edge lengths along x, y, z (scene units).
    notch : extent of the cut-out along x and z, each smaller than ``size``'s.
    """
    p = _parameters("notched_prism", base_center=base_center, size=size, notch=notch)
    (sx, sy, sz), (nx, nz) = p["size"], p["notch"]
    x0, x1, z0, z1 = -sx / 2.0, sx / 2.0, -sz / 2.0, sz / 2.0
    xn, zn = x0 + nx, z1 - nz  # the inner (reflex) corner, fanned from
    footprint = np.array([[xn, zn], [xn, z1], [x1, z1], [x1, z0], [x0, z0], [x0, zn]])
    v, t = _prism(footprint, p["base_center"], sy, fan_start=0)
    return _mesh(v, t, "notched_prism", p, material, name)


PRIMITIVES: dict[str, Primitive] = {
    "box": Primitive(box, (
        Param("center", "point", doc="centre of the box"),
        Param("size", "size3", doc="edge lengths along x, y, z; one number for a cube"),
    ), "axis-aligned box (cube when all sizes are equal)"),
    "cone": Primitive(cone, (
        Param("base_center", "point", doc="centre of the base disk"),
        Param("radius", "length", doc="radius of the base"),
        Param("height", "length", doc="height of the apex above the base"),
        Param("segments", "count", 32, 3, doc="corners of the base polygon"),
    ), "cone standing along +y, closed by its base disk"),
    "pyramid": Primitive(pyramid, (
        Param("base_center", "point", doc="centre of the square base"),
        Param("base_size", "length", doc="edge length of the square base"),
        Param("height", "length", doc="height of the apex above the base"),
    ), "pyramid on a square base, apex up"),
    "quad": Primitive(quad, (
        Param("center", "point", doc="centre; the quad lies in the plane y = center[1]"),
        Param("size", "size2", doc="extent along x and z; one number for a square"),
    ), "horizontal rectangle facing +y (a ground plane), single-sided"),
    "uv_sphere": Primitive(uv_sphere, (
        Param("center", "point", doc="centre"),
        Param("radius", "length", doc="radius"),
        Param("rings", "count", 16, 2, doc="bands of latitude between the poles"),
        Param("segments", "count", 32, 3, doc="corners of each circle of latitude"),
    ), "tessellated sphere (a triangle mesh, unlike the analytic sphere)"),
    "notched_prism": Primitive(notched_prism, (
        Param("base_center", "point", doc="centre of the bounding box's bottom face"),
        Param("size", "size3", doc="bounding box edge lengths along x, y, z"),
        Param("notch", "size2",
              doc="extent along x and z of the full-height cut at the (-x, +z) corner"),
    ), "L-shaped (non-convex) prism for the back-face culling lesson"),
}
"""Primitive type name -> builder and its parameters."""
