"""Scene files: a :class:`core.scene.Scene` as JSON, checked field by field.

A scene file is a JSON object::

    {"format": "render-explorer-scene", "version": 1,
     "camera": {...}, "background": [r, g, b], "lights": [...], "objects": [...]}

Every field has a default except the few that must be given (a sphere's
centre and radius, a mesh's vertices, ...).  Loading checks everything and
reports *every* problem at once, each with the path of its field
(``objects[2].radius: must be > 0, got -1``), as one :class:`SceneFileError`;
the file is read and its values checked with :mod:`core.files.checked_json`.
The README's "Scene files" section documents the schema.

Limits keep a small file from making a huge scene: at most
:data:`MAX_OBJECTS` objects, :data:`MAX_LIGHTS` lights and
:data:`MAX_TRIANGLES` triangles in all (counted from a primitive's parameters
*before* it is built), JSON nested at most :data:`MAX_NESTING` deep, and a
file of at most :data:`MAX_FILE_BYTES`.  Only a regular file is read (never a
FIFO or a device, see :mod:`core.files.safe_files`), and :func:`save` writes
atomically: a failed save leaves the old file as it was.

``core`` does not read mesh files (OBJ, STL, PLY) itself: the application
passes a ``read_mesh(path) -> (vertices, triangles)`` callable, e.g.
:func:`core.files.mesh_files.read_mesh`.
"""

from __future__ import annotations

import json
import os
from collections.abc import Callable
from dataclasses import fields
from pathlib import Path, PurePath

import numpy as np

from core import shapes
from core.camera import PROJECTIONS, Camera, camera_problems
from core.files import safe_files
from core.files.checked_json import (
    MAX_LISTED,
    MAX_MAGNITUDE,
    SCENE_FORMAT,
    CheckedFileError,
    Reader,
    finite,
    is_integer,
    is_number,
    join,
    nesting_depth,
    other_kind,
    read_json,
    show,
    too_big,
)
from core.scene import Material, Mesh, PointLight, Scene, Sphere

FORMAT = SCENE_FORMAT
VERSION = 1
OBJECT_TYPES = ("sphere", *shapes.PRIMITIVES, "mesh", "mesh_file")
MAX_IMAGE_SIZE = 16384
MAX_OBJECTS = 1000
MAX_LIGHTS = 100
MAX_TRIANGLES = 2_000_000  # of the whole scene: primitives, inline meshes and mesh files
MAX_NESTING = 32  # levels of JSON arrays and objects; a scene needs 5
MAX_FILE_BYTES = 100_000_000
DEGENERATE_BLOCK = 100_000  # triangles checked for zero area at a time

MeshReader = Callable[[str], tuple[np.ndarray, np.ndarray]]

_MATERIAL_UNIT = ("opacity", "reflectivity", "transparency", "ambient", "diffuse", "specular")
_COMMON = ("type", "name", "material")
_TYPE_FIELDS = {
    "sphere": ("center", "radius"),
    "mesh": ("vertices", "triangles"),
    "mesh_file": ("path",),
    **{t: tuple(p.name for p in prim.params) for t, prim in shapes.PRIMITIVES.items()},
}


class SceneFileError(CheckedFileError):
    """A scene file (or dict) that cannot be loaded; see :class:`core.files.checked_json.CheckedFileError`."""

    thing = "scene"


class _Reader(Reader):
    """A :class:`core.files.checked_json.Reader` that also counts the scene's triangles."""

    def __init__(self):
        super().__init__()
        self.triangles = 0  # so far, of the objects read

    def count_triangles(self, path: str, n: int, what: str) -> bool:
        """Add ``n`` triangles to the scene's total; False (and a problem) if over the limit."""
        if self.triangles + n > MAX_TRIANGLES:
            if self.triangles <= MAX_TRIANGLES:  # reported once, at the first object past it
                self.add(path, f"{what} has {n:,} triangles, which takes the scene past its "
                               f"limit of {MAX_TRIANGLES:,} ({self.triangles:,} before it)")
            self.triangles = MAX_TRIANGLES + 1
            return False
        self.triangles += n
        return True


# --- the parts of a scene ----------------------------------------------------


