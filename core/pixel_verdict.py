"""Why this pixel: one sentence on what decided a pixel, and the evidence behind it.

A picked pixel's full story is long: every fragment that reached it in the
z-buffer (:mod:`core.object_order.step_history`), or every ray of its ray tree
(:mod:`core.image_order.ray_tree`).  The verdict says first, in one sentence,
what decided the pixel, then lists the data the sentence comes from.

Object order (:func:`raster_verdict`):

- ``background``: no polygon covers the pixel;
- ``visible``: a polygon of an object is kept by the z-buffer (the fragments that
  arrived, and which failed the z-test);
- ``blended``: a transparent polygon (alpha_s) over what lies behind it, in the
  order drawn;
- ``culled``: only back faces cover the pixel, and back-face culling dropped them;
- ``frustum-culled``: an object reaches the pixel only from wholly outside the
  frustum: its bounding sphere lies outside one of the frustum's planes (named),
  so frustum culling dropped the whole object before clipping;
- ``clipped``: an object reaches the pixel only outside the frustum (beyond the
  near or the far plane; the plane is named), and clipping cut that part away.

Fragments that never were (dropped by culling, frustum culling or clipping before rasterization)
are found by asking every face whether it covers the pixel centre before
culling and clipping: in homogeneous clip space the pixel's projecting ray is
the line ``x = x_ndc w, y = y_ndc w`` (``w > 0``), which crosses a face's plane
at the barycentric weights ``beta ~ a x b`` with ``a_i = x_i - x_ndc w_i``,
``b_i = y_i - y_ndc w_i`` (Olano and Greer's homogeneous rasterization); the
face covers the pixel when all three weights are >= 0.  Where that point lies
against the frustum's planes is :func:`core.object_order.clipping.boundary_distances`.

Image order (:func:`trace_verdict`): ``miss``, or ``hit`` at a named object at
distance t, lit by some lights and in the shadow of named objects for others;
a mirror whose colour comes in part from its reflected ray; glass, split by
Fresnel into reflected and refracted parts, with total internal reflection
where it happens.

This module sits above both halves of the lecture and reads both; neither
half imports it.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.image_order import flat_layout
from core.image_order.optics import critical_angle_deg
from core.image_order.ray_tree import LIGHT_STATUS, RayNode
from core.in_words import counted, listed
from core.object_order import clipping
from core.object_order.culling import OUTSIDE
from core.object_order.pipeline import RasterResult
from core.scene import Scene
from core.shown_numbers import shown_number

RASTER_VERDICTS = ("background", "visible", "blended", "culled", "frustum-culled", "clipped")
TRACE_VERDICTS = ("miss", "hit")
FATES = ("kept", "overwritten", "failed z-test", "blended", "culled", "frustum-culled", "clipped")
"""What became of a fragment: ``kept`` (its colour is the pixel's, or what a
transparent polygon is blended over), ``overwritten`` (it passed the z-test but a
later fragment replaced it), ``failed z-test``, ``blended`` (a transparent
polygon's fragment mixed in), ``culled`` (its face is a back face, dropped
before rasterization), ``frustum-culled`` (its object's bounding sphere lies
wholly outside a plane of the frustum, so frustum culling dropped the whole
object before clipping), ``clipped`` (its point at this pixel lies outside the
frustum, so the clipped polygon does not reach the pixel)."""
DROPPED_BY = {"culled": "back-face culling", "frustum-culled": "frustum culling", "clipped": "clipping"}
"""The stage of the pipeline that drops, before drawing, what a raster verdict of that kind names."""


@dataclass(frozen=True)
class Fragment:
    """One fragment at the picked pixel, drawn or dropped before drawing.

    Attributes
    ----------
    object : name of its object.
    object_index : index into ``scene.objects``.
    triangle : its face's triangle index within the object's mesh.
    step : the drawing step it was drawn at (1 = first polygon), ``None`` for a
        fragment dropped before rasterization.
    depth : distance along the viewing axis at the pixel (scene units; negative
        behind the eye).
    fate : one of :data:`FATES`.
    plane : for a clipped fragment, the frustum plane it lies outside of; for a
        frustum-culled one, the plane its object's bounding sphere lies wholly
        outside of (:data:`core.object_order.clipping.PLANES`); else ``None``.
    alpha : the polygon's opacity alpha_s.
    """

    object: str
    object_index: int
    triangle: int
    step: int | None
    depth: float
    fate: str
    plane: str | None = None
    alpha: float = 1.0

    @property
    def polygon(self) -> str:
        return f"triangle {self.triangle}"

    def to_dict(self) -> dict:
        return {"object": self.object, "polygon": self.polygon, "triangle": self.triangle,
                "step": self.step, "depth": _finite(self.depth), "fate": self.fate, "plane": self.plane,
                "alpha": self.alpha}


@dataclass(frozen=True)
class LightVerdict:
    """One light seen from the primary ray's hit point.

    Attributes
    ----------
    name : the light's name.
    lit : the light reaches the point (its shadow ray got through, or nothing can block it).
    blocked_by : name of the object the shadow ray hit first, ``None`` when not blocked.
    status : what happened, in words (:data:`core.image_order.ray_tree.LIGHT_STATUS`).
    """

    name: str
    lit: bool
    blocked_by: str | None
    status: str

    def to_dict(self) -> dict:
        return {"name": self.name, "lit": self.lit, "blocked_by": self.blocked_by, "status": self.status}


@dataclass(frozen=True)
class InternalReflection:
    """A ray inside a transparent object that meets its surface beyond the critical angle and is
    reflected whole (no refracted part).

    Attributes
    ----------
    object : the object's name.
    point : (x, y, z) world space, where the ray meets the surface.
    critical_deg : the critical angle asin(1 / ior) of the object's material into air, degrees from
        the normal.
    """

    object: str
    point: tuple[float, float, float]
    critical_deg: float

    def to_dict(self) -> dict:
        return {"object": self.object, "point": list(self.point), "critical_deg": self.critical_deg}


@dataclass(frozen=True)
class PixelVerdict:
    """What decided one pixel, in one sentence, with the data it comes from.

    Attributes
    ----------
    pixel : (column, row) from the top-left.
    mode : ``"raster"``, ``"raycast"`` or ``"raytrace"``.
    verdict : one of :data:`RASTER_VERDICTS` (raster) or :data:`TRACE_VERDICTS`.
    object : name of the object seen at the pixel (the nearest, for a blend), or ``None``.
    sentence : the verdict in words.
    fragments : (raster) every fragment at the pixel: drawn ones in drawing
        order, then those dropped before drawing, nearest first.
    lights : (traced) each light seen from the primary hit, in scene order.
    rays : (traced) rays traced for the pixel, by kind.
    total_internal_reflection : (traced) every total internal reflection in the pixel's ray tree,
        in the order the tree's rays are walked (parents before children).
    """

    pixel: tuple[int, int]
    mode: str
    verdict: str
    object: str | None
    sentence: str
    fragments: tuple[Fragment, ...] | None = None
    lights: tuple[LightVerdict, ...] | None = None
    rays: dict[str, int] | None = None
    total_internal_reflection: tuple[InternalReflection, ...] | None = None

    def to_dict(self) -> dict:
        """JSON-serialisable (no NaN or infinity)."""
        out = {"pixel": list(self.pixel), "mode": self.mode, "verdict": self.verdict,
               "object": self.object, "sentence": self.sentence}
        if self.fragments is not None:
            out["fragments"] = [f.to_dict() for f in self.fragments]
        if self.lights is not None:
            out["lights"] = [light.to_dict() for light in self.lights]
        if self.rays is not None:
            out["rays"] = dict(self.rays)
        if self.total_internal_reflection is not None:
            out["total_internal_reflection"] = [r.to_dict() for r in self.total_internal_reflection]
        return out


def _finite(v: float) -> float | None:
    return float(v) if np.isfinite(v) else None


# --- object order -----------------------------------------------------------


def covering_faces(result: RasterResult, x: int, y: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Every face whose plane's point on pixel ``(x, y)``'s projecting ray lies inside the face.

    Before culling and clipping: the faces as the scene has them, in homogeneous
    clip space (see the module's notes).

    Returns
    -------
    face : (K,) int64, global face numbers (index into ``result.faces``).
    clip : (K, 4) float64, the point on each face at the pixel, clip space (``w > 0``).
    depth : (K,) float64, its distance along the viewing axis (scene units).
    """
    faces = result.faces
    x_ndc = 2.0 * (x + 0.5) / result.history.width - 1.0
    y_ndc = 1.0 - 2.0 * (y + 0.5) / result.history.height
    m = result.clip_from_view
    # Per vertex first (a face's corners are shared), then gathered per face.
    clip_x, clip_y, w = (faces.view @ m[row, :3] + m[row, 3] for row in (0, 1, 3))
    a, b = clip_x - x_ndc * w, clip_y - y_ndc * w
    # A face whose corners all have a > 0 (or all a < 0, b > 0, b < 0) cannot have weights
    # beta >= 0 with sum(beta a) = 0: one bit per sign, kept by a face only if all corners share it.
    signs = ((a > 0) | (a < 0) << 1 | (b > 0) << 2 | (b < 0) << 3).astype(np.uint8)
    corner_signs = signs[faces.triangles]
    maybe = np.flatnonzero((corner_signs[:, 0] & corner_signs[:, 1] & corner_signs[:, 2]) == 0)
    tri = faces.triangles[maybe]
    beta = np.cross(a[tri], b[tri])
    total = beta.sum(axis=1)
    with np.errstate(divide="ignore", invalid="ignore"):
        beta /= total[:, None]
        inside = (total != 0) & np.all(beta >= 0.0, axis=1)
    beta, corners = beta[inside], tri[inside]
    face = maybe[inside]
    view = np.einsum("fk,fkc->fc", beta, faces.view[corners])
    clip = view @ m[:, :3].T + m[:, 3]
    ahead = clip[:, 3] > 0.0  # the projecting ray starts at the eye: the line behind it is not seen
    return face[ahead], clip[ahead], -view[ahead, 2]


