"""Facts: what a lesson step claims, in words the pipelines can decide.

A step's text tells the student what happens ("object 5 is outside the
view", "yellow's fragment fails the depth test behind blue").  The step's
``facts`` say the same in a small vocabulary, and :func:`check_step` decides
each one by running the step's scene through the real pipelines: object order
(:func:`core.object_order.pipeline.render_raster` with its step history), image
order (:func:`core.image_order.ray_tree.trace_pixel`, the pixel's ray tree) and
the worked intersections (:mod:`core.image_order.intersect_sphere`,
:mod:`core.image_order.intersect_triangle`).  Nothing is compared with an
answer stored in the file except the numbers a fact itself states.

Every fact is one JSON object whose ``"fact"`` names its kind (pixels are
``[column, row]`` from the top left; objects are named as in the scene)::

    {"fact": "frustum", "object": "cube", "is": "inside"}           # inside | crossing | outside
    {"fact": "frustum", "object": "object 5", "is": "outside", "beyond": "left"}
    {"fact": "back_face", "object": "pyramid", "triangle": 2, "is": true}
    {"fact": "clipped", "object": "ground", "plane": "near", "is": true}
    {"fact": "zbuffer_keeps", "pixel": [80, 60], "object": "blue", "after": 3}
    {"fact": "ztest_fails", "pixel": [80, 60], "object": "yellow", "after": 3, "is": true}
    {"fact": "seen", "object": "object 3", "is": false}
    {"fact": "blend", "pixel": [128, 125], "object": "green pane", "equals": [0.4, 0.5, 0.3]}
    {"fact": "projects_to", "object": "cube", "vertex": 6, "pixel": [230, 110]}
    {"fact": "first_hit", "pixel": [80, 60], "object": "ball", "front_face": true}
    {"fact": "shadow", "pixel": [230, 155], "object": "cone", "light": 0}
    {"fact": "ray_event", "pixel": [205, 132], "hit": 1, "event": "refract"}
    {"fact": "rays", "pixel": [205, 132], "kind": "shadow", "count": 3}
    {"fact": "primitive_tests", "pixel": [132, 93], "count": 110}
    {"fact": "tests_per_pixel", "accel": "bvh", "fewer_than": "grid", "tests": "primitive tests"}
    {"fact": "changes_picture", "stage": "z_test", "is": false}
    {"fact": "same_surfaces"}
    {"fact": "ray_sphere", "origin": [2, 1, 2], "end": [10, 6, 6], "center": [6, 4, 6],
     "radius": 10, "value": "a", "equals": 105, "tolerance": 1e-9}
    {"fact": "ray_triangle", "origin": [0, 0, 0], "direction": [1, 1, 1], "a": [3, 0, 0],
     "b": [0, 3, 0], "c": [0, 0, 3], "value": "t", "equals": 1, "tolerance": 1e-9}

``frustum`` decides where the object's bounding sphere lies (object order's frustum culling); an
object ``outside`` may add the plane it lies wholly ``beyond`` (``left``, ``right``, ``bottom``,
``top``, ``near``, ``far``), as words such as "off to the observer's left" or "behind the eye" say.
``after`` (z-buffer facts) is the number of polygons drawn so far; left out it is the step's
``zbuffer_step``, or every polygon; they and ``seen`` (some pixel of the finished object-order image
shows the object) may narrow the object to one ``triangle`` of its mesh. ``blend`` holds when a
fragment of a transparent object passes at the pixel and the image memory after it is the lecture's
``c0 = alpha_s c_s + (1 - alpha_s) c_d`` of the colours before it (and equals ``equals``, when
given). ``is`` defaults to true (``"is": false`` states the opposite). ``first_hit`` with
``"object": null`` says the ray hits nothing; it may add the hit's ``"t"`` (distance along the unit
direction) or ``"point"``, with a ``"tolerance"``, and ``"front_face"``. ``ray_event``'s events are
``reflect``, ``refract`` and ``total_reflection`` at the ``hit``-th surface along some path of the
pixel's ray tree (1 = the primary ray's hit), optionally on a named ``object``. ``rays`` counts the
rays of a kind that were traced; ``primitive_tests`` the triangles and spheres the pixel's primary
ray is tested against in its search for the first hit (with no acceleration, every one; ``"is":
false``: another number of them).
``tests_per_pixel`` compares two acceleration methods by the mean intersection tests a pixel's rays
cost (all of them, as the image-order heat map counts them; ``tests`` is ``"primitive tests"``, the
default, or ``"box and sphere tests"``): it holds when the whole image traced with ``accel`` (and the
step's other image-order settings) costs fewer a pixel than with ``fewer_than``. ``changes_picture``
switches one object-order ``stage`` (``back_face_culling``, ``frustum_culling``, ``clipping``,
``sort_transparent``, ``z_test``) the other way from the step's settings and holds when some pixel of
the finished image changes ("for a convex solid this test alone gives the right picture": switching
the z-test off changes none). ``same_surfaces`` holds when object order's z-buffer and image order's
first hits find the same surface at every pixel of the step's image: the same view depth (within
:data:`core.compare.SAME_DEPTH`), or the background in both.
``ray_sphere`` takes the lecture's segment (``end``) or a ray (``direction``); its values are those
of :class:`core.image_order.intersect_sphere.SphereIntersection` (``a``, ``b``, ``c``,
``discriminant``, ``sqrt_discriminant``, ``offset_squared``, ``radius_squared``, ``t_near``,
``t_far``, ``t``, ``ray_hit_t``, ``hit``, ``point``, ...), ``ray_triangle``'s those of
:class:`core.image_order.intersect_triangle.TriangleIntersection` (``t``, ``alpha``, ``beta``,
``gamma``, ``hit``, ``point``). ``equals`` is a number, three numbers (a point) or true/false;
``tolerance`` (default ``1e-9``) is absolute. The README's "Lesson files" section shows the same
list.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from types import MappingProxyType

import numpy as np

from core.files.checked_json import is_integer, join, show
from core.image_order.flat_layout import ACCEL_CODES, HEAT_BOUNDS_TESTS, HEAT_PRIM_TESTS
from core.image_order.ray_tree import KINDS as RAY_KINDS
from core.in_words import counted, listed
from core.lessons.naming import step_unnamed
from core.lessons.numbers_said import unchecked_numbers
from core.object_order.clipping import PLANES
from core.object_order.culling import CROSSING, INSIDE, OUTSIDE
from core.object_order.pipeline import STAGES
from core.scene import Mesh, Scene, Sphere

FRUSTUM_STATES = (INSIDE, CROSSING, OUTSIDE)
EVENTS = ("reflect", "refract", "total_reflection")
SPHERE_VALUES = ("a", "b", "c", "half_b", "discriminant", "sqrt_discriminant", "line_distance", "t_near",
                 "t_far", "t", "ray_hit_t", "hit", "origin_inside", "offset_squared", "radius_squared",
                 "point", "classification", "chosen")
TRIANGLE_VALUES = ("t", "alpha", "beta", "gamma", "hit", "point", "determinant")
DEFAULT_TOLERANCE = 1e-9
#: The counts an image-order heat map shows, by name, and where the tracer keeps each per pixel.
HEAT_TESTS = MappingProxyType({"primitive tests": HEAT_PRIM_TESTS, "box and sphere tests": HEAT_BOUNDS_TESTS})

#: Fact kind -> (required fields, optional fields).
KINDS = MappingProxyType({
    "frustum": (("object", "is"), ("beyond",)),
    "back_face": (("object", "triangle"), ("is",)),
    "clipped": (("object", "plane"), ("is",)),
    "zbuffer_keeps": (("pixel", "object"), ("triangle", "after")),
    "ztest_fails": (("pixel", "object"), ("triangle", "after", "is")),
    "seen": (("object",), ("triangle", "is")),
    "blend": (("pixel", "object"), ("after", "equals", "tolerance")),
    "projects_to": (("object", "vertex", "pixel"), ()),
    "first_hit": (("pixel", "object"), ("t", "point", "tolerance", "front_face")),
    "shadow": (("pixel", "object"), ("light", "is")),
    "ray_event": (("pixel", "hit", "event"), ("object", "is")),
    "rays": (("pixel", "kind", "count"), ()),
    "primitive_tests": (("pixel", "count"), ("is",)),
    "tests_per_pixel": (("accel", "fewer_than"), ("tests", "is")),
    "changes_picture": (("stage",), ("is",)),
    "same_surfaces": ((), ("is",)),
    "ray_sphere": (("origin", "center", "radius", "value", "equals"), ("end", "direction", "tolerance")),
    "ray_triangle": (("origin", "direction", "a", "b", "c", "value", "equals"), ("tolerance",)),
})


@dataclass(frozen=True, eq=False)
class Fact:
    """One claim of a step, read and checked against the step's scene.

    Attributes
    ----------
    kind : a key of :data:`KINDS`.
    args : its fields as read (pixels as ``(x, y)`` tuples, vectors as tuples).
    path : where it was written, e.g. ``"steps[1].facts[0]"``.
    """

    kind: str
    args: MappingProxyType
    path: str

    def describe(self) -> str:
        """The fact in words, as a failure line shows it."""
        a = self.args
        yes = a.get("is", True)
        neg = "" if yes else "not "
        if self.kind == "frustum":
            beyond = f", beyond its {a['beyond']} plane" if a.get("beyond") else ""
            return f"{a['object']!r} is {a['is']} the frustum{beyond}"
        if self.kind == "back_face":
            return f"triangle {a['triangle']} of {a['object']!r} is {neg}a back face"
        if self.kind == "clipped":
            return f"{a['object']!r} is {neg}clipped by the {a['plane']} plane"
        after = f" after {counted(a['after'], 'polygon')}" if a.get("after") is not None else ""
        if self.kind == "zbuffer_keeps":
            kept = _part(a) if a["object"] else "the background"
            return f"at pixel {a['pixel']} the z-buffer keeps {kept}{after}"
        if self.kind == "ztest_fails":
            return f"at pixel {a['pixel']} a fragment of {_part(a)} {'fails' if yes else 'never fails'} " \
                   f"the z-test{after}"
        if self.kind == "seen":
            return f"{_part(a)} is {neg}seen in the object-order image"
        if self.kind == "blend":
            return f"at pixel {a['pixel']} {a['object']!r} is blended over what is behind it{after}"
        if self.kind == "projects_to":
            return f"vertex {a['vertex']} of {a['object']!r} projects into pixel {a['pixel']}"
        if self.kind == "first_hit":
            return f"the ray through pixel {a['pixel']} first hits {_name(a['object'])}"
        if self.kind == "shadow":
            light = a.get("light", 0)
            return f"pixel {a['pixel']} is {neg}in the shadow of {a['object']!r} for light {light}"
        if self.kind == "ray_event":
            on = f" on {a['object']!r}" if a.get("object") else ""
            event = a["event"].replace("_", " ")
            return f"a ray of pixel {a['pixel']} does {neg}{event} at hit {a['hit']}{on}"
        if self.kind == "rays":
            return f"pixel {a['pixel']} traces {counted(a['count'], a['kind'] + ' ray')}"
        if self.kind == "primitive_tests":
            return f"the ray through pixel {a['pixel']} makes {'' if yes else 'other than '}" \
                   f"{counted(a['count'], 'primitive test')}"
        if self.kind == "tests_per_pixel":
            return f"{a['accel']} {'costs' if yes else 'does not cost'} fewer {a.get('tests', _TESTS)} " \
                   f"a pixel than {a['fewer_than']}"
        if self.kind == "changes_picture":
            return f"switching {a['stage']} {'changes' if yes else 'does not change'} the object-order image"
        if self.kind == "same_surfaces":
            return f"object order and image order {'' if yes else 'do not '}find the same surface at " \
                   "every pixel"
        tolerance = a.get("tolerance", DEFAULT_TOLERANCE)
        return f"{self.kind} {a['value']} = {show(a['equals'])} (within {tolerance:g})"


_TESTS = "primitive tests"
"""What ``tests_per_pixel`` counts when it does not say."""


def _name(obj) -> str:
    return "nothing (the background)" if obj is None else repr(obj)


def _part(a) -> str:
    if a.get("triangle") is None:
        return repr(a["object"])
    return f"triangle {a['triangle']} of {a['object']!r}"


# --- reading ---------------------------------------------------------------------------------


def read_list(r, value, path: str, read_one, *context) -> tuple:
    """Each item of the list at ``path``, read by ``read_one(r, item, item_path, *context)``; the bad ones
    are left out, their problems in ``r`` (a :class:`core.files.checked_json.Reader`)."""
    items = (read_one(r, item, f"{path}[{k}]", *context) for k, item in enumerate(r.listing(value, path)))
    return tuple(item for item in items if item is not None)


def read_facts(r, value, path: str, scene: Scene | None) -> tuple[Fact, ...]:
    """The ``facts`` list of a step; every problem goes to ``r``."""
    return read_list(r, value, path, read_fact, scene)


_TAGGED = {kind: (("fact", *required), optional) for kind, (required, optional) in KINDS.items()}
"""Each fact's fields with its tag ``fact`` among the required ones."""


