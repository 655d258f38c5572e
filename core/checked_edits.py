"""Editing a scene the way its file would be edited: every change passes the file's checks.

An edit is made on the changed item's file form (its part of
:func:`core.files.scene_file.to_dict`) and read back by the loader
(:func:`core.files.scene_file.read_object` for an object, :func:`core.files.scene_file.from_dict`
for lights and the background).  So a value the loader would refuse in a file
is refused here too, with the loader's own message
(``objects[0].radius: must be > 0, got -1``), and a refused edit leaves the
scene as it was: every function returns a new :class:`core.scene.Scene` or
raises :class:`core.files.scene_file.SceneFileError`.  The scene's limits (objects,
lights, triangles in all) are checked with the other items counted as they are.

Only the changed item is read: the others were checked when they came in and
stay the same Python objects, so what the renderers cached for them stays
valid.  A mesh whose vertices an edit leaves alone (a new name or material, a
copy) is checked with a one-triangle stand-in for its geometry and keeps its
own arrays, so editing a large mesh costs no more than editing a cube.

Items of a scene are addressed as ``(kind, index)``: ``("object", i)``,
``("light", i)`` and :data:`BACKGROUND`.  An item's *form* is its part of the
file: an object's or light's dict, and for the background ``{"color": [r, g, b]}``.
Fields are addressed by their key in the form, with ``"material.color"`` for
a material's field.

The observer (the scene's camera) is never changed here: moving it is not an
edit of the scene.
"""

from __future__ import annotations

import copy
import math
import os
import re
from dataclasses import replace

import numpy as np

from core import shapes
from core.files import scene_file
from core.files.checked_json import Reader
from core.scene import Mesh, Scene

Item = tuple[str, int]
BACKGROUND: Item = ("background", 0)

NEW_OBJECTS = {
    "sphere": {"center": None, "radius": 0.5},
    "box": {"center": None, "size": [1.0, 1.0, 1.0]},
    "cone": {"base_center": None, "radius": 0.5, "height": 1.0},
    "pyramid": {"base_center": None, "base_size": 1.0, "height": 1.0},
    "quad": {"center": None, "size": [4.0, 4.0]},
    "uv_sphere": {"center": None, "radius": 0.5},
    "notched_prism": {"base_center": None, "size": [1.2, 1.0, 1.2], "notch": [0.5, 0.5]},
}
"""The file form of a new object of each type; ``None`` is where it goes (its position)."""
NEW_LIGHT = {"color": [1.0, 1.0, 1.0], "intensity": 1.0}
LIGHT_ABOVE = 3.0
"""A new light is placed this far (scene units) above the point given."""
_STAND_IN = {"vertices": [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]], "triangles": [[0, 1, 2]]}


def name_of(scene: Scene, item: Item) -> str:
    """How the item is called in the tree and in the edits' names."""
    kind, index = item
    if kind == "background":
        return "background"
    return (scene.objects if kind == "object" else scene.lights)[index].name


def names(scene: Scene, kind: str) -> list[str]:
    return [x.name for x in (scene.objects if kind == "object" else scene.lights)]


def _base(base_dir) -> str:
    """The folder relative mesh file paths are written against (and read back from)."""
    return os.getcwd() if base_dir is None else os.fspath(base_dir)


def _is_plain_mesh(obj) -> bool:
    """A mesh given by its vertices (inline or from a file), not built from a primitive's parameters."""
    return isinstance(obj, Mesh) and (obj.source or {}).get("type") not in shapes.PRIMITIVES


def form(scene: Scene, item: Item, base_dir=None) -> dict:
    """The item's part of the scene file (a fresh copy that the caller may change).

    ``base_dir`` is the scene file's folder (default: the current one); give the
    same to the function that takes the changed form back.  A mesh's form holds
    its vertices, so for a large mesh it is large.
    """
    kind, index = item
    if kind == "object":
        one = replace(scene, objects=(scene.objects[index],))
        return scene_file.to_dict(one, _base(base_dir))["objects"][0]
    d = scene_file.to_dict(replace(scene, objects=()))
    return {"color": d["background"]} if kind == "background" else d["lights"][index]


def _light_forms(scene: Scene) -> list[dict]:
    return scene_file.to_dict(replace(scene, objects=()))["lights"]


def position_key(scene: Scene, item: Item) -> str | None:
    """The form's field that places the item (``center``, ``base_center``, ``position``);
    ``None`` for a mesh (placed by its vertices) and the background."""
    kind, index = item
    if kind == "light":
        return "position"
    if kind != "object":
        return None
    obj = scene.objects[index]
    if not isinstance(obj, Mesh):
        return "center"
    type_name = (obj.source or {}).get("type")
    if type_name in shapes.PRIMITIVES:
        return next(p.name for p in shapes.PRIMITIVES[type_name].params if p.kind == "point")
    return None