def _object_of(result: RasterResult, face: int) -> tuple[int, int]:
    o = int(np.searchsorted(result.face_offsets, face, side="right") - 1)
    return o, int(face - result.face_offsets[o])


def dropped_fragments(result: RasterResult, x: int, y: int) -> tuple[Fragment, ...]:
    """The fragments culling, frustum culling and clipping dropped at pixel ``(x, y)``, nearest first.

    In the pipeline's order: a back face is ``culled`` (with back-face culling
    on) even when its object is outside the frustum too; a face of an object that
    frustum culling dropped whole is ``frustum-culled``; a face whose point at the
    pixel lies outside the frustum is ``clipped``.

    They do not depend on the drawing step, and finding them tests every face of
    the scene (a tenth of a second for a million), so a view scrubbing through the
    steps finds them once per pixel and passes them to :func:`raster_verdict`.
    """
    settings, objects = result.settings, result.objects
    drawn = {result.face_index(e.object_index, e.triangle_index) for e in result.history.pixel_history(x, y)}
    out = []
    face, point, depth = covering_faces(result, x, y)
    distance = clipping.boundary_distances(point)
    for f, d, dist in zip(face.tolist(), depth.tolist(), distance, strict=True):
        if f in drawn:
            continue
        o, t = _object_of(result, f)
        mesh = result.meshes[o]
        alpha = float(mesh.material.opacity)
        if settings.back_face_culling and not result.faces.visible[f]:
            out.append(Fragment(mesh.name, o, t, None, d, "culled", alpha=alpha))
        elif objects is not None and objects.state[o] == OUTSIDE:
            # Outside a plane by more than its radius: the plane the centre lies farthest outside of
            # (culling.ObjectCulling.distance has clipping.PLANES' order).
            out.append(Fragment(mesh.name, o, t, None, d, "frustum-culled",
                                clipping.PLANES[int(np.argmin(objects.distance[o]))], alpha))
        elif dist.min() < 0.0:
            out.append(Fragment(mesh.name, o, t, None, d, "clipped", clipping.PLANES[int(np.argmin(dist))],
                                alpha))
        # Otherwise the face covers the centre only to rounding (the rasterizer's fill rule decided).
    return tuple(sorted(out, key=lambda frag: frag.depth))