def read_tagged(r, value, path: str, key: str, fields, thing: str, kind_word: str) -> tuple[str, dict] | None:
    """An object whose ``key`` names its kind, one of ``fields`` (kind -> (required, optional) field
    names, ``key`` among them): its kind and its fields, checked; None (and problems in ``r``) if bad.
    ``thing`` ("a fact") and ``kind_word`` ("fact") name it in the messages."""
    if not isinstance(value, dict):
        r.add(path, f"expected {thing} object {{\"{key}\": ...}}, got {show(value)}")
        return None
    kind = value.get(key)
    if kind not in fields:
        r.add(join(path, key), f"unknown {kind_word} {show(kind)} (known: {', '.join(fields)})")
        return None
    required, optional = fields[kind]
    return kind, r.fields(value, path, (*required, *optional), required)


def read_fact(r, value, path: str, scene: Scene | None) -> Fact | None:
    """One fact object, checked field by field against ``scene``; None (and problems in ``r``) if bad."""
    tagged = read_tagged(r, value, path, "fact", _TAGGED, "a fact", "fact")
    if tagged is None:
        return None
    kind, d = tagged
    required, optional = KINDS[kind]
    before = len(r.problems)
    args = {}
    for key, v in d.items():
        if key != "fact" and key in required + optional:
            args[key] = _read_arg(r, kind, key, v, join(path, key), scene, d)
    if kind == "ray_sphere" and ("end" in d) == ("direction" in d):
        r.add(path, 'give either "end" (the lecture\'s segment) or "direction" (a ray), not both or neither')
    if len(r.problems) > before or any(key not in d for key in required):
        return None
    return Fact(kind, MappingProxyType(args), path)


