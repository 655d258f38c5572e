"""The ray tree of one pixel: every ray, what it hit, and how the colours combine.

The lecture's ray tracing has two stages.  First the rays: the primary ray
hits A, is reflected to B, refracted there to C...  Then the colours, from
the last hits back to the first: "at first find the colour of point C, then
the colour of point B (including the refracted ray) and finally the colour of
point A".  :func:`trace_pixel` records both stages as a tree of
:class:`RayNode`: each node's colour is its local colour plus its children's
colours times their coefficients, and :meth:`RayNode.explain` writes that
combination out number by number.

The tree is computed with the very kernels of the full render
(:func:`core.image_order.kernels.closest_hit.closest_hit`,
:func:`core.image_order.kernels.shade.shade_hit`), so the root's colour clipped to
``[0, 1]`` equals the rendered pixel.
"""

from __future__ import annotations

from collections.abc import Iterator
from dataclasses import dataclass

import numpy as np

from core.image_order import flat_layout
from core.image_order.effects_plan import effects_plan
from core.image_order.flat_scene import TraceSettings, kernel_inputs, trace_scene
from core.image_order.grid_of_cuboids import cells_on_ray
from core.image_order.ray_casting import primary_ray
from core.scene import Scene

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).

KINDS = ("primary", "shadow", "reflection", "refraction")

LIGHT_STATUS = {  # what a shadow ray did (RayNode.status), by the kernels' status code
    flat_layout.LIGHT_BEHIND: "light behind the surface: no shadow ray",
    flat_layout.LIGHT_UNBLOCKABLE: "nothing can block this light: no shadow ray needed",
    flat_layout.LIGHT_REACHED: "reached the light",
    flat_layout.LIGHT_BLOCKED: "blocked: in shadow",
}
_CHILD_STATUS = {
    flat_layout.CHILD_DEPTH_LIMIT: "not traced: depth limit reached",
    flat_layout.CHILD_TOO_WEAK: "not traced: weight below min_weight",
}