def raster_verdict(result: RasterResult, x: int, y: int, step: int | None = None,
                   dropped: tuple[Fragment, ...] | None = None) -> PixelVerdict:
    """What decided pixel ``(x, y)`` (column, row) of an object-order render.

    Parameters
    ----------
    result : a render with its step history (``RasterSettings(record_steps=True)``).
    x, y : the pixel.
    step : only the first ``step`` polygons drawn count (default all: the finished image).
    dropped : :func:`dropped_fragments` of the pixel, when already found.

    Raises
    ------
    ValueError
        For a render without its history, or a pixel outside the image.
    """
    history = result.history
    if history is None:
        raise ValueError("the pixel's verdict needs the render's step history (record_steps=True)")
    events = history.pixel_history(x, y)  # refuses a pixel outside the image
    step = history.n_steps if step is None else step
    names = [m.name for m in result.meshes]
    events = [e for e in events if e.polygon < step]
    passed = [i for i, e in enumerate(events) if e.passed]
    opaque = [i for i in passed if events[i].blend is None]
    kept = opaque[-1] if opaque else None
    fragments = []
    for i, e in enumerate(events):
        fate = ("failed z-test" if not e.passed else "blended" if e.blend is not None
                else "kept" if i == kept else "overwritten")
        fragments.append(Fragment(names[e.object_index], e.object_index, e.triangle_index, e.polygon + 1,
                                  e.distance, fate, alpha=float(history.alpha[e.polygon])))
    dropped = dropped_fragments(result, x, y) if dropped is None else dropped
    fragments = (*fragments, *dropped)
    verdict, obj, sentence = _raster_sentence(result, fragments, events, kept, step)
    return PixelVerdict((x, y), "raster", verdict, obj, sentence, fragments=fragments)