def _read_arg(r, kind: str, key: str, v, path: str, scene: Scene | None, d: dict):
    if key == "object":
        if v is None and kind in ("first_hit", "zbuffer_keeps"):
            return None
        return read_object_name(r, v, path, scene)
    if key == "pixel":
        return read_pixel(r, v, path, scene)
    if key == "is":
        if kind == "frustum":
            return r.choice(v, path, FRUSTUM_STATES, "frustum state")
        if not isinstance(v, bool):
            r.add(path, f"expected true or false, got {show(v)}")
        return v
    if key in ("triangle", "vertex"):
        return read_part_index(r, v, path, object_named(scene, d.get("object")), key)
    if key in ("after", "light", "hit", "count"):
        got = r.integer(v, path)
        low = 1 if key == "hit" else 0
        if got is not None and got < low:
            r.add(path, f"must be >= {low}, got {got}")
        if key == "light" and got is not None and scene is not None and got >= len(scene.lights):
            r.add(path, f"the scene has {counted(len(scene.lights), 'light')}, numbered from 0; got {got}")
        return got
    if key == "plane":
        return r.choice(v, path, PLANES, "plane")
    if key == "beyond":
        if d.get("is") != "outside":
            r.add(path, f"only an object outside the frustum lies beyond one of its planes; \"is\" is "
                        f"{show(d.get('is'))}")
        return r.choice(v, path, PLANES, "plane")
    if key == "event":
        return r.choice(v, path, EVENTS, "event")
    if key == "kind":
        return r.choice(v, path, RAY_KINDS, "ray kind")
    if key in ("accel", "fewer_than"):
        return r.choice(v, path, tuple(ACCEL_CODES), "acceleration method")
    if key == "tests":
        return r.choice(v, path, tuple(HEAT_TESTS), "count")
    if key == "stage":
        return r.choice(v, path, STAGES, "stage")
    if key == "front_face":
        if not isinstance(v, bool):
            r.add(path, f"expected true or false, got {show(v)}")
        return v
    if key == "t":
        return r.number(v, path)
    if key in ("tolerance", "radius"):
        return r.number(v, path, ge=0) if key == "tolerance" else r.number(v, path, gt=0)
    if key == "value":
        return r.choice(v, path, SPHERE_VALUES if kind == "ray_sphere" else TRIANGLE_VALUES, "value")
    if key == "equals":
        if isinstance(v, (bool, str)):
            return v
        if isinstance(v, list):
            return r.vector(v, path)
        return r.number(v, path)
    return r.vector(v, path)  # origin, end, direction, center, point, a, b, c