def read_camera(r: Reader, value, path="camera") -> Camera:
    """The ``camera`` object at ``path``: every field checked, problems in ``r``; defaults for the rest."""
    known = [f.name for f in fields(Camera)]
    d = r.fields(value, path, known) or {}
    values, bad = {}, set()
    for key, v in d.items():
        p = join(path, key)
        if key in ("eye", "target", "up"):
            got = r.vector(v, p)
        elif key in ("fov_y_deg", "near", "far", "ortho_height"):
            got = r.number(v, p)
        elif key == "projection":
            got = r.string(v, p)
            if got is not None and got not in PROJECTIONS:
                r.add(p, f"must be one of {', '.join(PROJECTIONS)}, got {show(v)}")
                got = None
        elif key in ("width", "height"):
            got = r.integer(v, p)
            if got is not None and got > MAX_IMAGE_SIZE:
                r.add(p, f"must be <= {MAX_IMAGE_SIZE} pixels, got {show(got)}")
                got = None
        else:
            continue  # unknown, already reported
        if got is None:
            bad.add(key)
        else:
            values[key] = got
    camera = Camera(**values)
    involves = {"target": {"eye", "target"}, "up": {"eye", "target", "up"}, "far": {"near", "far"}}
    for key, message in camera_problems(camera):
        if not involves.get(key, {key}) & bad:
            r.add(join(path, key), message)
    return camera


def _read_light(r: _Reader, value, path) -> PointLight | None:
    d = r.fields(value, path, ["position", "color", "intensity", "name"], ["position"])
    if d is None:
        return None
    values = {
        "name": r.string(d["name"], f"{path}.name") if "name" in d else "light",
        "position": r.vector(d["position"], f"{path}.position") if "position" in d else None,
        "color": r.color(d["color"], f"{path}.color") if "color" in d else (1.0, 1.0, 1.0),
        "intensity": r.number(d["intensity"], f"{path}.intensity", ge=0)
        if "intensity" in d
        else 1.0,
    }
    if any(v is None for v in values.values()):
        return None
    return PointLight(**values)


def _read_material(r: _Reader, value, path) -> Material:
    known = [f.name for f in fields(Material)]
    d = r.fields(value, path, known) or {}
    values = {}
    for key, v in d.items():
        p = join(path, key)
        if key == "color":
            got = r.color(v, p)
        elif key in _MATERIAL_UNIT:
            got = r.number(v, p, ge=0, le=1)
        elif key == "ior":
            got = r.number(v, p, ge=1)
        elif key == "shininess":
            got = r.number(v, p, gt=0)
        else:
            continue
        if got is not None:
            values[key] = got
    return Material(**values)


def degenerate(vertices: np.ndarray, triangles: np.ndarray) -> np.ndarray:
    """(M,) bool: triangles of (nearly) zero area, whose normal is undefined.

    A triangle is degenerate when twice its area is at most ``1e-12`` times the
    product of two of its edge lengths (its corners are collinear or repeated).
    Computed :data:`DEGENERATE_BLOCK` triangles at a time, so that a large mesh
    needs little memory beyond its own.
    """
    out = np.empty(len(triangles), dtype=bool)
    for first in range(0, len(triangles), DEGENERATE_BLOCK):
        c = vertices[triangles[first:first + DEGENERATE_BLOCK]]
        e1, e2 = c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]
        area2 = np.linalg.norm(np.cross(e1, e2), axis=1)
        scale = np.linalg.norm(e1, axis=1) * np.linalg.norm(e2, axis=1)
        out[first:first + len(c)] = ~(area2 > 1e-12 * scale)
    return out


def _triangle_problems(vertices: np.ndarray, triangles: np.ndarray) -> list[tuple[int, str]]:
    """Triangles with indices out of range or of zero area, as ``(index, message)``."""
    n = len(vertices)
    out_of_range = ((triangles < 0) | (triangles >= n)).any(axis=1)
    problems = [
        (int(k), f"vertex index out of range in {triangles[k].tolist()}: "
                 f"there are {n} vertices, indices 0 to {n - 1}")
        for k in np.flatnonzero(out_of_range)
    ]
    ok = np.flatnonzero(~out_of_range)
    for k in ok[degenerate(vertices, triangles[ok])]:
        problems.append((int(k), f"degenerate triangle (zero area): {triangles[k].tolist()}"))
    return sorted(problems)