def _capital(text: str) -> str:
    return text[:1].upper() + text[1:]


def _label(f: Fragment) -> str:
    return f"{f.polygon} of {f.object}"


def _raster_sentence(result: RasterResult, fragments, events, kept, step):
    drawn = [f for f in fragments if f.step is not None]
    dropped = [f for f in fragments if f.step is None]
    upto = "" if step >= result.history.n_steps else f"After {counted(step, 'polygon')}: "
    if not drawn:
        if not dropped:
            return ("background", None,
                    upto + "No polygon covers this pixel, so it keeps the background colour.")
        first = dropped[0]
        culled = [f for f in dropped if f.fate == "culled"]
        parts = []
        if culled:
            parts.append(f"only back faces cover this pixel ({listed([_label(f) for f in culled])}), "
                         "turned away from the observer and dropped before drawing")
        for f in dropped:
            if f.fate == "frustum-culled":
                parts.append(f"{f.object} reaches this pixel only {_outside(result, f)}, and its bounding "
                             f"sphere lies wholly outside the {f.plane} plane: frustum culling dropped "
                             "the whole object before clipping")
            elif f.fate == "clipped":
                parts.append(f"{f.object} reaches this pixel only {_outside(result, f)}, clipped away")
        what = {"culled": "Culled", "frustum-culled": f"Culled by the frustum at the {first.plane} plane",
                "clipped": f"Clipped at the {first.plane} plane"}[first.fate]
        return (first.fate, None, upto + f"{what}: " + "; ".join(dict.fromkeys(parts))
                + ", so the pixel keeps the background colour.")
    failed = [f for f in drawn if f.fate == "failed z-test"]
    blended = [f for f in drawn if f.fate == "blended"]
    arrived = f"{len(drawn)} fragment{'s' * (len(drawn) != 1)} arrived"
    if blended:
        top = blended[-1]
        behind = _label(next(f for f in drawn if f.fate == "kept")) if kept is not None else "the background"
        layers = (f" (and {len(blended) - 1} more transparent layer{'s' * (len(blended) > 2)} between, "
                  "drawn far to near)" if len(blended) > 1 else "")
        return ("blended", top.object,
                upto + f"Blended: the transparent {_label(top)} (αs = {top.alpha:.2g}) is mixed over "
                f"{behind}{layers}, c0 = αs·cs + (1 − αs)·cd in the order drawn; {arrived}.")
    winner = next(f for f in drawn if f.fate == "kept")
    if not result.history.z_test:
        return ("visible", winner.object,
                upto + f"{_capital(_label(winner))} was drawn last with the z-test off, so it covers the "
                f"{len(drawn) - 1} fragment{'s' * (len(drawn) != 2)} drawn before it, near or far.")
    if failed:
        lost = f", and {listed([_label(f) for f in failed])} failed the z-test"
    else:
        lost = ", none failed the z-test"
    overwritten = [f for f in drawn if f.fate == "overwritten"]
    if overwritten:
        lost += f"; it replaced the farther {listed([_label(f) for f in overwritten])}"
    return ("visible", winner.object,
            upto + f"{_capital(_label(winner))} is kept by the z-buffer at distance {winner.depth:.3g}: "
            f"{arrived}{lost}.")


def _outside(result: RasterResult, f: Fragment) -> str:
    """Where a clipped or frustum-culled fragment lies against its plane, in words."""
    if f.plane == "near":
        return f"nearer than the near plane ({f.depth:.3g} < {result.history.near:g})"
    if f.plane == "far":
        return f"beyond the far plane ({f.depth:.3g} > {result.history.far:g})"
    return f"outside the {f.plane} plane"