def read_pixel(r, value, path: str, scene: Scene | None) -> tuple[int, int] | None:
    """A pixel ``[x, y]`` (column and row from the top left) of ``scene``'s image; None (and a
    problem in ``r``) if it is not two whole numbers or lies outside the image."""
    if not (isinstance(value, list) and len(value) == 2 and all(is_integer(v) for v in value)):
        r.add(path, f"expected two whole numbers [x, y], got {show(value)}")
        return None
    x, y = value
    if scene is not None:
        w, h = scene.camera.width, scene.camera.height
        if not (0 <= x < w and 0 <= y < h):
            r.add(path, f"pixel ({x}, {y}) lies outside the {w} x {h} image")
            return None
    return int(x), int(y)


def read_object_name(r, value, path: str, scene: Scene | None) -> str | None:
    """The name of one of ``scene``'s objects (any string when the scene is not known); None (and a
    problem in ``r``) if there is no such object."""
    name = r.string(value, path)
    names = [o.name for o in scene.objects] if scene is not None else None
    if name is not None and names is not None and name not in names:
        r.add(path, f"no object {name!r} in the scene (objects: {', '.join(names)})")
        return None
    return name


_PARTS = {"triangle": "triangles", "vertex": "vertices"}


def read_part_index(r, value, path: str, obj, part: str) -> int | None:
    """The number of a ``part`` (``"triangle"`` or ``"vertex"``) of the mesh ``obj`` (any whole number
    when ``obj`` is not known); None (and a problem in ``r``) if ``obj`` has no such part."""
    index = r.integer(value, path)
    if index is None or obj is None:
        return index
    if isinstance(obj, Sphere):
        r.add(path, f"{obj.name!r} is an analytic sphere: it has no {_PARTS[part]}")
        return None
    count = len(obj.triangles if part == "triangle" else obj.vertices)
    if not 0 <= index < count:
        r.add(path, f"must be in [0, {count - 1}] ({obj.name!r} has {count}), got {index}")
        return None
    return index


