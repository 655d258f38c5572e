"""The effects plan: which kinds of rays a scene calls for, decided before tracing.

Simulate only what the scene calls for.  Before a single ray is traced the
scene is read once:

- no reflective and no transparent material: no reflection rays (a
  transparent surface reflects part of the light too, by Fresnel's split);
- no transparent material: no refraction rays and no Fresnel terms;
- no light: no shadow rays (the scene is lit by ambient light only);
- a light that nothing can block: no shadow rays towards it;
- every object opaque: no transparency (blending) pass in object order;
- ray casting mode: first hits and shadow rays only.

When nothing can block a light
------------------------------
A shadow ray from a point ``q`` on object ``Y`` towards light ``L`` is
blocked when some object ``X`` meets the segment ``qL``.  This module proves
"never blocked" conservatively (when in doubt the light keeps its shadow
rays), object pair by object pair:

- ``X = Y`` (self-shadowing) is impossible when ``X`` is convex: an analytic
  sphere, or a mesh with every vertex on or behind the plane of every one of
  its faces (checked for meshes of at most ``CONVEXITY_LIMIT`` vertex-face
  pairs).  From a lit point of a convex solid the segment to the light only
  leaves the solid.
- ``X != Y`` is impossible when the segment keeps clear of ``X``'s bounding
  sphere: every segment ``qL`` lies within ``r_Y`` of the segment from ``Y``'s
  centre to ``L``, so a distance of at least ``r_X + r_Y`` between that segment
  and ``X``'s centre suffices;
- or when ``X`` is flat (all its vertices in one plane), ``L`` lies strictly
  on one side of that plane and all of ``Y`` on that side or in the plane
  (an object resting on the ground): the segment leaves the plane at once,
  if it starts in it at all.

Typical results: one sphere (or one convex mesh) and any number of lights
outside it: no shadow rays at all.  A ground quad under objects, lit from
above: the ground blocks nothing, but the objects still shadow the ground,
so the light keeps its shadow rays.

Which objects can shadow which
------------------------------
The same pair by pair proof also says, for each receiving object, which
objects may block its shadow rays (:attr:`LightPlan.blockers`): on the
lecture scene only the cube and the cone can shadow the ground, and nothing
can shadow the cube or the cone.  A shadow ray from the outside of a convex
receiver (leaving it by the scaled offset of :mod:`core.image_order.ray_offset`)
then first asks those objects' bounding spheres, the lecture's cheap
stand-in (:mod:`core.image_order.bounding_spheres`), and goes through the
scene only when it meets one of them; a ray that meets none reaches the
light, as it would have found by searching the whole scene.  Worked out for
scenes of at most ``PAIRS_LIMIT`` objects.
"""

from __future__ import annotations

import threading
from dataclasses import asdict, dataclass

import numpy as np

from core.image_order.bounding_spheres import bounding_sphere
from core.in_words import listed
from core.scene import Scene, Sphere

MODES = ("raycast", "raytrace")
#: Convexity of a mesh is only checked up to this many vertex x face pairs.
CONVEXITY_LIMIT = 4_000_000
#: Relative tolerance of "on or behind a plane" and "strictly on one side".
_PLANE_TOLERANCE = 1e-9
#: Which objects can shadow which is worked out (every pair) for at most this many objects.
PAIRS_LIMIT = 16


@dataclass(frozen=True)
class LightPlan:
    """Whether shadow rays are traced towards one light.

    Attributes
    ----------
    index : int, index into ``scene.lights``.
    blockable : bool, some object might cast a shadow from this light.
    reason : str, why (in words).
    blockers : tuple of tuples of int, or None
        Per object of the scene (as a receiver), the objects that may cast a shadow on it
        from this light (itself included when it is not convex); ``None`` when not worked
        out (more than ``PAIRS_LIMIT`` objects).
    """

    index: int
    blockable: bool
    reason: str
    blockers: tuple[tuple[int, ...], ...] | None = None


