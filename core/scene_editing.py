"""Editing a scene the way its file would be edited: every change passes the file's checks.

An edit is made on the scene's file form (:func:`core.scene_file.to_dict`) and
loaded back with :func:`core.scene_file.from_dict`.  So a value the loader
would refuse in a file is refused here too, with the loader's own message
(``objects[0].radius: must be > 0, got -1``), and a refused edit leaves the
scene as it was: every function returns a new :class:`core.scene.Scene` or
raises :class:`core.scene_file.SceneFileError`.

Items of a scene are addressed as ``(kind, index)``: ``("object", i)``,
``("light", i)`` and :data:`BACKGROUND`.  An item's *form* is its part of the
file: an object's or light's dict, and for the background ``{"color": [r, g, b]}``.
Fields are addressed by their key in the form, with ``"material.color"`` for
a material's field.

The observer (the scene's camera) is never changed here: moving it is not an
edit of the scene.  Objects an edit did not touch are kept as they were (the
same Python objects), so what the renderers cached for them stays valid.
"""

from __future__ import annotations

import copy
import os
import re
from dataclasses import replace

import numpy as np

from core import scene_file, shapes
from core.scene import Mesh, Scene

Item = tuple[str, int]
BACKGROUND: Item = ("background", 0)
KINDS = ("object", "light")

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


def _key(kind: str) -> str:
    return {"object": "objects", "light": "lights"}[kind]


def name_of(scene: Scene, item: Item) -> str:
    """How the item is called in the tree and in the edits' names."""
    kind, index = item
    if kind == "background":
        return "background"
    return (scene.objects if kind == "object" else scene.lights)[index].name


def _base(base_dir) -> str:
    """The folder relative mesh file paths are written against (and read back from)."""
    return os.getcwd() if base_dir is None else os.fspath(base_dir)


def form(scene: Scene, item: Item, base_dir=None) -> dict:
    """The item's part of the scene file (a fresh copy that the caller may change).

    ``base_dir`` is the scene file's folder (default: the current one); give the
    same to the function that takes the changed form back.
    """
    kind, index = item
    if kind == "object":
        one = replace(scene, objects=(scene.objects[index],))
        return scene_file.to_dict(one, _base(base_dir))["objects"][0]
    d = scene_file.to_dict(replace(scene, objects=()))
    return {"color": d["background"]} if kind == "background" else d["lights"][index]


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
    key = position_key(scene, item)
    if key is not None:
        return np.array(form(scene, item)[key], dtype=float)
    if item[0] == "object":
        v = scene.objects[item[1]].vertices
        return (v.min(axis=0) + v.max(axis=0)) / 2.0
    return None


def with_field(scene: Scene, item: Item, key: str, value, base_dir=None, read_mesh=None) -> Scene:
    """``scene`` with the item's field ``key`` (``"radius"``, ``"material.color"``) set to ``value``
    (a JSON value: number, list, string), checked as the loader checks a file."""
    new = form(scene, item, base_dir)
    *parents, last = key.split(".")
    target = new
    for part in parents:
        target = target.setdefault(part, {})
    target[last] = value
    return with_form(scene, item, new, base_dir, read_mesh)


def with_form(scene: Scene, item: Item, value: dict, base_dir=None, read_mesh=None) -> Scene:
    """``scene`` with the item's whole form replaced by ``value`` (checked)."""
    kind, index = item
    if kind == "background":
        return _checked(scene, list(scene.objects), base_dir, read_mesh, background=value.get("color"))
    if kind == "light":
        lights = _light_forms(scene)
        lights[index] = value
        return _checked(scene, list(scene.objects), base_dir, read_mesh, lights=lights)
    objects = list(scene.objects)
    objects[index] = value
    return _checked(scene, objects, base_dir, read_mesh)