def object_named(scene: Scene | None, name):
    """The object of ``scene`` called ``name``, or None (also when the scene is not known)."""
    if scene is None:
        return None
    return next((o for o in scene.objects if o.name == name), None)


# --- checking --------------------------------------------------------------------------------


class StepPipelines:
    """What the pipelines compute for one step's scene and settings, each at most once.

    Attributes
    ----------
    step : the :class:`core.lessons.lesson_file.LessonStep`.
    """

    def __init__(self, step):
        self.step = step
        self._raster = None
        self._trees: dict[tuple[int, int], object] = {}
        self._traced: dict[str, object] = {}

    @property
    def raster(self):
        """The object-order result with every fragment recorded."""
        if self._raster is None:
            from dataclasses import replace

            from core.object_order.pipeline import render_raster

            self._raster = render_raster(self.step.scene, replace(self.step.object_order, record_steps=True))
        return self._raster

    def tree(self, pixel):
        """The ray tree of ``pixel`` with the step's image-order settings."""
        if pixel not in self._trees:
            from core.image_order.ray_tree import trace_pixel

            self._trees[pixel] = trace_pixel(self.step.scene, *pixel, self.step.image_order)
        return self._trees[pixel]

    def traced(self, accel: str | None = None):
        """The whole image traced with the step's image-order settings and the acceleration method
        ``accel`` (the step's by default), each pixel's intersection tests counted."""
        accel = accel or self.step.image_order.accel
        if accel not in self._traced:
            from dataclasses import replace

            from core.image_order.ray_tracing import render_trace

            settings = replace(self.step.image_order, accel=accel)
            self._traced[accel] = render_trace(self.step.scene, settings, heat=True)
        return self._traced[accel]

    def heat(self, accel: str) -> np.ndarray:
        """Each pixel's intersection tests (H, W, HEAT_SIZE), the whole image traced with the step's
        image-order settings and the acceleration method ``accel``."""
        return self.traced(accel).heat

    def object_index(self, name: str) -> int:
        return [o.name for o in self.step.scene.objects].index(name)


def check_step(step, pipelines: StepPipelines | None = None) -> list[tuple[Fact, str]]:
    """Every fact of ``step`` that does not hold, with what the pipelines computed instead."""
    pipelines = pipelines or StepPipelines(step)
    failures = []
    for fact in step.facts:
        holds, computed = check_fact(fact, pipelines)
        if not holds:
            failures.append((fact, computed))
    return failures


def check_fact(fact: Fact, p: StepPipelines) -> tuple[bool, str]:
    """Decide ``fact`` for the step of ``p``: (holds, what was computed, in words)."""
    return _CHECKS[fact.kind](fact.args, p)


def _frustum(a, p):
    r = p.raster
    if r.objects is None:
        return False, "frustum culling is switched off in this step"
    index = p.object_index(a["object"])
    state = r.objects.state[index]
    beyond = _planes_beyond(r.objects, index)
    where = f", beyond its {listed(beyond)} plane{'s' if len(beyond) > 1 else ''}" if beyond else ""
    holds = state == a["is"] and a.get("beyond") in (None, *beyond)
    return holds, f"{a['object']!r} is {state} the frustum{where}"