@dataclass(frozen=True)
class EffectsPlan:
    """What a render of a scene has to simulate.

    Attributes
    ----------
    mode : ``"raycast"`` or ``"raytrace"``.
    reflection_rays : bool, reflected rays may be traced.
    refraction_rays : bool, refracted rays may be traced.
    fresnel : bool, Fresnel's split is computed (only at transparent surfaces).
    shadow_rays : bool, at least one light needs shadow rays.
    lights : tuple of LightPlan, one per light.
    transparency_pass : bool, object order must blend transparent objects
        (some object has ``opacity < 1``).
    reasons : tuple of str, one sentence per decision, for the user.
    """

    mode: str
    reflection_rays: bool
    refraction_rays: bool
    fresnel: bool
    shadow_rays: bool
    lights: tuple[LightPlan, ...]
    transparency_pass: bool
    reasons: tuple[str, ...]

    def to_dict(self) -> dict:
        """JSON-ready form."""
        d = asdict(self)
        d["lights"] = [asdict(light) for light in self.lights]
        d["reasons"] = list(self.reasons)
        return d


def effects_plan(scene: Scene, mode: str = "raytrace") -> EffectsPlan:
    """Derive the effects plan of ``scene`` for ``mode`` (see the module notes).

    The last few plans are remembered (by the identity of ``scene.objects``,
    the lights and the mode), so rendering a scene band by band, or moving the
    observer, does not redo the checks.
    """
    if mode not in MODES:
        raise ValueError(f"mode must be one of {MODES}, got {mode!r}")
    key = (id(scene.objects), scene.lights, mode)
    with _lock:
        cached = _recent.get(key)
    if cached is not None and cached[0] is scene.objects:
        return cached[1]
    plan = _derive(scene, mode)
    with _lock:
        _recent[key] = (scene.objects, plan)
        while len(_recent) > _RECENT:
            _recent.pop(next(iter(_recent)))
    return plan


_RECENT = 8
_recent: dict = {}
_lock = threading.Lock()


def _derive(scene: Scene, mode: str) -> EffectsPlan:
    objects = scene.objects
    mirrors = [o.name for o in objects if o.material.reflectivity > 0]
    glass = [o.name for o in objects if o.material.transparency > 0]
    translucent = [o.name for o in objects if o.material.opacity < 1]
    reasons = []
    tracing = mode == "raytrace"
    if not tracing:
        reasons.append("ray casting: first hits and shadow rays only, no reflection or refraction")
    elif mirrors or glass:
        reasons.append(f"reflection rays: {listed(mirrors + glass, most=4)} reflect"
                       + (" (transparent ones by Fresnel's split)" if glass else ""))
    else:
        reasons.append("no reflective or transparent material: no reflection rays")
    if tracing and glass:
        reasons.append(f"refraction rays and Fresnel terms: {listed(glass, most=4)} transparent")
    elif tracing:
        reasons.append("no transparent material: no refraction rays, no Fresnel terms")
    lights = tuple(_light_plan(scene, i) for i in range(len(scene.lights)))
    if not lights:
        reasons.append("no light: no shadow rays, ambient light only")
    reasons += [f"light {p.index}: {p.reason}" for p in lights]
    reasons.append(f"transparency pass in object order: {listed(translucent, most=4)} not opaque"
                   if translucent else "every object opaque: no transparency pass in object order")
    return EffectsPlan(
        mode=mode,
        reflection_rays=tracing and bool(mirrors or glass),
        refraction_rays=tracing and bool(glass),
        fresnel=tracing and bool(glass),
        shadow_rays=any(p.blockable for p in lights),
        lights=lights,
        transparency_pass=bool(translucent),
        reasons=tuple(reasons),
    )