# --- image order ------------------------------------------------------------


def _lights(root: RayNode, scene: Scene) -> tuple[LightVerdict, ...]:
    out = []
    for node in root.children:
        if node.kind != "shadow":
            continue
        blocked = node.status == LIGHT_STATUS[flat_layout.LIGHT_BLOCKED]
        lit = node.status in (LIGHT_STATUS[flat_layout.LIGHT_REACHED],
                              LIGHT_STATUS[flat_layout.LIGHT_UNBLOCKABLE])
        out.append(LightVerdict(scene.lights[node.light].name, lit, node.hit_name if blocked else None,
                                node.status))
    return tuple(out)


def _seen(node: RayNode | None) -> str:
    if node is None:
        return "is not sent"
    if not node.traced:
        return f"is not traced ({node.status.removeprefix('not traced: ')})"
    return "misses everything (background)" if node.hit is None else f"hits {node.hit_name}"


def _child(root: RayNode, kind: str) -> RayNode | None:
    return next((c for c in root.children if c.kind == kind), None)


def trace_verdict(root: RayNode, scene: Scene, mode: str, x: int, y: int) -> PixelVerdict:
    """What decided pixel ``(x, y)`` of a ray-cast or ray-traced image, from its ray tree ``root``.

    ``mode`` is ``"raycast"`` or ``"raytrace"``
    (:func:`core.image_order.ray_tree.trace_pixel` with those settings made ``root``).
    """
    rays = {kind: 0 for kind in ("primary", "shadow", "reflection", "refraction")}
    for node in root.walk():
        if node.traced:
            rays[node.kind] += 1
    if root.hit is None:
        return PixelVerdict((x, y), mode, "miss", None,
                            "The primary ray misses everything between the near and the far plane, so the "
                            "pixel shows the background colour.", lights=(), rays=rays,
                            total_internal_reflection=())
    lights = _lights(root, scene)
    parts = [f"The primary ray hits {root.hit_name} at t = {shown_number(root.t)}"]
    lit = [v.name for v in lights if v.lit]
    if lit:
        parts.append(f"lit by {listed(lit)}")
    for blocker in dict.fromkeys(v.blocked_by for v in lights if v.blocked_by):
        parts.append(f"in the shadow of {blocker} for "
                     f"{listed([v.name for v in lights if v.blocked_by == blocker])}")
    behind = [v.name for v in lights if not v.lit and v.blocked_by is None]
    if behind:
        parts.append(f"facing away from {listed(behind)}")
    if not lights:
        parts.append("no light in the scene: ambient light only")
    sentence = ", ".join(parts)
    reflected, refracted = _child(root, "reflection"), _child(root, "refraction")
    if root.fresnel is not None:
        r, t = root.fresnel
        sentence += (f"; {root.hit_name} is glass, split by Fresnel into R = {r:.3g} reflected and "
                     f"T = {t:.3g} refracted: the reflected ray {_seen(reflected)}, "
                     f"the refracted ray {_seen(refracted)}")
    elif reflected is not None:
        sentence += (f"; {root.hit_name} is a mirror, {root.k_reflect:.0%} of its colour comes from the "
                     f"reflected ray, which {_seen(reflected)}")
    tir = tuple(InternalReflection(n.hit_name, tuple(float(c) for c in n.point),
                                   critical_angle_deg(scene.objects[n.hit].material.ior, 1.0))
                for n in root.walk() if n.total_internal_reflection)
    for name in dict.fromkeys(r.object for r in tir):
        first = next(r for r in tir if r.object == name)
        times = sum(r.object == name for r in tir)
        sentence += (f"; total internal reflection inside {name}: a ray inside meets its surface beyond "
                     f"the critical angle {first.critical_deg:.1f}° at {_point(first.point)}"
                     + (f" ({times} times in all)" if times > 1 else ""))
    return PixelVerdict((x, y), mode, "hit", root.hit_name, sentence + ".", lights=lights, rays=rays,
                        total_internal_reflection=tir)


def _point(p) -> str:
    """``(1, 0.293, 0)``: three digits, and no ``-0`` or ``1e-17`` for what is zero."""
    return "(" + ", ".join(f"{round(c, 9) + 0.0:.3g}" for c in p) + ")"