def _read_inline_mesh(r: _Reader, d: dict, path: str):
    """Vertices and triangles given in the file, or None."""
    vs = r.listing(d["vertices"], f"{path}.vertices") if "vertices" in d else []
    ts = r.listing(d["triangles"], f"{path}.triangles") if "triangles" in d else []
    bad_v = []
    for k, v in enumerate(vs):
        if not (isinstance(v, list) and len(v) == 3 and all(is_number(c) for c in v)):
            bad_v.append((k, f"expected 3 numbers, got {show(v)}"))
        elif not all(finite(c) for c in v):
            bad_v.append((k, f"expected 3 finite numbers, got {show(v)}"))
        elif too_big(v):
            bad_v.append((k, f"numbers must be within ±{MAX_MAGNITUDE:,.0f}, got {show(v)}"))
    r.capped(f"{path}.vertices", bad_v)
    if isinstance(d.get("vertices"), list) and len(vs) < 3:
        r.add(f"{path}.vertices", f"a mesh needs at least 3 vertices, got {len(vs)}")
    bad_t, good_t = [], []
    for k, t in enumerate(ts):
        if not (isinstance(t, list) and len(t) == 3 and all(is_integer(i) for i in t)):
            bad_t.append((k, f"expected 3 whole-number vertex indices, got {show(t)}"))
        elif len(vs) < 3:
            continue  # the vertices are the problem
        elif not all(0 <= i < len(vs) for i in t):
            bad_t.append((k, f"vertex index out of range in {show(t)}: there are "
                             f"{len(vs)} vertices, indices 0 to {len(vs) - 1}"))
        else:
            good_t.append(k)
    if "triangles" in d and isinstance(d["triangles"], list) and not ts:
        r.add(f"{path}.triangles", "a mesh needs at least one triangle")
    if not bad_v and good_t:
        vertices = np.array(vs, dtype=float)
        triangles = np.array([ts[k] for k in good_t], dtype=np.int64)
        for k in np.flatnonzero(degenerate(vertices, triangles)):
            bad_t.append((good_t[k], f"degenerate triangle (zero area): {show(ts[good_t[k]])}"))
    r.capped(f"{path}.triangles", sorted(bad_t))
    if bad_v or bad_t or len(vs) < 3 or not ts:
        return None
    if not r.count_triangles(f"{path}.triangles", len(triangles), "this mesh"):
        return None
    return vertices, triangles


def _read_mesh_file(r: _Reader, d: dict, path: str, base_dir, read_mesh):
    """Vertices, triangles and source of a mesh file, or None."""
    p = f"{path}.path"
    name = r.string(d["path"], p) if "path" in d else None
    if name is None:
        return None
    if not name:
        r.add(p, "must not be empty")
        return None
    resolved = os.path.abspath(os.path.join(base_dir or os.getcwd(), name))
    if read_mesh is None:
        r.add(p, f"cannot read mesh file {name!r}: no mesh reader was given (read_mesh)")
        return None
    try:
        vertices, triangles = read_mesh(resolved)
        vertices = np.asarray(vertices, dtype=float)
        triangles = np.asarray(triangles)
    except Exception as exc:  # any failure of the reader is a problem of this field
        r.add(p, str(exc) or f"cannot read mesh file {name!r} ({type(exc).__name__})")
        return None
    if vertices.ndim != 2 or vertices.shape[1] != 3 or not np.isfinite(vertices).all():
        r.add(p, f"mesh file {name!r}: vertices are not finite (N, 3) numbers")
    elif np.abs(vertices).max(initial=0.0) > MAX_MAGNITUDE:
        r.add(p, f"mesh file {name!r}: coordinates must be within ±{MAX_MAGNITUDE:,.0f}")
    elif triangles.ndim != 2 or triangles.shape[1] != 3 or len(triangles) == 0 or (
        not np.issubdtype(triangles.dtype, np.integer)
    ):
        r.add(p, f"mesh file {name!r}: no triangles (expected (M, 3) vertex indices)")
    else:
        bad = _triangle_problems(vertices, triangles.astype(np.int64))
        for k, message in bad[:MAX_LISTED]:
            r.add(p, f"mesh file {name!r}, triangle {k}: {message}")
        if len(bad) > MAX_LISTED:
            r.add(p, f"mesh file {name!r}: ... and {len(bad) - MAX_LISTED} more bad triangles")
        if not bad and r.count_triangles(p, len(triangles), f"mesh file {name!r}"):
            source = {"type": "mesh_file", "path": name, "resolved_path": resolved}
            return vertices, triangles, source
    return None