def _planes_beyond(culling, index: int) -> tuple[str, ...]:
    """The frustum planes whose outside holds object ``index``'s whole bounding sphere (in the
    order of :data:`core.object_order.clipping.PLANES`); one at least for an object culled as
    outside, none for the others."""
    distance, radius = culling.distance[index], culling.radius[index]
    return tuple(plane for plane, d in zip(PLANES, distance, strict=True) if d < -radius)


def _back_face(a, p):
    r = p.raster
    face = r.face_index(p.object_index(a["object"]), a["triangle"])
    back = bool(r.faces.culled[face])
    facing = float(r.faces.facing[face])
    return back == a.get("is", True), f"{'a back' if back else 'a front'} face (facing value {facing:+.3g})"


def _clip_planes(p, obj_index: int) -> set[str]:
    """The frustum planes that cut the object's clipped polygons."""
    r = p.raster
    polygons = r.clipping.polygons
    lo, hi = r.face_offsets[obj_index], r.face_offsets[obj_index + 1]
    faces = polygons.face[polygons.clipped & (polygons.face >= lo) & (polygons.face < hi)]
    if not len(faces):
        return set()
    from core.object_order.clipping import boundary_distances

    mesh = r.meshes[obj_index]
    corners = mesh.vertices[mesh.triangles[np.unique(faces) - lo]]  # (F, 3, 3) world
    clip = np.concatenate([corners, np.ones((*corners.shape[:2], 1))], axis=-1) @ (
        r.clip_from_view @ r.view_from_world).T
    outside = (boundary_distances(clip) < 0).any(axis=(0, 1))
    return {plane for plane, out in zip(PLANES, outside, strict=True) if out}


def _clipped(a, p):
    planes = _clip_planes(p, p.object_index(a["object"]))
    computed = (f"clipped by the {listed(sorted(planes))} plane{'s' * (len(planes) > 1)}" if planes
                else "not clipped")
    return (a["plane"] in planes) == a.get("is", True), computed


def events_before(p: StepPipelines, pixel, after: int | None) -> tuple:
    """The fragments that reached ``pixel`` in the first ``after`` polygons (default: the step's
    ``zbuffer_step``, else all), as :meth:`core.object_order.step_history.StepHistory.pixel_history`."""
    r = p.raster
    if r.history is None or not r.history.n_steps:
        return ()
    after = _after(p, after)
    return tuple(e for e in r.history.pixel_history(*pixel) if e.polygon < after)


def _after(p: StepPipelines, after: int | None) -> int:
    if after is not None:
        return after
    n = p.raster.history.n_steps if p.raster.history is not None else 0
    return p.step.zbuffer_step if p.step.zbuffer_step is not None else n


def _events(a, p):
    return events_before(p, a["pixel"], a.get("after")), _after(p, a.get("after"))


def _object_name(p, index: int) -> str:
    return p.step.scene.objects[index].name


def _is_part(a, p, object_index: int, triangle_index: int) -> bool:
    """The fragment's polygon is the fact's object (and triangle, when it names one)."""
    return _object_name(p, object_index) == a["object"] and a.get("triangle") in (None, triangle_index)


def _zbuffer_keeps(a, p):
    events, after = _events(a, p)
    kept = [e for e in events if e.passed]
    if not kept:
        return a["object"] is None, f"after {counted(after, 'polygon')} it keeps the background"
    e = kept[-1]
    holds = a["object"] is not None and _is_part(a, p, e.object_index, e.triangle_index)
    return holds, f"after {counted(after, 'polygon')} it keeps triangle {e.triangle_index} of " \
                  f"{_object_name(p, e.object_index)!r}"


def _ztest_fails(a, p):
    events, after = _events(a, p)
    mine = [e for e in events if _is_part(a, p, e.object_index, e.triangle_index)]
    failed = [e for e in mine if not e.passed]
    if not mine:
        computed = f"no fragment of {_part(a)} reaches the pixel in the first {counted(after, 'polygon')}"
    else:
        computed = ", ".join(f"depth {e.distance:.4g} vs stored {e.stored_distance:.4g}: "
                             f"{'passed' if e.passed else 'failed'}" for e in mine)
    return bool(failed) == a.get("is", True), computed


def _seen(a, p):
    r = p.raster
    h = r.history
    f = h.fragments
    passed = np.flatnonzero(f.passed)
    polygon = np.searchsorted(h.offsets, passed, side="right") - 1
    # The last fragment that passed at a pixel is what the finished image shows there.
    _, last = np.unique(f.pixel[passed][::-1], return_index=True)
    shown = polygon[::-1][last]
    mine = h.object_index[shown] == p.object_index(a["object"])
    if a.get("triangle") is not None:
        mine &= h.triangle_index[shown] == a["triangle"]
    count = int(np.count_nonzero(mine))
    shows = "shows" if count == 1 else "show"
    return (count > 0) == a.get("is", True), f"{counted(count, 'pixel')} {shows} {_part(a)}"