def position_of(scene: Scene, item: Item) -> np.ndarray | None:
    """(3,) world-space point that places the item: its centre, base centre or position;
    for a mesh the centre of its bounding box; ``None`` for the background."""
    kind, index = item
    if kind == "light":
        return np.array(scene.lights[index].position, dtype=float)
    if kind != "object":
        return None
    obj = scene.objects[index]
    if not isinstance(obj, Mesh):
        return np.array(obj.center, dtype=float)
    if not _is_plain_mesh(obj):
        return np.array(obj.source[position_key(scene, item)], dtype=float)
    return (obj.vertices.min(axis=0) + obj.vertices.max(axis=0)) / 2.0


# --- edits -------------------------------------------------------------------------


def with_field(scene: Scene, item: Item, key: str, value, base_dir=None, read_mesh=None) -> Scene:
    """``scene`` with the item's field ``key`` (``"radius"``, ``"material.color"``) set to ``value``
    (a JSON value: number, list, string), checked as the loader checks a file, and a new name
    checked to be free (:func:`_name_free`)."""
    kind, index = item
    if key == "name":
        _name_free(scene, item, value)
    keeps_geometry = kind == "object" and _is_plain_mesh(scene.objects[index])
    new = _small_form(scene, item, base_dir) if keeps_geometry else form(scene, item, base_dir)
    *parents, last = key.split(".")
    target = new
    for part in parents:
        target = target.setdefault(part, {})
    target[last] = value
    if keeps_geometry:
        objects = list(scene.objects)
        objects[index] = _read(scene, new, index, len(objects), index, base_dir, read_mesh,
                               geometry_of=objects[index])
        return replace(scene, objects=tuple(objects))
    return with_form(scene, item, new, base_dir, read_mesh)


def _name_free(scene: Scene, item: Item, name) -> None:
    """Refuse ``name`` for ``item`` when another object (another light, for a light) has it: lessons,
    their facts and exercises pick objects out by name, and two of one name would leave the second
    unreachable.  The item's own name, typed again, is fine."""
    kind, index = item
    taken = names(scene, kind)
    if name != taken[index] and name in taken:
        whose = f"{kind}s[{taken.index(name)}]"
        raise scene_file.SceneFileError([f"{kind}s[{index}].name: {name!r} is already the name of {whose}; "
                                         f"each {kind} needs a name of its own"])


def with_form(scene: Scene, item: Item, value: dict, base_dir=None, read_mesh=None) -> Scene:
    """``scene`` with the item's whole form replaced by ``value`` (checked)."""
    kind, index = item
    if kind == "background":
        loaded = scene_file.from_dict({"background": value.get("color")})
        return replace(scene, background=loaded.background)
    if kind == "light":
        lights = _light_forms(scene)
        lights[index] = value
        return replace(scene, lights=scene_file.from_dict({"lights": lights}).lights)
    objects = list(scene.objects)
    objects[index] = _read(scene, value, index, len(objects), index, base_dir,
                           _cached_reader(scene.objects, read_mesh))
    return replace(scene, objects=tuple(objects))


def moved(scene: Scene, item: Item, position, base_dir=None, read_mesh=None) -> Scene:
    """``scene`` with the item placed at ``position`` (see :func:`position_of`).

    A mesh is moved by moving its vertices; one read from a file is then
    written into the scene file (inline), since the file no longer holds it.
    """
    key = position_key(scene, item)
    r = Reader()  # three numbers, checked as the scene file's are: never a bare ValueError
    kind, index = item
    given = position.tolist() if isinstance(position, np.ndarray) else (
        list(position) if isinstance(position, (list, tuple)) else position)
    position = r.vector(given, f"{'objects' if kind == 'object' else 'lights'}[{index}].{key or 'position'}")
    if r.problems:
        raise scene_file.SceneFileError(r.problems)
    if key is not None:
        return with_field(scene, item, key, list(position), base_dir, read_mesh)
    obj = scene.objects[index]
    vertices = obj.vertices + (np.asarray(position) - position_of(scene, item))
    # The moved vertices pass the checks of a mesh read from a file (numbers in range,
    # no triangle of zero area), done on the arrays.
    as_read = {k: v for k, v in _small_form(scene, item, base_dir).items() if k not in _STAND_IN}
    as_read.update(type="mesh_file", path=obj.name or "mesh")
    mesh = _read(scene, as_read, index, len(scene.objects), index, base_dir,
                 lambda path: (vertices, obj.triangles))
    objects = list(scene.objects)
    objects[index] = replace(mesh, source=None)
    return replace(scene, objects=tuple(objects))