def _read_primitive(r: _Reader, type_name: str, d: dict, path: str) -> dict:
    values = {}
    for param in shapes.PRIMITIVES[type_name].params:
        p = join(path, param.name)
        if param.name not in d:
            if param.default is shapes.REQUIRED:
                continue  # reported as missing
            values[param.name] = shapes.canonical(param.kind, param.default)
            continue
        v = d[param.name]
        if param.kind in ("point", "size3", "size2"):
            got = r.vector(v, p, 2 if param.kind == "size2" else 3, param.kind != "point")
        elif param.kind == "length":
            got = r.number(v, p)
        else:
            got = r.integer(v, p)
        if got is not None:
            values[param.name] = got
    for key, message in shapes.param_problems(type_name, values):
        r.add(join(path, key), message)
    return values


def _primitive_triangles(type_name: str, values: dict) -> int:
    """How many triangles a primitive will have, from its checked parameters alone."""
    if type_name == "uv_sphere":
        return 2 * values["segments"] * (values["rings"] - 1)
    if type_name == "cone":
        return 2 * values["segments"]
    return 24  # box, pyramid, quad, notched_prism: a fixed handful


def _read_object(r: _Reader, value, path, base_dir, read_mesh):
    if not isinstance(value, dict):
        r.add(path, f"expected an object {{...}}, got {show(value)}")
        return None
    if "type" not in value:
        r.add(f"{path}.type", f"required field is missing (one of: {', '.join(OBJECT_TYPES)})")
        return None
    type_name = value["type"]
    if type_name not in OBJECT_TYPES:
        r.add(f"{path}.type",
              f"unknown object type {show(type_name)}; known types: {', '.join(OBJECT_TYPES)}")
        return None
    own = _TYPE_FIELDS[type_name]
    required = own if type_name in ("sphere", "mesh", "mesh_file") else [
        p.name for p in shapes.PRIMITIVES[type_name].params if p.default is shapes.REQUIRED
    ]
    before = len(r.problems)
    d = r.fields(value, path, [*_COMMON, *own], required)
    name = r.string(d["name"], f"{path}.name") if "name" in d else None
    material = _read_material(r, d.get("material", {}), f"{path}.material")

    if type_name == "sphere":
        center = r.vector(d["center"], f"{path}.center") if "center" in d else None
        radius = r.number(d["radius"], f"{path}.radius", gt=0) if "radius" in d else None
        if len(r.problems) == before:
            return Sphere(center, radius, material, "sphere" if name is None else name)
    elif type_name == "mesh":
        arrays = _read_inline_mesh(r, d, path)
        if arrays is not None and len(r.problems) == before:
            return Mesh(*arrays, material=material, name="mesh" if name is None else name)
    elif type_name == "mesh_file":
        got = _read_mesh_file(r, d, path, base_dir, read_mesh)
        if got is not None and len(r.problems) == before:
            vertices, triangles, source = got
            if name is None:
                name = PurePath(source["path"]).stem or "mesh"
            return Mesh(vertices, triangles, material, name, source)
    else:
        values = _read_primitive(r, type_name, d, path)
        if len(r.problems) == before and r.count_triangles(
            path, _primitive_triangles(type_name, values), f"this {type_name}"
        ):
            try:
                mesh = shapes.PRIMITIVES[type_name].builder(**values, material=material, name=name)
            except ValueError as exc:  # not expected: the parameters were checked
                r.add(path, str(exc))
                return None
            if degenerate(mesh.vertices, mesh.triangles).any():
                r.add(path, "too small to build: some of its triangles have zero area")
                return None
            return mesh
    return None