def _blend(a, p):
    events, after = _events(a, p)
    blends = [e for e in events if e.blend is not None and _is_part(a, p, e.object_index, e.triangle_index)]
    if not blends:
        return False, f"no fragment of {a['object']!r} is blended at the pixel in the first " \
                      f"{counted(after, 'polygon')}"
    e = blends[-1]
    b = e.blend
    c0 = b.alpha * np.asarray(b.source) + (1 - b.alpha) * np.asarray(b.destination)
    x, y = a["pixel"]
    memory = p.raster.history.buffers(e.polygon + 1)[0][y, x]  # image memory right after that fragment
    holds = bool(np.allclose(c0, memory, rtol=0, atol=1e-9))
    if "equals" in a:
        holds &= bool(np.max(np.abs(c0 - np.asarray(a["equals"]))) <= a.get("tolerance", DEFAULT_TOLERANCE))
    terms = f"{b.alpha:g} x {_vec(b.source)} + {1 - b.alpha:g} x {_vec(b.destination)}"
    return holds, f"c0 = {terms} = {_vec(c0)}, image memory {_vec(memory)}"


def _projects_to(a, p):
    from core.projection import project_point

    scene = p.step.scene
    obj = object_named(scene, a["object"])
    cam = scene.camera
    point = project_point(obj.vertices[a["vertex"]] if isinstance(obj, Mesh) else obj.center,
                          cam.view_from_world, cam.clip_from_view, cam.width, cam.height)
    if point.pixel is None:
        return False, "it lies behind the eye: no projection"
    got = tuple(int(math.floor(c)) for c in point.pixel)
    return got == tuple(a["pixel"]), f"it lands at ({point.pixel[0]:.2f}, {point.pixel[1]:.2f}), pixel {got}"


def _first_hit(a, p):
    root = p.tree(a["pixel"])
    computed = f"it hits {_name(root.hit_name)}"
    holds = root.hit_name == a["object"]
    if root.hit_name is not None:
        computed += f" at t = {root.t:.6g}, point {_vec(root.point)}, " \
                    f"{'from outside' if root.front_face else 'from inside'}"
        if "t" in a:
            holds &= abs(root.t - a["t"]) <= a.get("tolerance", DEFAULT_TOLERANCE)
        if "point" in a:
            holds &= bool(np.max(np.abs(root.point - a["point"])) <= a.get("tolerance", DEFAULT_TOLERANCE))
        if "front_face" in a:
            holds &= root.front_face == a["front_face"]
    return holds, computed


def _shadow(a, p):
    root = p.tree(a["pixel"])
    light = a.get("light", 0)
    if root.hit_name is None:
        return not a.get("is", True), "the pixel's ray hits nothing: no shadow ray"
    ray = next(c for c in root.children if c.kind == "shadow" and c.light == light)
    blocked = ray.hit_name == a["object"]
    by = f", blocked by {ray.hit_name!r}" if ray.hit_name is not None else ""
    computed = f"at {root.hit_name!r} the shadow ray to light {light}: {ray.status}{by}"
    return blocked == a.get("is", True), computed


def _ray_event(a, p):
    makers = [n for n in p.tree(a["pixel"]).walk()
              if n.kind != "shadow" and n.traced and n.hit is not None and n.generation == a["hit"] - 1
              and a.get("object") in (None, n.hit_name)]
    seen = []
    for n in makers:
        kinds = {c.kind for c in n.children}
        events = {"reflect" if "reflection" in kinds else None, "refract" if "refraction" in kinds else None,
                  "total_reflection" if n.total_internal_reflection else None} - {None}
        seen.append(f"at {n.hit_name!r}: {', '.join(sorted(events)) or 'neither'}")
        if a["event"] in events:
            return a.get("is", True), "; ".join(seen)
    return not a.get("is", True), f"hit {a['hit']} " + ("; ".join(seen) if seen else "is never reached")


def _rays(a, p):
    count = sum(1 for n in p.tree(a["pixel"]).walk() if n.kind == a["kind"] and n.traced)
    return count == a["count"], f"{counted(count, a['kind'] + ' ray')} traced"


def _primitive_tests(a, p):
    tests = p.tree(a["pixel"]).tests
    return (tests == a["count"]) == a.get("is", True), counted(tests, "primitive test")