def moved(scene: Scene, item: Item, position, base_dir=None, read_mesh=None) -> Scene:
    """``scene`` with the item placed at ``position`` (see :func:`position_of`).

    A mesh is moved by moving its vertices; one read from a file is then
    written into the scene file (inline), since the file no longer holds it.
    """
    position = [float(c) for c in position]
    key = position_key(scene, item)
    if key is not None:
        return with_field(scene, item, key, position, base_dir, read_mesh)
    obj = scene.objects[item[1]]
    offset = np.asarray(position) - position_of(scene, item)
    new = form(scene, item, base_dir)
    new.pop("path", None)
    new.update(type="mesh", vertices=(obj.vertices + offset).tolist(), triangles=obj.triangles.tolist())
    return with_form(scene, item, new, base_dir, read_mesh)


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
        return _checked(scene, list(scene.objects), base_dir, read_mesh, lights=lights), (kind, index)
    objects = list(scene.objects)
    index = len(objects) if index is None else index
    objects.insert(index, value)
    return _checked(scene, objects, base_dir, read_mesh, known), (kind, index)


def duplicated(scene: Scene, item: Item, base_dir=None, read_mesh=None) -> tuple[Scene, Item]:
    """``scene`` with a copy of the item just after it, named like it with a number."""
    kind, index = item
    copied = form(scene, item, base_dir)
    copied["name"] = unique_name(name_of(scene, item), names(scene, kind))
    return added(scene, kind, copied, index + 1, base_dir, read_mesh)


def removed(scene: Scene, item: Item) -> Scene:
    """``scene`` without the item (nothing to check: any part of a valid scene is valid)."""
    kind, index = item
    items = scene.objects if kind == "object" else scene.lights
    kept = items[:index] + items[index + 1:]
    return replace(scene, **{_key(kind): kept})


def names(scene: Scene, kind: str) -> list[str]:
    return [x.name for x in (scene.objects if kind == "object" else scene.lights)]


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


def read_object(value: dict, read_mesh=None):
    """One object from its form, checked on its own (e.g. a mesh file, read in the background)."""
    return scene_file.from_dict({"objects": [value]}, read_mesh=read_mesh).objects[0]


# --- checking ------------------------------------------------------------------


def _cached_reader(objects, read_mesh):
    """A ``read_mesh`` that gives the meshes of ``objects`` read from files without reading them again."""
    read = {o.source["resolved_path"]: (o.vertices, o.triangles) for o in objects
            if isinstance(o, Mesh) and (o.source or {}).get("type") == "mesh_file"
            and "resolved_path" in o.source}

    def reader(path):
        if path in read:
            return read[path]
        if read_mesh is None:
            raise ValueError(f"cannot read mesh file {path!r}: no mesh reader was given")
        return read_mesh(path)

    return reader


def _light_forms(scene: Scene) -> list[dict]:
    return scene_file.to_dict(replace(scene, objects=()))["lights"]


def _checked(scene: Scene, objects: list, base_dir, read_mesh, known=(), lights=None,
             background=None) -> Scene:
    """Load ``scene`` with new parts, checking every value as the loader checks a file.

    ``objects`` holds the scene's objects to keep as they are and forms (dicts) of new or
    changed ones; ``lights`` (forms) and ``background`` (a colour) replace the scene's when
    given.  Kept objects stay the same Python objects; the camera stays.
    """
    base_dir = _base(base_dir)
    kept = [None if isinstance(o, dict) else o for o in objects]
    d = scene_file.to_dict(replace(scene, objects=tuple(o for o in kept if o is not None)), base_dir)
    kept_forms = iter(d["objects"])
    d["objects"] = [o if isinstance(o, dict) else next(kept_forms) for o in objects]
    if lights is not None:
        d["lights"] = lights
    if background is not None:
        d["background"] = background
    loaded = scene_file.from_dict(d, base_dir, _cached_reader([*scene.objects, *known], read_mesh))
    return replace(loaded, camera=scene.camera, objects=tuple(
        k if k is not None else new for k, new in zip(kept, loaded.objects, strict=True)))