def _too_many(n: int, limit: int) -> str:
    return f"at most {limit:,} are allowed, got {n:,}"


def _limited(r: _Reader, value, path: str, limit: int) -> list:
    """The list at ``path``, or an empty one (and a problem) if it holds more than ``limit``."""
    items = r.listing(value, path)
    if len(items) > limit:
        r.add(path, _too_many(len(items), limit))
        return []
    return items


def counted_triangles(obj) -> int:
    """The triangles the loader counts for ``obj`` against :data:`MAX_TRIANGLES`: a primitive's
    from its parameters (as :func:`from_dict` counts them), a mesh's own, none for a sphere."""
    if isinstance(obj, Sphere):
        return 0
    source = obj.source or {}
    if source.get("type") in shapes.PRIMITIVES:
        return _primitive_triangles(source["type"], source)
    return len(obj.triangles)


def read_object(value, index: int, count: int, triangles_elsewhere: int = 0, base_dir=None,
                read_mesh: MeshReader | None = None):
    """Object ``objects[index]`` of a scene file, checked exactly as :func:`from_dict` checks it.

    For the scene's limits, the file has ``count`` objects and the others have
    ``triangles_elsewhere`` triangles (as :func:`counted_triangles` counts them);
    so an editor can check one changed object without reading the others again.

    Raises
    ------
    SceneFileError
        Listing every problem, with the paths a whole file would give.
    """
    r = _Reader()
    r.triangles = triangles_elsewhere
    if count > MAX_OBJECTS:
        r.add("objects", _too_many(count, MAX_OBJECTS))
    obj = _read_object(r, value, f"objects[{index}]", base_dir, read_mesh)
    if r.problems:
        raise SceneFileError(r.problems)
    return obj


def from_dict(d, base_dir=None, read_mesh: MeshReader | None = None) -> Scene:
    """Build a scene from the parsed JSON of a scene file.

    Parameters
    ----------
    d : the JSON object (a dict).
    base_dir : folder that relative ``mesh_file`` paths are relative to
        (default: the current directory).
    read_mesh : ``path -> (vertices (N, 3), triangles (M, 3))`` for
        ``mesh_file`` objects; it may raise any exception, whose message
        becomes the problem of that object's ``path``.

    Raises
    ------
    SceneFileError
        Listing every problem found.
    """
    r = _Reader()
    if other_kind(d, FORMAT):
        raise SceneFileError([other_kind(d, FORMAT)])
    if nesting_depth(d, MAX_NESTING) > MAX_NESTING:
        raise SceneFileError([f"top level: arrays and objects nested more than {MAX_NESTING} "
                              "levels deep (a scene needs 5)"])
    known = ["format", "version", "camera", "background", "lights", "objects"]
    data = r.fields(d, "", known)
    if data is None:
        raise SceneFileError(r.problems)
    r.header(data, FORMAT, VERSION)
    camera = read_camera(r, data.get("camera", {}))
    background = Scene().background
    if "background" in data:
        background = r.color(data["background"], "background") or background
    lights = [
        _read_light(r, v, f"lights[{k}]")
        for k, v in enumerate(_limited(r, data.get("lights", []), "lights", MAX_LIGHTS))
    ]
    objects = [
        _read_object(r, v, f"objects[{k}]", base_dir, read_mesh)
        for k, v in enumerate(_limited(r, data.get("objects", []), "objects", MAX_OBJECTS))
    ]
    if r.problems:
        raise SceneFileError(r.problems)
    return Scene(camera=camera, objects=tuple(objects), lights=tuple(lights),
                 background=background)


def load(path_or_dict, read_mesh: MeshReader | None = None) -> Scene:
    """Load a scene from a JSON file (or an already parsed dict).

    Relative ``mesh_file`` paths are resolved against the scene file's folder.
    Raises :class:`SceneFileError` for anything wrong: a missing or unreadable
    file, invalid JSON (with its line and column), or invalid content.
    """
    if isinstance(path_or_dict, dict):
        return from_dict(path_or_dict, read_mesh=read_mesh)
    path = Path(path_or_dict)
    data = read_json(path, MAX_FILE_BYTES, SceneFileError)
    try:
        return from_dict(data, base_dir=path.parent, read_mesh=read_mesh)
    except SceneFileError as exc:
        raise SceneFileError(exc.problems, str(path)) from None