def _tests_per_pixel(a, p):
    tests = a.get("tests", _TESTS)
    methods = (a["accel"], a["fewer_than"])
    mean = {accel: float(p.heat(accel)[..., HEAT_TESTS[tests]].mean()) for accel in methods}
    fewer = mean[a["accel"]] < mean[a["fewer_than"]]
    return fewer == a.get("is", True), ", ".join(f"{accel} {m:.4g}" for accel, m in mean.items()) + \
        f" {tests} a pixel"


def _changes_picture(a, p):
    from dataclasses import replace

    from core.object_order.pipeline import render_raster

    settings = p.step.object_order
    switched = replace(settings, **{a["stage"]: not getattr(settings, a["stage"])})
    other = render_raster(p.step.scene, switched).color
    differ = int(np.count_nonzero(np.any(other != p.raster.color, axis=-1)))
    state = "off" if getattr(settings, a["stage"]) else "on"
    return (differ > 0) == a.get("is", True), \
        f"switched {state}, {counted(differ, 'pixel')} {'differs' if differ == 1 else 'differ'}"


def _same_surfaces(a, p):
    from core.compare import surfaces_part

    parted = int(np.count_nonzero(surfaces_part(p.raster.depth, p.traced().depth)))
    return (parted == 0) == a.get("is", True), f"they find different surfaces at {counted(parted, 'pixel')}"


def _value(a, result):
    got = getattr(result, a["value"])
    want = a["equals"]
    if isinstance(want, (bool, str)) or got is None or isinstance(got, (bool, np.bool_, str)):
        return got == want, f"{a['value']} = {show(got if not isinstance(got, np.bool_) else bool(got))}"
    tol = a.get("tolerance", DEFAULT_TOLERANCE)
    got_arr = np.atleast_1d(np.asarray(got, dtype=float))
    want_arr = np.atleast_1d(np.asarray(want, dtype=float))
    holds = got_arr.shape == want_arr.shape and bool(np.all(np.abs(got_arr - want_arr) <= tol))
    shown = _vec(got_arr) if got_arr.size > 1 else f"{float(got_arr[0]):.9g}"
    return holds, f"{a['value']} = {shown}"


def solve_intersection(kind: str, a):
    """The worked crossing a ``ray_sphere`` or ``ray_triangle`` fact (or exercise) names."""
    from core.image_order.intersect_sphere import intersect_sphere, intersect_sphere_segment
    from core.image_order.intersect_triangle import intersect_triangle

    if kind == "ray_triangle":
        return intersect_triangle(a["origin"], a["direction"], a["a"], a["b"], a["c"])
    if "end" in a:
        return intersect_sphere_segment(a["origin"], a["end"], a["center"], a["radius"])
    return intersect_sphere(a["origin"], a["direction"], a["center"], a["radius"])


def _ray_sphere(a, p):
    return _value(a, solve_intersection("ray_sphere", a))


def _ray_triangle(a, p):
    return _value(a, solve_intersection("ray_triangle", a))


def _vec(v) -> str:
    return "(" + ", ".join(f"{float(c):.6g}" for c in v) + ")"


_CHECKS = {
    "frustum": _frustum, "back_face": _back_face, "clipped": _clipped, "zbuffer_keeps": _zbuffer_keeps,
    "ztest_fails": _ztest_fails, "seen": _seen, "blend": _blend, "projects_to": _projects_to,
    "first_hit": _first_hit, "shadow": _shadow, "ray_event": _ray_event, "rays": _rays,
    "primitive_tests": _primitive_tests, "tests_per_pixel": _tests_per_pixel, "same_surfaces": _same_surfaces,
    "changes_picture": _changes_picture, "ray_sphere": _ray_sphere, "ray_triangle": _ray_triangle,
}


def check_lesson(lesson) -> list[str]:
    """One line per fact of ``lesson`` that does not hold (lesson, step, fact and what was computed),
    per highlight its step's words do not name (:func:`core.lessons.naming.step_unnamed`) and
    per step or exercise that writes a number none of its facts states
    (:func:`core.lessons.numbers_said.unchecked_numbers`)."""
    lines = []
    for k, step in enumerate(lesson.steps):
        pipelines = StepPipelines(step)
        for fact, computed in check_step(step, pipelines):
            lines.append(f"lesson {lesson.id}, step {k + 1} {step.title!r}, {fact.path} "
                         f"({fact.describe()}): computed {computed}")
        lines += step_unnamed(lesson, k, lambda p=pipelines: p.raster)  # the render its facts used
    return lines + unchecked_numbers(lesson)