def added(scene: Scene, kind: str, value: dict, index: int | None = None, base_dir=None,
          read_mesh=None, known=()) -> tuple[Scene, Item]:
    """``scene`` with a new object or light (its form ``value``) at ``index`` (default: last).

    ``known`` are meshes already read (e.g. in the background) whose files
    need not be read again.  Returns the new scene and the new item.
    """
    if kind == "light":
        lights = _light_forms(scene)
        index = len(lights) if index is None else index
        lights.insert(index, value)
        return replace(scene, lights=scene_file.from_dict({"lights": lights}).lights), (kind, index)
    objects = list(scene.objects)
    index = len(objects) if index is None else index
    objects.insert(index, _read(scene, value, index, len(objects) + 1, None, base_dir,
                                _cached_reader([*scene.objects, *known], read_mesh)))
    return replace(scene, objects=tuple(objects)), (kind, index)


def duplicated(scene: Scene, item: Item, base_dir=None, read_mesh=None) -> tuple[Scene, Item]:
    """``scene`` with a copy of the item just after it, named like it with a number."""
    kind, index = item
    name = unique_name(name_of(scene, item), names(scene, kind))
    if kind == "object" and _is_plain_mesh(scene.objects[index]):
        original = scene.objects[index]
        copied = _read(scene, {**_small_form(scene, item, base_dir), "name": name}, index + 1,
                       len(scene.objects) + 1, None, base_dir, read_mesh, geometry_of=original)
        objects = list(scene.objects)
        objects.insert(index + 1, copied)
        return replace(scene, objects=tuple(objects)), (kind, index + 1)
    return added(scene, kind, {**form(scene, item, base_dir), "name": name}, index + 1, base_dir,
                 read_mesh)


def removed(scene: Scene, item: Item) -> Scene:
    """``scene`` without the item (nothing to check: any part of a valid scene is valid)."""
    kind, index = item
    if kind == "object":
        return replace(scene, objects=scene.objects[:index] + scene.objects[index + 1:])
    return replace(scene, lights=scene.lights[:index] + scene.lights[index + 1:])


def unique_name(name: str, taken) -> str:
    """``name``, or if it is taken, its stem with the smallest free number: ``"cube 2"``."""
    taken = set(taken)
    if name not in taken:
        return name
    stem = re.sub(r" \d+$", "", name)
    k = 2
    while f"{stem} {k}" in taken:
        k += 1
    return f"{stem} {k}"


def new_object(scene: Scene, type_name: str, at) -> dict:
    """The form of a new primitive of ``type_name`` placed at ``at`` (world space), with a free name."""
    value = {"type": type_name, "name": unique_name(type_name, names(scene, "object"))}
    for key, default in NEW_OBJECTS[type_name].items():
        value[key] = [float(c) for c in at] if default is None else copy.deepcopy(default)
    return value


#: How many steps towards the eye :func:`plain_view_spot` tries at most (for a tiny object they are
#: longer than the object: the search runs on the GUI thread, and steps of a tiny object's size
#: were billions).
_MOST_STEPS_BACK = 100


def plain_view_spot(scene: Scene, low, high) -> np.ndarray:
    """Where to put a new object whose bounding box, relative to its position, is ``low`` to
    ``high`` (scene units), so that the observer sees it: the point nearest the observer's
    target, stepping sideways (along the screen's right) and then towards the eye, at which the
    object's box touches no other object's box, its position lies in the frustum and the line
    from the eye to it passes no object's box.  The target itself when no such point is near.

    (The lecture scene's target lies behind the cone: a new object put there was hidden.)  The
    point's coordinates are rounded to a hundredth of the object's size in its order of magnitude
    (a unit sphere's to 0.01), so that the editor shows its position as a person would type it
    (it showed ``1.6641005``).
    """
    cam = scene.camera
    eye, target = np.asarray(cam.eye, float), np.asarray(cam.target, float)
    low, high = np.asarray(low, float), np.asarray(high, float)
    forward = cam.forward
    right = np.cross(forward, np.asarray(cam.up, float))
    right /= np.linalg.norm(right)
    boxes = [object_bounds(obj) for obj in scene.objects]
    step = float(np.max(high - low))
    if not 0.0 < step < math.inf:
        return target
    sideways = [0.0] + [sign * k * step for k in range(1, 6) for sign in (1.0, -1.0)]
    digits = min(2 - math.floor(math.log10(step)), 15)  # a hundredth of its size (15 round nothing)
    reach = max(cam.distance - cam.near - step, 0.0)
    for back in np.arange(0.0, reach, max(step, reach / _MOST_STEPS_BACK)):
        for side in sideways:
            spot = np.round(target - back * forward + side * right, digits) + 0.0  # no -0.0
            if (_free(spot + low, spot + high, boxes) and cam.project(spot).inside
                    and all(_misses(eye, spot, box) for box in boxes)):
                return spot
    return target