def _light_plan(scene: Scene, index: int) -> LightPlan:
    light = np.asarray(scene.lights[index].position, dtype=float)
    objects = scene.objects
    if not objects:
        return LightPlan(index, False, "nothing in the scene can cast a shadow: no shadow rays")
    spheres = [bounding_sphere(o) for o in objects]
    planes = [_plane(o) for o in objects]
    every_pair = len(objects) <= PAIRS_LIMIT  # else the first pair that may shadow decides
    reason, blockers = None, []
    for y, receiver in enumerate(objects):
        shadowing = []
        if not _is_convex(receiver):
            reason = reason or f"{receiver.name} may shadow itself (not convex): shadow rays"
            shadowing.append(y)
        for x, blocker in enumerate(objects):
            if reason and not every_pair:
                return LightPlan(index, True, reason)
            if x == y or _clear(spheres[x], spheres[y], light) or _beside(planes[x], receiver, light):
                continue
            reason = reason or f"{blocker.name} may shadow {receiver.name}: shadow rays"
            shadowing.append(x)
        blockers.append(tuple(shadowing))
    if not every_pair:
        return LightPlan(index, reason is not None, reason or "nothing can block it: no shadow rays")
    if reason is None:
        return LightPlan(index, False, "nothing can block it: no shadow rays", tuple(blockers))
    return LightPlan(index, True, _pairs(objects, blockers) + ": shadow rays", tuple(blockers))


def _pairs(objects, blockers) -> str:
    """Which objects may shadow which, in words: every pair found, the receivers' lists in turn.

    >>> from core.scene import Sphere
    >>> a, b, c = (Sphere((0.0, 0.0, 0.0), 1.0, name=n) for n in "abc")
    >>> _pairs((a, b, c), ((1, 2), (), (2,)))
    'b and c may shadow a; c may shadow itself (not convex)'
    """
    clauses = []
    for y, found in enumerate(blockers):
        others = [objects[x].name for x in found if x != y]
        if others:
            clauses.append(f"{listed(others, most=4)} may shadow {objects[y].name}")
        if y in found:
            clauses.append(f"{objects[y].name} may shadow itself (not convex)")
    return "; ".join(clauses[:3]) + (f"; and {len(clauses) - 3} more" if len(clauses) > 3 else "")


def _clear(blocker, receiver, light) -> bool:
    """The blocker's bounding sphere keeps clear of every segment from the receiver to the light."""
    (cx, rx), (cy, ry) = blocker, receiver
    axis = light - cy
    length2 = float(axis @ axis)
    s = 0.0 if length2 == 0 else float(np.clip((cx - cy) @ axis / length2, 0.0, 1.0))
    return float(np.linalg.norm(cx - (cy + s * axis))) >= rx + ry


def _plane(obj):
    """``(n, c)`` with unit ``n``, ``n . x = c`` holding for every vertex of a flat mesh; else None."""
    if isinstance(obj, Sphere):
        return None
    normals = obj.normals
    n = normals[0]
    v = obj.vertices
    c = float(v[0] @ n)
    scale = float(np.abs(v).max()) + 1.0
    if np.abs(v @ n - c).max() > _PLANE_TOLERANCE * scale:
        return None
    return n, c


def _beside(plane, receiver, light) -> bool:
    """The light lies strictly on one side of the flat blocker's plane, and all of the receiver on that
    side or in the plane."""
    if plane is None:
        return False
    n, c = plane
    side = float(light @ n) - c
    if isinstance(receiver, Sphere):
        s = float(np.asarray(receiver.center) @ n) - c
        values = np.array([s - receiver.radius, s + receiver.radius])
    else:
        values = receiver.vertices @ n - c
    margin = _PLANE_TOLERANCE * (float(np.abs(light).max()) + 1.0)
    return bool(side > margin and values.min() >= -margin) or bool(side < -margin and values.max() <= margin)


def _is_convex(obj) -> bool:
    """Every vertex lies on or behind the plane of every face (or an analytic sphere)."""
    if isinstance(obj, Sphere):
        return True
    v, normals = obj.vertices, obj.normals
    if len(v) * len(normals) > CONVEXITY_LIMIT:
        return False
    offsets = np.einsum("ij,ij->i", normals, obj.corners[:, 0])
    scale = float(np.abs(v).max()) + 1.0
    return bool((v @ normals.T - offsets).max() <= _PLANE_TOLERANCE * scale)