@dataclass(frozen=True, eq=False)
class RayNode:
    """One ray of a pixel's ray tree.

    Attributes
    ----------
    kind : ``"primary"``, ``"shadow"``, ``"reflection"`` or ``"refraction"``.
    generation : int, 0 for the primary ray, +1 per reflection or refraction
        (a shadow ray has its parent's generation).
    traced : bool, the ray was really traced (False for rays the depth limit,
        the minimum weight or the effects plan left out; they are listed so the
        reason can be shown).
    status : str, what happened, in words.
    origin, direction : (3,) float64, world space; ``direction`` is unit length.
    t_min, t_max : float, the part of the ray searched (``t_max`` is the
        distance to the light for a shadow ray, the far plane for a primary ray).
    hit : int or None, index into ``scene.objects`` of the first object met.
    hit_name : str or None, its name.
    t : float or None, distance to that hit along the ray.
    point : (3,) float64 or None, the hit point (on the surface).
    normal : (3,) float64 or None, unit surface normal there, facing the ray.
    front_face : bool or None, the ray arrived from outside the object.
    local_color : (3,) float64 or None, Phong colour of the hit from the
        unblocked lights (the sum of the shadow children's colours plus ``ambient``).
    ambient : (3,) float64 or None, the ambient part of ``local_color``.
    fresnel : (R, T) or None, reflectance and transmittance at a transparent surface.
    total_internal_reflection : bool.
    k_reflect, k_refract : float, coefficients of the reflected and refracted
        children's colours.
    coefficient : float, this ray's factor in its parent's colour (1 for the
        primary ray; for a shadow ray 1: its colour is already a part of the
        parent's local colour).
    weight : float, this ray's weight in the pixel (product of the
        coefficients from the root).
    color : (3,) float64, the colour this ray returns, not clipped: the
        background on a miss, else ``local + k_reflect C_reflect + k_refract C_refract``;
        for a shadow ray the light's contribution to the local colour (0 when blocked).
    light : int or None, the light a shadow ray goes to.
    tests, bounds_tests : int, primitive tests this ray took, and its box and sphere tests
        (bounding spheres, BVH boxes and the grid's cells walked, as the heat map counts them).
    cells : (K, 3) int64 or None, grid cells the ray walked (grid methods).
    children : tuple of RayNode, shadow rays first, then reflection, then refraction.
    """

    kind: str
    generation: int
    traced: bool
    status: str
    origin: np.ndarray
    direction: np.ndarray
    t_min: float
    t_max: float
    hit: int | None = None
    hit_name: str | None = None
    t: float | None = None
    point: np.ndarray | None = None
    normal: np.ndarray | None = None
    front_face: bool | None = None
    local_color: np.ndarray | None = None
    ambient: np.ndarray | None = None
    fresnel: tuple[float, float] | None = None
    total_internal_reflection: bool = False
    k_reflect: float = 0.0
    k_refract: float = 0.0
    coefficient: float = 1.0
    weight: float = 1.0
    color: np.ndarray = None
    light: int | None = None
    tests: int = 0
    bounds_tests: int = 0
    cells: np.ndarray | None = None
    children: tuple[RayNode, ...] = ()

    @property
    def pixel_color(self) -> np.ndarray:
        """``color`` clipped to ``[0, 1]``: for the root, the pixel's colour."""
        return np.clip(self.color, 0.0, 1.0)

    def walk(self) -> Iterator[RayNode]:
        """This node and all below it, depth first."""
        yield self
        for child in self.children:
            yield from child.walk()

    def colour_order(self, path: str | None = None) -> Iterator[tuple[str, RayNode]]:
        """The order of the second stage: every traced ray but the shadow rays, children before
        their parent, so the last hits come first (Fig. VII.11: C, then B, then A).

        Each ray comes with its path from this node, the kinds joined by ``/``, e.g.
        ``"primary/refraction/reflection"`` (a ray has at most one reflected and one refracted child).
        """
        path = path or self.kind
        for child in self.children:
            yield from child.colour_order(f"{path}/{child.kind}")
        if self.kind != "shadow" and self.traced:
            yield path, self

    def explain(self) -> list[str]:
        """The second stage of ray tracing: colours from the last hits back to the first.

        One line per traced ray, in :meth:`colour_order`, e.g.
        ``reflection (gen 1) at mirror ball: C = local (0.1, 0.1, 0.1) +
        0.85 x (0.5, 0.2, 0.1) = (0.525, 0.27, 0.185)``.
        """
        return [node._colour_line() for _, node in self.colour_order()]

    def _colour_line(self) -> str:
        label = f"{self.kind} (gen {self.generation})"
        if self.hit is None:
            return f"{label} hits nothing: C = background {_rgb(self.color)}"
        terms = [f"local {_rgb(self.local_color)}"]
        for child in self.children:
            if child.kind != "shadow" and child.traced:
                terms.append(f"{child.coefficient:.3g} x {_rgb(child.color)}")
        return f"{label} at {self.hit_name}: C = " + " + ".join(terms) + f" = {_rgb(self.color)}"


def _rgb(c) -> str:
    return "(" + ", ".join(f"{v:.3g}" for v in c) + ")"


def trace_pixel(scene: Scene, x: int, y: int, settings=None) -> RayNode:
    """The ray tree of pixel ``(x, y)`` (column, row from the top-left) of ``scene``'s camera.

    Parameters
    ----------
    scene : Scene
    x, y : int, pixel coordinates (``0 <= x < width``, ``0 <= y < height``).
    settings : core.image_order.ray_tracing.TraceSettings, optional (the default settings).

    Returns
    -------
    RayNode, the primary ray with everything below it.
    """

    settings = settings or TraceSettings()
    cam = scene.camera
    if not (0 <= x < cam.width and 0 <= y < cam.height):
        raise ValueError(f"pixel ({x}, {y}) lies outside the {cam.width} x {cam.height} image")
    flat = trace_scene(scene)
    structure, _, _ = flat.geometry.accel(settings.accel)
    plan = effects_plan(scene, settings.mode)
    k = kernel_inputs(scene, settings, plan, flat, structure)
    tracer = _Tracer(scene, settings, flat, structure, k)
    o, d, t_min, t_max = primary_ray(k.cam, float(x), float(y))
    return tracer.trace("primary", o, d, t_min, t_max, 0, 1.0, 1.0)