def object_bounds(obj) -> tuple[np.ndarray, np.ndarray]:
    """The object's axis-aligned bounding box: its lowest and highest corner (world space)."""
    if isinstance(obj, Mesh):
        return obj.vertices.min(axis=0), obj.vertices.max(axis=0)
    center = np.asarray(obj.center, float)
    return center - obj.radius, center + obj.radius


def _free(low, high, boxes) -> bool:
    """Whether the box ``low`` to ``high`` shares no inner point with any of ``boxes``."""
    return not any(np.all(high > other_low) and np.all(low < other_high) for other_low, other_high in boxes)


def _misses(start, end, box) -> bool:
    """Whether the segment from ``start`` to ``end`` misses ``box`` (the slab test: the segment's
    parameter interval inside all three slabs is empty)."""
    low, high = box
    direction = end - start
    enter, leave = 0.0, 1.0
    for axis in range(3):
        if direction[axis] == 0.0:
            if not low[axis] <= start[axis] <= high[axis]:
                return True
            continue
        t0, t1 = sorted(((low[axis] - start[axis]) / direction[axis],
                         (high[axis] - start[axis]) / direction[axis]))
        enter, leave = max(enter, t0), min(leave, t1)
    return enter > leave


def new_mesh_file(scene: Scene, path) -> dict:
    """The form of a mesh read from the file ``path`` (kept as an absolute path)."""
    path = os.path.abspath(path)
    stem = os.path.splitext(os.path.basename(path))[0] or "mesh"
    return {"type": "mesh_file", "name": unique_name(stem, names(scene, "object")), "path": path}


def new_light(scene: Scene, at) -> dict:
    """The form of a new white light :data:`LIGHT_ABOVE` above ``at``, with a free name."""
    position = [float(at[0]), float(at[1]) + LIGHT_ABOVE, float(at[2])]
    return {"position": position, **copy.deepcopy(NEW_LIGHT),
            "name": unique_name("light", names(scene, "light"))}


def read_object(value: dict, read_mesh=None, index: int = 0):
    """One object from its form, checked on its own (e.g. a mesh file, read in the background), its
    problems named as those of object ``index`` (where it is to go)."""
    return scene_file.read_object(value, index, index + 1, read_mesh=read_mesh)


# --- checking ------------------------------------------------------------------------


def _small_form(scene: Scene, item: Item, base_dir) -> dict:
    """A plain mesh's form with a one-triangle stand-in for its vertices (name and material as they are)."""
    stand_in = replace(scene.objects[item[1]], source=None, **{k: np.array(v) for k, v in _STAND_IN.items()})
    return scene_file.to_dict(replace(scene, objects=(stand_in,)), _base(base_dir))["objects"][0]


def _cached_reader(meshes, read_mesh):
    """A ``read_mesh`` that gives the meshes of ``meshes`` read from files without reading them again."""
    read = {o.source["resolved_path"]: (o.vertices, o.triangles) for o in meshes
            if isinstance(o, Mesh) and "resolved_path" in (o.source or {})}

    def reader(path):
        if path in read:
            return read[path]
        if read_mesh is None:
            raise ValueError(f"cannot read mesh file {path!r}: no mesh reader was given")
        return read_mesh(path)

    return reader


def _read(scene: Scene, value: dict, index: int, count: int, replacing: int | None, base_dir,
          read_mesh, geometry_of: Mesh | None = None):
    """Object ``index`` of the edited scene (``count`` objects) from its form ``value``, checked.

    The scene's other objects (all but ``replacing``) count towards its triangle limit.
    With ``geometry_of``, ``value`` holds the stand-in geometry and the object
    read keeps that mesh's arrays and source instead.
    """
    elsewhere = sum(scene_file.counted_triangles(o) for j, o in enumerate(scene.objects) if j != replacing)
    if geometry_of is not None:
        elsewhere += scene_file.counted_triangles(geometry_of) - 1  # the stand-in has one
    obj = scene_file.read_object(value, index, count, elsewhere, _base(base_dir), read_mesh)
    if geometry_of is not None:
        return replace(geometry_of, name=obj.name, material=obj.material)
    return obj