# --- writing -----------------------------------------------------------------


def _material_dict(m: Material) -> dict:
    """The fields of ``m`` that differ from the defaults."""
    d = {}
    for f in fields(Material):
        value = getattr(m, f.name)
        if value != getattr(Material(), f.name):
            d[f.name] = [float(c) for c in value] if f.name == "color" else float(value)
    return d


def _mesh_file_path(source: dict, base_dir) -> str:
    """The path to write: as it was read, unless the file moves to another folder."""
    path, resolved = source["path"], source.get("resolved_path")
    if base_dir is None or resolved is None or os.path.isabs(path):
        return path
    if os.path.abspath(os.path.join(base_dir, path)) == resolved:
        return path
    try:
        return PurePath(os.path.relpath(resolved, os.path.abspath(base_dir))).as_posix()
    except ValueError:  # another drive (Windows)
        return resolved


def _object_dict(obj, base_dir) -> dict:
    d = {"type": "sphere", "name": obj.name}
    if obj.material != Material():
        d["material"] = _material_dict(obj.material)
    if isinstance(obj, Sphere):
        d.update(center=[float(c) for c in obj.center], radius=float(obj.radius))
        return d
    source = obj.source or {}
    kind = source.get("type")
    if kind in shapes.PRIMITIVES:
        d.update(type=kind, **{k: v for k, v in source.items() if k != "type"})
    elif kind == "mesh_file":
        d.update(type="mesh_file", path=_mesh_file_path(source, base_dir))
    else:
        d.update(type="mesh", vertices=obj.vertices.tolist(), triangles=obj.triangles.tolist())
    return d


def to_dict(scene: Scene, base_dir=None) -> dict:
    """The scene as the JSON object of a scene file.

    Primitives are written as primitives (from ``Mesh.source``), meshes read
    from files as their path, other meshes inline.  ``base_dir`` is the folder
    the file will be written to: relative mesh file paths are rewritten, if
    needed, to stay correct from there.
    """
    c = scene.camera
    camera = {
        "eye": [float(x) for x in c.eye],
        "target": [float(x) for x in c.target],
        "up": [float(x) for x in c.up],
        "fov_y_deg": float(c.fov_y_deg),
        "near": float(c.near),
        "far": float(c.far),
        "projection": c.projection,
        "ortho_height": float(c.ortho_height),
        "width": int(c.width),
        "height": int(c.height),
    }
    lights = [
        {"position": [float(x) for x in light.position],
         "color": [float(x) for x in light.color],
         "intensity": float(light.intensity),
         "name": light.name}
        for light in scene.lights
    ]
    return {
        "format": FORMAT,
        "version": VERSION,
        "camera": camera,
        "background": [float(x) for x in scene.background],
        "lights": lights,
        "objects": [_object_dict(obj, base_dir) for obj in scene.objects],
    }


def dumps(d: dict, indent: int = 0) -> str:
    """JSON text of ``d``: lists of plain values on one line, everything else indented."""
    pad, inner = "  " * indent, "  " * (indent + 1)
    if isinstance(d, dict) and d:
        items = [f"{inner}{json.dumps(k)}: {dumps(v, indent + 1)}" for k, v in d.items()]
        return "{\n" + ",\n".join(items) + f"\n{pad}}}"
    if isinstance(d, list) and any(isinstance(x, (dict, list)) for x in d):
        items = [inner + dumps(x, indent + 1) for x in d]
        return "[\n" + ",\n".join(items) + f"\n{pad}]"
    return json.dumps(d, allow_nan=False)


def save(scene: Scene, path) -> None:
    """Write ``scene`` to a JSON scene file; :func:`load` gives back an equal scene.

    The file is replaced only once the new text is completely written.

    Raises
    ------
    core.files.safe_files.OutputError
        An ``OSError`` naming the file, when it cannot be written; the old
        file is then unchanged.
    """
    path = Path(path)
    text = dumps(to_dict(scene, base_dir=path.parent)) + "\n"
    safe_files.write_atomic(path, text.encode("utf-8"))
