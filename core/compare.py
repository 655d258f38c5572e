"""Compare: two renders of one scene, their difference image, and why they differ.

The lecture renders a scene in two ways.  Object order projects polygons and
keeps the nearest fragment per pixel in a z-buffer (orthographically or in
perspective); image order sends a ray through every pixel and takes its first
hit (ray casting), then follows reflected and refracted rays too (ray
tracing).  This module renders any two of those four *outputs* of a scene
from the same observer and puts them side by side:

- the **difference image**: the absolute difference of the two images in
  linear RGB, per pixel and channel, with its scale (the largest difference,
  in linear RGB units from 0 to 1) and a colour-mapped version for display;
- the **same pixel in every output**: its colour in each and what each
  pipeline found there (the fragments that reached it in the z-buffer, the
  ray tree of the tracer);
- a few **sentences** on what differs and why, chosen from the scene: which
  objects it has, which of them are true spheres, which reflect or transmit
  light, and which lights can be blocked (the effects plan).

This module sits above both halves of the lecture and may use both; neither
half imports it.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass, replace

import numpy as np

from core.image_order.effects_plan import effects_plan
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tracing import TraceResult, render_trace
from core.image_order.ray_tree import RayNode, trace_pixel
from core.in_words import counted, listed
from core.object_order.pipeline import RasterResult, RasterSettings, render_raster
from core.object_order.step_history import PixelEvent
from core.pixel_verdict import DROPPED_BY, PixelVerdict, raster_verdict, trace_verdict
from core.scene import Scene, Sphere
from core.srgb import colormapped

OUTPUTS = {
    "orthographic": "orthographic z-buffer",
    "perspective": "perspective z-buffer",
    "raycast": "ray cast",
    "raytrace": "ray traced",
}
"""The four outputs of a scene, by key, with the title shown for each."""

#: A difference below half an 8-bit step cannot be seen on screen or in a file.
VISIBLE_STEP = 0.5 / 255
#: What the difference image's colours measure, said wherever its colour scale is shown.
#: Short enough to read whole in three lines under the difference image presenting at x2 on 1280 x 720.
DIFFERENCE_UNITS = "max(|ΔR|, |ΔG|, |ΔB|), linear RGB (1\u00a0=\u00a0white − black)"


@dataclass(frozen=True, eq=False)
class Output:
    """One output of a scene: its image and what its pipeline recorded.

    Attributes
    ----------
    name : a key of :data:`OUTPUTS`.
    scene : the scene as rendered (the z-buffer outputs set the camera's projection).
    color : (H, W, 3) float64, the image in linear RGB, [0, 1].
    raster : the object-order result, with its step history (z-buffer outputs).
    trace : the image-order result (ray cast and ray traced outputs).
    settings : the tracer's settings (image-order outputs).
    """

    name: str
    scene: Scene
    color: np.ndarray
    raster: RasterResult | None = None
    trace: TraceResult | None = None
    settings: TraceSettings | None = None

    @property
    def title(self) -> str:
        return OUTPUTS[self.name]

    @property
    def projection(self) -> str:
        return self.scene.camera.projection

    @property
    def depth(self) -> np.ndarray:
        """(H, W) the view depth of the surface each pixel shows, +inf where it shows the background."""
        return self.raster.depth if self.raster is not None else self.trace.depth


SAME_DEPTH = 1e-9
"""Two renders show the same surface at a pixel when their view depths there differ by at most this
part of the larger (float64 rounding parts them by a few 1e-15 on the lecture's scene), or when both
show the background."""


def surfaces_part(depth_a: np.ndarray, depth_b: np.ndarray) -> np.ndarray:
    """(H, W) bool: the pixels where two renders' depth images (:attr:`Output.depth`) show different
    surfaces: one the background and the other not, or depths that differ by more than
    :data:`SAME_DEPTH`.

    >>> surfaces_part(np.array([[2.0, np.inf, 3.0]]), np.array([[2.0, np.inf, np.inf]])).tolist()
    [[False, False, True]]
    """
    far_a, far_b = ~np.isfinite(depth_a), ~np.isfinite(depth_b)
    both = ~far_a & ~far_b
    a, b = np.where(both, depth_a, 0.0), np.where(both, depth_b, 0.0)
    return (far_a != far_b) | (both & (np.abs(a - b) > SAME_DEPTH * np.maximum(np.abs(a), np.abs(b))))


def output_projection(scene: Scene, name: str) -> str:
    """The projection output ``name`` uses: its own for the z-buffers, the observer's for the tracers."""
    return name if name in ("orthographic", "perspective") else scene.camera.projection


def render_output(scene: Scene, name: str, settings: TraceSettings = TraceSettings()) -> Output:
    """Render output ``name`` (a key of :data:`OUTPUTS`) of ``scene`` from its observer.

    The z-buffer outputs keep their step history, so any pixel can be asked
    what reached it; the tracer outputs use ``settings`` with the mode set by
    ``name``.

    Raises
    ------
    ValueError
        For a name that is not one of :data:`OUTPUTS` (naming them).
    """
    if name not in OUTPUTS:
        raise ValueError(f"output must be one of {', '.join(OUTPUTS)}, got {name!r}")
    scene = replace(scene, camera=scene.camera.replace(projection=output_projection(scene, name)))
    if name in ("orthographic", "perspective"):
        result = render_raster(scene, RasterSettings(record_steps=True))
        return Output(name, scene, result.color, raster=result)
    settings = replace(settings, mode=name)
    result = render_trace(scene, settings)
    return Output(name, scene, result.color, trace=result, settings=settings)


@dataclass(frozen=True, eq=False)
class Difference:
    """The absolute difference of two images in linear RGB, and how to show it.

    Attributes
    ----------
    delta : (H, W, 3) float64, ``|a - b|`` per channel, linear RGB units in [0, 1].
    magnitude : (H, W) float64, the largest of the three channels' differences.
    scale : float, the largest difference anywhere (linear RGB units); the top
        of the colour scale (0 when the images are equal).
    colormap : name of the matplotlib colour map.
    colored : (H, W, 3) float64, ``magnitude`` through the colour map, from 0
        (the map's first colour) to ``scale`` (its last), given as linear RGB
        so that :func:`core.srgb.to_srgb8` shows exactly the map's colours.
    """

    delta: np.ndarray
    magnitude: np.ndarray
    scale: float
    colormap: str
    colored: np.ndarray

    @property
    def visible_fraction(self) -> float:
        """Fraction of the pixels that differ by at least half an 8-bit step in some channel."""
        return float(np.mean(self.magnitude >= VISIBLE_STEP))

    def colorbar(self, length: int = 256, thickness: int = 12) -> np.ndarray:
        """The colour scale as a (thickness, length, 3) linear-RGB strip: 0 left, ``scale`` right."""
        ramp = colormapped(np.linspace(0.0, 1.0, length), self.colormap)
        return np.repeat(ramp[None], thickness, axis=0)

    def ticks(self, n: int = 5) -> list[tuple[float, float]]:
        """``n`` labelled points of the scale: (position along the bar in [0, 1], difference there)."""
        return [(float(p), float(p * self.scale)) for p in np.linspace(0.0, 1.0, n)]


def difference(a: np.ndarray, b: np.ndarray, colormap: str = "magma") -> Difference:
    """The difference image of two (H, W, 3) linear-RGB images.

    Raises
    ------
    ValueError
        When the images differ in size.
    """
    a, b = np.asarray(a, dtype=np.float64), np.asarray(b, dtype=np.float64)
    if a.shape != b.shape:
        raise ValueError(f"the images differ in size: {a.shape[1]} x {a.shape[0]} "
                         f"and {b.shape[1]} x {b.shape[0]} pixels")
    delta = np.abs(a - b)
    magnitude = delta.max(axis=2)
    scale = float(magnitude.max()) if magnitude.size else 0.0
    level = magnitude / scale if scale > 0 else np.zeros_like(magnitude)
    return Difference(delta, magnitude, scale, colormap, colormapped(level, colormap))


@dataclass(frozen=True, eq=False)
class PixelReport:
    """One pixel of one output: its colour and what the pipeline found there.

    Attributes
    ----------
    output : the output's key in :data:`OUTPUTS`.
    color : (3,) float64, the pixel's linear RGB.
    verdict : what decided the pixel, in one sentence with its evidence
        (:mod:`core.pixel_verdict`).
    events : the fragments that reached the pixel, in drawing order (z-buffer outputs).
    ray_tree : the pixel's ray tree (tracer outputs).
    """

    output: str
    color: np.ndarray
    verdict: PixelVerdict
    events: tuple[PixelEvent, ...] | None = None
    ray_tree: RayNode | None = None

    @property
    def found(self) -> str:
        """One sentence on what decided the pixel."""
        return self.verdict.sentence


def probe(output: Output, x: int, y: int) -> PixelReport:
    """What output ``output`` has at pixel (column ``x``, row ``y`` from the top-left).

    Raises
    ------
    ValueError
        For a pixel outside the image.
    """
    h, w = output.color.shape[:2]
    if not (0 <= x < w and 0 <= y < h):
        raise ValueError(f"pixel ({x}, {y}) is outside the {w} x {h} image")
    color = output.color[y, x].copy()
    if output.raster is not None:
        events = output.raster.history.pixel_history(x, y)
        return PixelReport(output.name, color, raster_verdict(output.raster, x, y), events=events)
    tree = trace_pixel(output.scene, x, y, output.settings)
    return PixelReport(output.name, color, trace_verdict(tree, output.scene, output.name, x, y),
                       ray_tree=tree)


def why_here(a: Output, b: Output, ra: PixelReport, rb: PixelReport) -> str:
    """Why outputs ``a`` and ``b`` differ at the pixel their reports ``ra`` and ``rb`` read.

    One sentence, chosen from what each found there: different objects under
    different projections, a faceted sphere against a true one, a shadow only
    the tracer computes, a reflection or refraction only ray tracing follows,
    flat shading against shading per hit point.
    """
    va, vb = ra.verdict, rb.verdict
    if a.name == b.name:
        return f"Both sides are the {a.title} image."
    raster = [v for v in (va, vb) if v.mode == "raster"]
    traced = [v for v in (va, vb) if v.mode != "raster"]
    if va.object != vb.object:
        said = f"{a.title} shows {va.object or 'the background'}, {b.title} {vb.object or 'the background'}"
        spheres = [o.name for o in a.scene.objects
                   if isinstance(o, Sphere) and o.name in (va.object, vb.object)]
        if a.projection != b.projection:
            why = f"the {a.projection} and {b.projection} projections put different things on this pixel"
        elif raster and traced and spheres:
            why = (f"the z-buffer draws {listed(spheres, most=4)} as flat triangles, so the outline is a "
                   "polygon inside the true sphere the tracer meets")
        elif raster and raster[0].verdict in DROPPED_BY:
            why = (f"before the z-buffer, {DROPPED_BY[raster[0].verdict]} dropped what reaches this pixel; "
                   "a ray has no such stage")
        else:
            why = "the pixel lies on an edge, which each pipeline's rule decides on its own"
        return f"{said}: {why}."
    if va.object is None:
        return "Both show the background here."
    obj = next(o for o in a.scene.objects if o.name == va.object)
    reasons = []
    if raster and traced:
        blocked = [light for light in traced[0].lights if light.blocked_by]
        if blocked:
            reasons.append("a shadow only the tracer computes ("
                           + "; ".join(f"{light.blocked_by} blocks {light.name}" for light in blocked) + ")")
        if isinstance(obj, Sphere):
            reasons.append(f"a faceted sphere: the z-buffer gives a facet of {obj.name} one flat colour, "
                           "the tracer shades the true sphere's point")
        else:
            reasons.append("flat shading: the z-buffer gives the polygon one colour, the tracer shades "
                           "the hit point itself")
    followed = [v for v in traced if v.mode == "raytrace" and (v.rays["reflection"] or v.rays["refraction"])]
    if len(followed) == 1 and len(traced) + len(raster) == 2 and (raster or traced[0].mode != traced[1].mode):
        reasons.append(f"only ray tracing follows the reflected and refracted rays of {obj.name}")
    if a.projection != b.projection:
        reasons.append(f"the two projections land on other points of {obj.name}")
    if not reasons:
        return f"Both show {obj.name} here, found the same way."
    return f"Both show {obj.name} here; they differ by " + "; ".join(reasons) + "."


def _depths(scene: Scene) -> list[tuple[float, str]]:
    """(distance along the viewing axis of the object's centre, name) for every object, nearest first."""
    cam = scene.camera
    found = []
    for obj in scene.objects:
        centre = np.asarray(obj.center) if isinstance(obj, Sphere) else obj.vertices.mean(axis=0)
        found.append((float((centre - np.asarray(cam.eye)) @ cam.forward), obj.name))
    return sorted(found)


def _projection_sentences(scene: Scene, pa: str, pb: str) -> list[str]:
    if pa == pb:
        return [f"Both use {pa} projection, so every object lands on the same pixels; what differs "
                "is how each pipeline colours them."]
    cam = scene.camera
    eye = ", ".join(f"{v:g}" for v in cam.eye)
    sentence = (f"The {pa if pa == 'orthographic' else pb} side projects along parallel rays, so an object "
                f"keeps its size at any distance and {cam.ortho_height:g} units of height fill the image; "
                f"the other side's rays converge in the eye at ({eye}) with a {cam.fov_y_deg:g} degree "
                "viewing angle, so distant things shrink towards the centre")
    depths = _depths(scene)
    if len(depths) >= 2 and depths[-1][0] - depths[0][0] > 1e-9:
        sentence += f" and {depths[0][1]}, the nearest object, looks larger beside {depths[-1][1]}"
    return [sentence + "."]


def _surfaces_found(raster: Output, tracer: Output) -> str:
    parted = int(np.count_nonzero(surfaces_part(raster.depth, tracer.depth)))
    if parted == 0:
        return "both find the same surface at every pixel, at the same depth."
    return f"both find the same surface at the same depth at every pixel but {counted(parted, 'pixel')}."


def _zbuffer_against_tracer(scene: Scene, raster: Output, tracer: Output) -> list[str]:
    stats = raster.raster.stats
    same = raster.projection == tracer.projection
    drawn = stats["polygons_drawn"]
    polygons = "its one polygon" if drawn == 1 else f"all {drawn:,} polygons"
    sentences = [
        f"The z-buffer removes hidden surfaces by drawing {polygons} and "
        f"keeping at each pixel the nearest fragment ({stats['fragments_failed']:,} of "
        f"{stats['fragments_generated']:,} fragments failed the z-test); the tracer keeps the first hit "
        "along each primary ray instead, so " + (
            _surfaces_found(raster, tracer) if same else
            "with one projection they would find the same visible surfaces.")]
    spheres = [i for i, o in enumerate(scene.objects) if isinstance(o, Sphere)]
    if spheres:
        facets = len(raster.raster.meshes[spheres[0]].triangles)
        spheres = [scene.objects[i].name for i in spheres]
        sentences.append(
            f"To the tracer {listed(spheres, most=4)} "
            f"{'is a true sphere' if len(spheres) == 1 else 'are true spheres'}"
            f" (it solves the ray-sphere equation exactly); the rasterizer draws each as "
            f"{facets:,} flat triangles, so outlines are polygons and the shading steps from "
            "facet to facet.")
    if scene.lights:
        shiny = [o.name for o in scene.objects if o.material.specular > 0]
        sentence = ("The z-buffer gives each polygon one flat colour (ambient and diffuse light at its "
                    "centre), while the tracer shades every hit point on its own")
        sentences.append(sentence + (f", with highlights on {listed(shiny, most=4)}." if shiny else "."))
        plan = effects_plan(scene, tracer.name)
        blockable = [p for p in plan.lights if p.blockable]
        if blockable:
            why = "; ".join(f"light {p.index}: {p.reason.removesuffix(': shadow rays')}" for p in blockable)
            why = f"the effects plan says {why}"
            sentences.append(
                f"Only the tracer casts shadows: from every hit point it sends a shadow ray to each light "
                f"and leaves out a light the ray cannot reach ({why}); the z-buffer lights every polygon "
                "as if nothing stood in the way, so shadowed parts are brighter there.")
        else:
            sentences.append("Nothing in the scene can block its light (the effects plan sends no shadow "
                             "rays), so there are no shadows for the z-buffer to miss.")
    else:
        sentences.append("The scene has no light, so both pipelines light every surface with ambient "
                         "light only.")
    return sentences


def _tracing_sentences(scene: Scene, other: str) -> list[str]:
    """What ray tracing adds compared with ``other`` (a z-buffer output or ``"raycast"``)."""
    mirrors = [o.name for o in scene.objects if o.material.reflectivity > 0]
    glass = [o for o in scene.objects if o.material.transparency > 0]
    other_title = "ray casting" if other == "raycast" else "the z-buffer"
    sentences = []
    if mirrors:
        one = len(mirrors) == 1
        sentences.append(
            f"Only ray tracing follows reflected rays (angle of reflection = angle of incidence), so "
            f"{listed(mirrors, most=4)} {'shows' if one else 'show'} the scene around "
            f"{'it' if one else 'them'}; "
            f"{other_title} paints {'it' if one else 'them'} in {'its' if one else 'their'} own colour.")
    if glass:
        iors = ", ".join(f"{o.material.ior:g}" for o in glass)
        instead = ("stops at their surface as if they were opaque" if other == "raycast" else
                   "blends them over what lies behind with their opacity, "
                   "c0 = alpha_s cs + (1 - alpha_s) cd, without bending anything")
        sentences.append(
            f"Ray tracing bends the rays that pass through {listed([o.name for o in glass], most=4)} "
            f"(Snell's law, "
            f"refractive index {iors}) and splits the light between reflection and refraction by the "
            f"Fresnel equations; {other_title} {instead}.")
    if not sentences:
        beyond = "the first hits and shadow rays" if scene.lights else "the first hits"
        sentences.append(f"No material reflects or transmits light, so ray tracing sends no rays beyond "
                         f"{beyond} of ray casting.")
    return sentences


def explain(a: Output, b: Output, diff: Difference | None = None) -> tuple[str, ...]:
    """A few sentences on what differs between outputs ``a`` and ``b`` of one scene, and why.

    The sentences are chosen from the scene: the projections of the two
    outputs, its spheres, its lights and what can block them (the effects
    plan), its mirrors and its glass; ``diff`` adds how much differs.
    """
    scene = a.scene
    if a.name == b.name:
        return (f"Both sides are the {a.title} image, so the difference is zero at every pixel.",)
    sentences = _projection_sentences(scene, a.projection, b.projection)
    rasters = [o for o in (a, b) if o.raster is not None]
    tracers = [o for o in (a, b) if o.trace is not None]
    if len(rasters) == 1:
        sentences += _zbuffer_against_tracer(scene, rasters[0], tracers[0])
    elif not rasters:
        sent = " and send the same shadow rays" if scene.lights else ""
        sentences.append(f"Ray casting and ray tracing find the same first hits{sent}; they part where "
                         "ray tracing follows the light further.")
    else:
        sentences.append("The same z-buffer draws both, so shading and hidden surfaces are decided alike; "
                         "every difference comes from the projection.")
    names = {a.name, b.name}
    if "raytrace" in names:
        sentences += _tracing_sentences(scene, (names - {"raytrace"}).pop())
    if diff is not None:
        sentences.append(f"The images differ visibly at {100 * diff.visible_fraction:.1f}% of the pixels; "
                         f"the largest difference is {diff.scale:.3f} (linear RGB, 0 to 1).")
    return tuple(sentences)


@dataclass(frozen=True, eq=False)
class Comparison:
    """Two outputs of one scene, their difference image and the explanation."""

    a: Output
    b: Output
    difference: Difference
    explanation: tuple[str, ...]

    def pixel(self, x: int, y: int) -> tuple[PixelReport, PixelReport]:
        """The same pixel (column ``x``, row ``y``) in both outputs."""
        return probe(self.a, x, y), probe(self.b, x, y)


def compare(scene: Scene, a: str, b: str, settings: TraceSettings = TraceSettings(),
            colormap: str = "magma", carry_on: Callable[[], bool] | None = None) -> Comparison | None:
    """Render outputs ``a`` and ``b`` (keys of :data:`OUTPUTS`) of ``scene`` and compare them.

    ``carry_on()``, if given, is asked once output ``a`` is rendered (a moment
    to report progress); when it answers False, ``b`` is not rendered and the
    result is ``None``.
    """
    first = render_output(scene, a, settings)
    if carry_on is not None and not carry_on():
        return None
    second = first if b == a else render_output(scene, b, settings)
    diff = difference(first.color, second.color, colormap)
    return Comparison(first, second, diff, explain(first, second, diff))