class _Tracer:
    """Follows one pixel's rays with the render's kernels, building :class:`RayNode` s."""

    def __init__(self, scene, settings, flat, structure, k):
        self.scene, self.k, self.structure, self.names = scene, k, structure, flat.names
        from core.image_order.kernels.render import make_scratch

        self.prim_object = flat.geometry.prim_object
        self.scratch = make_scratch(k.method, flat.geometry.n_prims, k.materials.shape[0], k.bvh_depth)
        self.counters = np.zeros(flat_layout.N_COUNTERS, np.int64)
        self.rec = np.empty(flat_layout.record_size(k.lights.shape[0]))
        self.scaled = settings.offset == "scaled"
        self.t_start = 0.0 if self.scaled else settings.epsilon
        self.background = np.asarray(scene.background, dtype=float)

    def _work(self, before) -> dict:
        delta = self.counters - before
        return {"tests": int(delta[flat_layout.PRIM_TESTS]),
                "bounds_tests": int(delta[flat_layout.BOUNDS_TESTS] + delta[flat_layout.CELLS])}

    def _cells(self, o, d, t_min, t_end):
        from core.image_order.kernels.closest_hit import GRID, GRID_SPHERES

        if self.k.method not in (GRID, GRID_SPHERES):
            return None

        return cells_on_ray(self.structure, o, d, t_min, t_end)

    def trace(self, kind, o, d, t_min, t_max, generation, coefficient, weight) -> RayNode:
        from core.image_order.kernels.closest_hit import closest_hit
        from core.image_order.kernels.shade import shade_hit

        k = self.k
        before = self.counters.copy()
        h = closest_hit(k.method, o, d, t_min, t_max, False, k.geo, k.grid, k.bvh, self.scratch,
                        self.counters)
        work = self._work(before)
        base = dict(kind=kind, generation=generation, traced=True, origin=np.array(o), direction=np.array(d),
                    t_min=t_min, t_max=t_max, coefficient=coefficient, weight=weight, **work)
        if h[flat_layout.HIT_PRIM] < 0:
            return RayNode(status="hits nothing: background", color=self.background.copy(),
                           cells=self._cells(o, d, t_min, t_max), **base)
        cells = self._cells(o, d, t_min, h[flat_layout.HIT_T])
        rec = self.rec
        shade_hit(o, d, h, weight, generation, k.materials, k.lights, k.opts, k.geo, k.grid, k.bvh,
                  self.scratch, self.counters, rec, True)
        rec = rec.copy()
        children = [self._shadow(rec, i, generation, weight) for i in range(k.lights.shape[0])]
        local = rec[flat_layout.REC_LOCAL:flat_layout.REC_LOCAL + 3].copy()
        color = local.copy()
        for child_kind, at, coef in (("reflection", flat_layout.REC_REFLECT, rec[flat_layout.REC_K_REFLECT]),
                                     ("refraction", flat_layout.REC_REFRACT, rec[flat_layout.REC_K_REFRACT])):
            child = self._child(child_kind, rec, at, coef, generation, weight)
            if child is not None:
                children.append(child)
                if child.traced:
                    color = color + coef * child.color
        obj = int(rec[flat_layout.REC_OBJECT])
        fresnel = None
        if not np.isnan(rec[flat_layout.REC_FRESNEL_R]):
            fresnel = (float(rec[flat_layout.REC_FRESNEL_R]), float(rec[flat_layout.REC_FRESNEL_T]))
        return RayNode(
            status=f"hits {self.names[obj]}", hit=obj, hit_name=self.names[obj],
            t=float(h[flat_layout.HIT_T]),
            point=rec[flat_layout.REC_POINT:flat_layout.REC_POINT + 3].copy(),
            normal=rec[flat_layout.REC_NORMAL:flat_layout.REC_NORMAL + 3].copy(),
            front_face=bool(rec[flat_layout.REC_FRONT] > 0), local_color=local,
            ambient=rec[flat_layout.REC_AMBIENT:flat_layout.REC_AMBIENT + 3].copy(), fresnel=fresnel,
            total_internal_reflection=bool(rec[flat_layout.REC_TIR] > 0),
            k_reflect=float(rec[flat_layout.REC_K_REFLECT]), k_refract=float(rec[flat_layout.REC_K_REFRACT]),
            color=color, cells=cells, children=tuple(children), **base)

    def _child(self, kind, rec, at, coef, generation, weight):
        status = rec[at + flat_layout.CHILD_STATUS]
        if status == flat_layout.CHILD_NONE:
            return None
        o = tuple(float(v) for v in rec[at + flat_layout.CHILD_ORIGIN:at + flat_layout.CHILD_ORIGIN + 3])
        direction = at + flat_layout.CHILD_DIRECTION
        d = tuple(float(v) for v in rec[direction:direction + 3])
        child_weight = float(rec[at + flat_layout.CHILD_WEIGHT])
        if status == flat_layout.CHILD_TRACED:
            return self.trace(kind, o, d, self.t_start, np.inf, generation + 1, float(coef), child_weight)
        return RayNode(kind=kind, generation=generation + 1, traced=False, status=_CHILD_STATUS[int(status)],
                       origin=np.array(o), direction=np.array(d), t_min=self.t_start, t_max=np.inf,
                       coefficient=float(coef), weight=child_weight, color=np.zeros(3))

    def _shadow(self, rec, i, generation, weight) -> RayNode:
        at = flat_layout.REC_LIGHTS + i * flat_layout.LIGHT_REC_SIZE
        status = int(rec[at + flat_layout.LR_STATUS])
        traced = status in (flat_layout.LIGHT_REACHED, flat_layout.LIGHT_BLOCKED)
        blocker = int(rec[at + flat_layout.LR_BLOCKER])
        hit = int(self.prim_object[blocker]) if blocker >= 0 else None
        origin = rec[at + flat_layout.LR_ORIGIN:at + flat_layout.LR_ORIGIN + 3].copy()
        direction = rec[at + flat_layout.LR_DIRECTION:at + flat_layout.LR_DIRECTION + 3].copy()
        distance = float(rec[at + flat_layout.LR_DISTANCE])
        t = float(rec[at + flat_layout.LR_BLOCKER_T]) if hit is not None else None
        work, cells = {"tests": 0, "bounds_tests": 0}, None
        if traced:  # the same query again, to count its work and list its cells
            from core.image_order.kernels.closest_hit import closest_hit
            from core.image_order.kernels.shade import (
                asks_bounds_first,
                asks_its_sphere_first,
                leaves_its_sphere,
                may_be_shadowed,
            )

            k, before = self.k, self.counters.copy()
            o, d = tuple(float(v) for v in origin), tuple(float(v) for v in direction)
            # As the render: from the inside of a sphere the ray tests that sphere first; from the
            # outside it may ask the bounding spheres of the objects that may shadow it; it searches
            # the scene unless either answered.
            front, prim = bool(rec[flat_layout.REC_FRONT] > 0.0), int(rec[flat_layout.REC_PRIM])
            searched = True
            if asks_its_sphere_first(k.method, front, prim, k.geo[flat_layout.GEO_N_SPHERES]):
                searched = leaves_its_sphere(k.geo, prim, o, d, self.t_start, distance, self.counters)[0] < 0
            elif asks_bounds_first(k.method, self.scaled, front):
                searched = may_be_shadowed(k.lights, i, int(rec[flat_layout.REC_OBJECT]), k.geo, o, d,
                                           self.t_start, distance, self.counters)
            if searched:
                closest_hit(k.method, o, d, self.t_start, distance, True, k.geo, k.grid, k.bvh,
                            self.scratch, self.counters)
            work = self._work(before)
            cells = self._cells(o, d, self.t_start, t if t is not None else distance)
        return RayNode(
            kind="shadow", generation=generation, traced=traced, status=LIGHT_STATUS[status],
            origin=origin, direction=direction, t_min=self.t_start, t_max=distance, hit=hit,
            hit_name=self.names[hit] if hit is not None else None, t=t,
            point=origin + t * direction if t is not None else None,
            weight=weight,
            color=rec[at + flat_layout.LR_CONTRIBUTION:at + flat_layout.LR_CONTRIBUTION + 3].copy(),
            light=i, cells=cells, **work)
