"""Exercises: the student predicts, the pipelines answer.

A lesson ends with exercises.  Each one is asked about the scene of one of the
lesson's steps (``"step"``, the last by default) and is checked against what the
pipelines compute for that scene (:mod:`core.lessons.facts`), never against an
answer typed into the file.  Kinds::

    {"kind": "choose_one", "question": "Which polygon does the z-buffer keep at (87, 74)?",
     "choices": ["green", "blue", "yellow"],
     "fact": {"fact": "zbuffer_keeps", "pixel": [87, 74], "object": "$choice"},
     "why": "Blue is the nearest of the three there."}
    {"kind": "click_pixel", "question": "Click a pixel in the cone's shadow.",
     "fact": {"fact": "shadow", "pixel": "$pixel", "object": "cone"}, "why": "..."}
    {"kind": "click_pixel", "question": "Click a pixel where yellow wins over green.",
     "fact": [{"fact": "zbuffer_keeps", "pixel": "$pixel", "object": "green", "after": 2},
              {"fact": "zbuffer_keeps", "pixel": "$pixel", "object": "yellow"}], "why": "..."}
    {"kind": "number", "question": "What is Δ?", "tolerance": 0.5,
     "value": {"of": "ray_sphere", "origin": [2, 1, 2], "end": [10, 6, 6], "center": [6, 4, 6],
               "radius": 10, "value": "discriminant"}, "why": "..."}
    {"kind": "order", "question": "In which order are the panes drawn?",
     "items": ["red pane", "green pane", "blue pane"], "by": "drawing_order", "why": "..."}
    {"kind": "order", "question": "In which order are the colours of A, B and C computed?",
     "items": ["primary", "primary/refraction", "primary/refraction/refraction"],
     "by": "ray_tree_colours", "pixel": [205, 132], "why": "..."}
    {"kind": "pick_picture", "question": "Which picture is the top view?", "view": "top"}

A ``choose_one`` choice is right when its fact (``$choice`` put in) holds; a
lesson check demands exactly one right choice.  A ``click_pixel`` answer is
right when the fact holds at the clicked pixel (``$pixel``), or each fact of a list.  A ``number``'s
``value`` is computed: ``ray_sphere`` / ``ray_triangle`` values (the lecture's
data), ``depth`` (the distance the z-buffer stores at ``pixel`` after ``after``
polygons), ``hit_t`` (the distance to the first hit of ``pixel``'s ray), ``primitive_tests`` (the
triangles and spheres that ray is tested against, :mod:`core.lessons.facts`),
``blend`` (channel ``channel`` of the c0 a transparent ``object`` writes at
``pixel``), ``perspective`` (coordinate ``component``, 0 for x′ and 1 for y′, of where the
lecture's perspective projection puts ``point``, the screen in z = 0 and the eye at z = −``d``:
:func:`core.projection.lecture_image`).  ``order`` ``by`` ``drawing_order`` puts the
named objects in the order object order draws them; ``ray_tree_colours`` puts rays of ``pixel``'s ray
tree, named by their path from the primary ray (``"primary"``,
``"primary/refraction"``, ``"primary/refraction/reflection"``...), in the order
the second stage of ray tracing computes their colours: the last hits first
(Fig. VII.11: C, then B, then A); a lesson check demands that they lie on one
branch, so that one order is right.  ``pick_picture`` offers the four pictures the
Four views tab draws (front, side, top, the observer's) and is right when the
picture picked is the one drawn from the named ``view``; a lesson check
demands that no two pictures look alike.

Variants: an exercise may list ``"variants"`` (pixels, or any JSON values);
``"$at"`` in its fact or value, and ``{at}`` in its question, stand for one of
them, and :func:`variant` draws one from a student's seed, so each student gets
another pixel; the answer is the pipelines' for that draw.  A variant may be an
object: ``"$at.origin"`` and ``{at.origin}`` stand for its ``origin`` (a segment,
its sphere and radius in one variant).  Exercises that name the same ``"draw"``
(and list as many variants) give a student the same draw, so that "What is b?"
asks about the segment "What is a?" gave.  A lesson check answers every variant,
and reports an exercise whose answer a step of its lesson states
(:func:`stated_answers`): the exercise is to apply the step, not to copy it.
"""

from __future__ import annotations

import copy
import random
import re
from dataclasses import dataclass, field
from types import MappingProxyType

import numpy as np

from core.files.checked_json import join, show
from core.lessons import facts as facts_mod
from core.lessons.facts import StepPipelines, check_fact, read_fact, read_list, read_pixel, read_tagged
from core.lessons.naming import says
from core.lessons.numbers_said import writes, written_numbers
from core.projection import lecture_image

KINDS = ("choose_one", "click_pixel", "number", "order", "pick_picture")
VIEWS = ("front", "side", "top", "observer")
"""The pictures of a ``pick_picture`` exercise: :data:`core.object_order.four_views.PANES`."""
PICTURE_SIZE = (160, 120)
"""Width and height (pixels) of each picture to pick from."""
NUMBERS = ("ray_sphere", "ray_triangle", "depth", "hit_t", "primitive_tests", "blend", "perspective")
ORDERS = ("drawing_order", "ray_tree_colours")
RAY_STEPS = ("reflection", "refraction")
"""What may follow ``primary`` in a ray's path (``ray_tree_colours``): the rays whose colours are gathered."""
_FIELDS = {
    "choose_one": (("kind", "question", "choices", "fact"), ("step", "why", "variants", "draw")),
    "click_pixel": (("kind", "question", "fact"), ("step", "why")),
    "number": (("kind", "question", "value", "tolerance"), ("step", "why", "variants", "draw")),
    "order": (("kind", "question", "items", "by"), ("step", "why", "pixel")),
    "pick_picture": (("kind", "question", "view"), ("step", "why")),
}
#: How far apart the pixels are that "show me" tries for a click exercise (every n-th row and column).
SEARCH_STRIDE = 4


@dataclass(frozen=True, eq=False)
class Exercise:
    """One exercise, read and resolved to the step whose scene it asks about.

    Attributes
    ----------
    kind : one of :data:`KINDS`.
    question : str.
    why : str, one sentence shown with the verdict.
    step : int, the lesson step (0-based) whose scene and settings it is asked about.
    args : the kind's fields as read.
    path : where it was written, e.g. ``"exercises[2]"``.
    variants : the exercise drawn with each of its ``variants`` (empty when it has none).
    draw : the name of the draw it shares with other exercises (None: its own).
    """

    kind: str
    question: str
    why: str
    step: int
    args: MappingProxyType
    path: str
    variants: tuple = field(default=())
    draw: str | None = None


def variant(ex: Exercise, seed: int, index: int = 0) -> Exercise:
    """The variant of ``ex`` a student with ``seed`` gets (``index``: the exercise's place, so that
    one seed does not draw the same variant everywhere); ``ex`` itself when it has none."""
    if not ex.variants:
        return ex
    rng = random.Random(f"{seed}/{ex.draw}") if ex.draw else random.Random(seed * 1009 + index)
    return ex.variants[rng.randrange(len(ex.variants))]


_AT = re.compile(r"\{at(?:\.(\w+))?\}")


def _put(value, at):
    """``value`` (JSON) with every ``"$at"`` replaced by ``at`` and every ``"$at.key"`` by ``at[key]``."""
    if value == "$at":
        return at
    if isinstance(value, str) and value.startswith("$at.") and isinstance(at, dict) and value[4:] in at:
        return at[value[4:]]
    if isinstance(value, dict):
        return {k: _put(v, at) for k, v in value.items()}
    if isinstance(value, list):
        return [_put(v, at) for v in value]
    return value


def _shown(at) -> str:
    return "(" + ", ".join(_shown(v) for v in at) + ")" if isinstance(at, list) else str(at)


def _asked_with(question: str, at) -> str:
    """``question`` with ``{at}`` (and ``{at.key}``, for an object) written out."""
    def one(m):
        key = m.group(1)
        if key is None:
            return _shown(at)
        return _shown(at[key]) if isinstance(at, dict) and key in at else m.group(0)
    return _AT.sub(one, question)


@dataclass(frozen=True)
class Verdict:
    """What the student is told: right or wrong, and one sentence why."""

    right: bool
    sentence: str


def _substituted(template, placeholder: str, value):
    """``template`` (a fact object) with ``"$choice"``/``"$pixel"`` replaced by ``value``."""
    out = copy.deepcopy(dict(template))
    for key, v in out.items():
        if v == placeholder:
            out[key] = value
    return out


def read_exercises(r, value, path: str, steps) -> tuple[Exercise, ...]:
    """The lesson's ``exercises`` list; every problem goes to ``r``."""
    read = read_list(r, value, path, _read, steps)
    counts = {}
    for ex in read:
        if ex is not None and ex.draw is not None:
            first = counts.setdefault(ex.draw, (ex.path, len(ex.variants)))
            if first[1] != len(ex.variants):
                r.add(join(ex.path, "variants"), f"draw {ex.draw!r}: {first[0]} lists {first[1]} variants, "
                                                 f"this one {len(ex.variants)}; list as many")
    return read


def _read(r, value, path: str, steps) -> Exercise | None:
    if isinstance(value, dict) and "variants" in value:
        listed = r.listing(value["variants"], join(path, "variants"))
        if not listed:
            r.add(join(path, "variants"), "give at least one variant")
            return None
        base = {k: v for k, v in value.items() if k not in ("variants", "draw")}
        drawn = []
        for i, at in enumerate(listed):
            concrete = _put(base, at)
            for key in ("question", "why"):
                if isinstance(concrete.get(key), str):
                    concrete[key] = _asked_with(concrete[key], at)
            drawn.append(_read(r, concrete, f"{path}.variants[{i}]", steps))
        if None in drawn:
            return None
        draw = r.string(value["draw"], join(path, "draw")) if "draw" in value else None
        first = drawn[0]
        return Exercise(first.kind, first.question, first.why, first.step, first.args, path, tuple(drawn),
                        draw)
    tagged = read_tagged(r, value, path, "kind", _FIELDS, "an exercise", "exercise kind")
    if tagged is None:
        return None
    kind, d = tagged
    required = _FIELDS[kind][0]
    before = len(r.problems)
    question = r.string(d.get("question", ""), join(path, "question")) or ""
    why = r.string(d.get("why", ""), join(path, "why")) or ""
    step = len(steps) - 1
    if "step" in d:
        step = r.integer(d["step"], join(path, "step"))
        if step is not None and not 0 <= step < len(steps):
            r.add(join(path, "step"), f"the lesson has steps 0 to {len(steps) - 1}, got {step}")
            return None
    if step is None or any(key not in d for key in required):
        return None
    scene = steps[step].scene
    args = {}
    if kind == "choose_one":
        listed = r.listing(d["choices"], join(path, "choices"))
        choices = []
        for i, c in enumerate(listed):
            if c is not None and not isinstance(c, (str, bool)):
                r.add(f"{path}.choices[{i}]", f"expected a name, true, false or null, got {show(c)}")
            choices.append(c)
        if len(choices) < 2:
            r.add(join(path, "choices"), "give at least two choices")
        for i, choice in enumerate(choices):  # each choice must make a readable fact
            read_fact(r, _substituted(d["fact"], "$choice", choice), f"{path}.fact (choice {i})", scene)
        args.update(choices=tuple(choices), fact=MappingProxyType(dict(d["fact"])))
    elif kind == "click_pixel":  # one fact, or a list of facts that must all hold
        listed = d["fact"] if isinstance(d["fact"], list) else [d["fact"]]
        many = isinstance(d["fact"], list)
        if not listed:
            r.add(join(path, "fact"), "give at least one fact")
        for i, template in enumerate(listed):
            at = f"{path}.fact[{i}]" if many else join(path, "fact")
            if not isinstance(template, dict) or "$pixel" not in template.values():
                r.add(at, 'the fact must say "pixel": "$pixel" (the clicked pixel)')
            else:
                read_fact(r, _substituted(template, "$pixel", [0, 0]), at, scene)
        args.update(facts=tuple(MappingProxyType(dict(t)) for t in listed if isinstance(t, dict)))
    elif kind == "number":
        args.update(value=_read_number(r, d["value"], join(path, "value"), scene),
                    tolerance=r.number(d["tolerance"], join(path, "tolerance"), ge=0))
    elif kind == "pick_picture":
        if d["view"] not in VIEWS:
            r.add(join(path, "view"), f"unknown view {show(d['view'])} (known: {', '.join(VIEWS)})")
        args.update(view=d["view"])
    else:
        listed = r.listing(d["items"], join(path, "items"))
        items = [r.string(c, f"{path}.items[{i}]") for i, c in enumerate(listed)]
        if d["by"] not in ORDERS:
            r.add(join(path, "by"), f"unknown order {show(d['by'])} (known: {', '.join(ORDERS)})")
        elif d["by"] == "ray_tree_colours":
            _read_ray_paths(r, items, d.get("pixel"), path, scene)
            args["pixel"] = tuple(d["pixel"]) if isinstance(d.get("pixel"), list) else None
        else:
            names = [o.name for o in scene.objects]
            for i, item in enumerate(items):
                if item is not None and item not in names:
                    r.add(f"{path}.items[{i}]",
                          f"no object {item!r} in the scene (objects: {', '.join(names)})")
        args.update(items=tuple(items), by=d["by"])
    if len(r.problems) > before:
        return None
    return Exercise(kind, question, why, step, MappingProxyType(args), path)


def _read_ray_paths(r, items, pixel, path: str, scene) -> None:
    """Check a ``ray_tree_colours`` order's ``pixel`` and its items, rays named by their paths."""
    if pixel is None:
        r.add(join(path, "pixel"), "required field is missing (the pixel whose ray tree is ordered)")
    else:
        read_pixel(r, pixel, join(path, "pixel"), scene)
    for i, item in enumerate(items):
        kinds = item.split("/") if item is not None else None
        if kinds is not None and (kinds[0] != "primary" or any(k not in RAY_STEPS for k in kinds[1:])):
            r.add(f"{path}.items[{i}]", f"expected a ray's path such as \"primary/refraction/reflection\" "
                                        f"(primary, then {' or '.join(RAY_STEPS)}), got {item!r}")


#: Values a choice may name, as the student reads them (a ``ray_sphere`` fact's ``chosen`` root).
CHOICE_WORDS = MappingProxyType({"t_near": "t1, the smaller root", "t_far": "t2, the larger root"})


def choice_label(choice) -> str:
    """A choice as the student reads it."""
    if choice is None:
        return "nothing (the background)"
    if isinstance(choice, bool):
        return "yes" if choice else "no"
    return CHOICE_WORDS.get(choice, str(choice))


#: The pipeline whose pane shows what an exercise asks about, by its fact or its number.
_PIPELINE_OF = MappingProxyType({
    "zbuffer_keeps": "object order", "ztest_fails": "object order", "blend": "object order",
    "depth": "object order", "first_hit": "image order", "shadow": "image order",
    "ray_event": "image order", "hit_t": "image order", "primitive_tests": "image order",
    "ray_tree_colours": "image order"})


def _asked(ex: Exercise):
    """What the exercise asks about: its fact (a choice), its number's quantity, or its order's
    fields; None for a pixel or a picture to find."""
    return {"choose_one": ex.args.get("fact"), "number": ex.args.get("value"),
            "order": ex.args}.get(ex.kind)


def named_pane(ex: Exercise) -> str | None:
    """The tab (``"object order"`` or ``"image order"``) whose pane shows the pixel the exercise
    names, or None."""
    asked = _asked(ex)
    return None if asked is None else _PIPELINE_OF.get(asked.get("fact", asked.get("of", asked.get("by"))))


RESULTS, PICTURES, HEAT_MAP = "results", "pictures", "heat map"
"""What the window withholds while an exercise waits for its answer (:func:`withheld`)."""


def withheld(ex: Exercise) -> tuple[str, ...]:
    """What the window must not show while ``ex`` waits for its answer: always :data:`RESULTS`, the
    readouts that state what the pipelines found in words and numbers (a picked pixel's history, ray
    tree and worked math, the step drawn, a face's side): every exercise asks the student to predict
    one of those; for a ``pick_picture`` exercise also :data:`PICTURES`, the Four views, which are
    the pictures offered, titled; and for one that asks what intersection tests cost, also
    :data:`HEAT_MAP`, the image-order heat map, which colours each pixel by them.  The pictures of
    the scene stay: the student reasons from them."""
    return (RESULTS, *((PICTURES,) if ex.kind == "pick_picture" else ()),
            *((HEAT_MAP,) if _counts_tests(ex) else ()))


_TESTS_COUNTED = ("primitive_tests", "tests_per_pixel")
"""The facts and number values that count intersection tests."""


def _counts_tests(ex: Exercise) -> bool:
    asked = (*ex.args.get("facts", ()), ex.args.get("fact") or {}, ex.args.get("value") or {})
    return any(a.get("fact", a.get("of")) in _TESTS_COUNTED for a in asked)


def offered(ex: Exercise) -> tuple[str, ...]:
    """The choices or the items ``ex`` offers, as the student reads them.

    >>> ex = Exercise("choose_one", "Which object is dropped?", "", 0,
    ...               MappingProxyType({"choices": ["cube", None]}), "exercises[0]")
    >>> offered(ex)
    ('cube', 'nothing (the background)')
    """
    return tuple(choice_label(c) for c in ex.args.get("choices", ex.args.get("items", ())))


def named_pixel(ex: Exercise) -> tuple[int, int] | None:
    """The pixel an exercise asks about by its coordinates (its fact's, its number's or its ray tree's),
    or None (a pixel exercise asks the student for one; others name none)."""
    pixel = (_asked(ex) or {}).get("pixel")
    return tuple(pixel) if isinstance(pixel, (list, tuple)) else None


def _read_number(r, value, path: str, scene):
    d = r.fields(value, path, ("of", "origin", "end", "direction", "center", "radius", "a", "b", "c",
                               "value", "component", "pixel", "after", "object", "channel", "point", "d"),
                 ("of",))
    if d is None or d.get("of") not in NUMBERS:
        if d is not None:
            r.add(join(path, "of"), f"unknown quantity {show(d.get('of'))} (known: {', '.join(NUMBERS)})")
        return None
    of = d["of"]
    if of == "perspective":
        return _read_perspective(r, d, path)
    if of in ("ray_sphere", "ray_triangle"):  # read as the fact of that name, with a dummy answer
        given = {k: v for k, v in d.items() if k not in ("of", "component")}
        fact = read_fact(r, {**given, "fact": of, "equals": 0}, path, scene)
        component = r.integer(d["component"], join(path, "component")) if "component" in d else None
        if component is not None and component not in (0, 1, 2):
            r.add(join(path, "component"), f"0 (x), 1 (y) or 2 (z), got {component}")
        return None if fact is None else MappingProxyType({"of": of, "component": component, **fact.args})
    needs = {"depth": ("pixel",), "hit_t": ("pixel",), "primitive_tests": ("pixel",),
             "blend": ("pixel", "object", "channel")}[of]
    for key in needs:
        if key not in d:
            r.add(join(path, key), "required field is missing")
    fact = read_fact(r, {"fact": "zbuffer_keeps", "pixel": d.get("pixel"), "object": d.get("object"),
                         **({"after": d["after"]} if "after" in d else {})}, path, scene)
    if fact is None:
        return None
    out = {"of": of, "pixel": fact.args["pixel"], "after": fact.args.get("after"), "object": d.get("object")}
    if of == "blend":
        channel = r.integer(d["channel"], join(path, "channel"))
        if channel is not None and channel not in (0, 1, 2):
            r.add(join(path, "channel"), f"0 (red), 1 (green) or 2 (blue), got {channel}")
        out["channel"] = channel
    return MappingProxyType(out)


def _read_perspective(r, d, path: str):
    """A ``perspective`` number's ``point``, ``d`` and ``component`` (x′ or y′)."""
    for key in ("point", "d", "component"):
        if key not in d:
            r.add(join(path, key), "required field is missing")
    point = r.vector(d["point"], join(path, "point")) if "point" in d else None
    distance = r.number(d["d"], join(path, "d"), gt=0.0) if "d" in d else None
    component = r.integer(d["component"], join(path, "component")) if "component" in d else None
    if component is not None and component not in (0, 1):
        r.add(join(path, "component"), f"0 (x′) or 1 (y′), got {component}")
    behind = point is not None and distance is not None and point[2] + distance <= 0.0
    if behind:
        r.add(join(path, "point"), f"must lie in front of the eye (z > -d = {-distance:g}), "
                                   f"got z = {point[2]:g}")
    if None in (point, distance, component) or component not in (0, 1) or behind:
        return None
    return MappingProxyType({"of": "perspective", "point": point, "d": distance, "component": component})


# --- the pipelines' answers ---------------------------------------------------------------------


def _fact(template, placeholder: str, value, path: str) -> facts_mod.Fact:
    d = _substituted(template, placeholder, list(value) if isinstance(value, tuple) else value)
    args = {k: (tuple(v) if k == "pixel" else v) for k, v in d.items() if k != "fact"}
    return facts_mod.Fact(d["fact"], MappingProxyType(args), path)


def right_choices(ex: Exercise, p: StepPipelines) -> list[int]:
    """The choices of a ``choose_one`` for which its fact holds."""
    return [i for i, choice in enumerate(ex.args["choices"])
            if check_fact(_fact(ex.args["fact"], "$choice", choice, ex.path), p)[0]]


def _facts(ex: Exercise) -> tuple:
    """A ``click_pixel`` exercise's facts (templates with ``"$pixel"``), all to hold at the pixel."""
    return ex.args["facts"]


def pixel_is_right(ex: Exercise, p: StepPipelines, pixel) -> tuple[bool, str]:
    """Do the ``click_pixel`` facts all hold at ``pixel``? (holds, what was computed there: of the
    first fact that does not hold, or of them all)."""
    said = []
    for template in _facts(ex):
        holds, computed = check_fact(_fact(template, "$pixel", tuple(pixel), ex.path), p)
        if not holds:
            return False, computed
        said.append(computed)
    return True, " and ".join(dict.fromkeys(said))


def a_right_pixel(ex: Exercise, p: StepPipelines) -> tuple[int, int] | None:
    """A pixel where a ``click_pixel`` answer is right ("show me"), searched on a grid from the centre."""
    template = _facts(ex)[0]
    if template["fact"] == "projects_to":  # one pixel: where the vertex projects
        obj = next(o for o in p.step.scene.objects if o.name == template["object"])
        cam = p.step.scene.camera
        from core.projection import project_point

        q = project_point(obj.vertices[template["vertex"]], cam.view_from_world, cam.clip_from_view,
                          cam.width, cam.height).pixel
        return None if q is None else (int(q[0]), int(q[1]))
    cam = p.step.scene.camera
    xs, ys = np.meshgrid(np.arange(SEARCH_STRIDE // 2, cam.width, SEARCH_STRIDE),
                         np.arange(SEARCH_STRIDE // 2, cam.height, SEARCH_STRIDE))
    order = np.argsort((xs - cam.width / 2) ** 2 + (ys - cam.height / 2) ** 2, axis=None)
    for x, y in zip(xs.ravel()[order].tolist(), ys.ravel()[order].tolist(), strict=True):
        if pixel_is_right(ex, p, (x, y))[0]:
            return x, y
    return None


def number(ex: Exercise, p: StepPipelines) -> float:
    """The value a ``number`` exercise asks for, as the pipelines compute it."""
    v = ex.args["value"]
    of = v["of"]
    if of in ("ray_sphere", "ray_triangle"):
        got = getattr(facts_mod.solve_intersection(of, v), v["value"])
        if got is None:
            return float("nan")
        return float(got[v["component"]] if v["component"] is not None else got)
    if of == "perspective":
        return float(lecture_image(v["point"], v["d"])[v["component"]])
    x, y = v["pixel"]
    if of == "hit_t":
        root = p.tree((x, y))
        return float("nan") if root.t is None else float(root.t)
    if of == "primitive_tests":
        return float(p.tree((x, y)).tests)
    events = facts_mod.events_before(p, v["pixel"], v.get("after"))
    if of == "depth":
        kept = [e for e in events if e.passed]
        return kept[-1].distance if kept else float(p.step.scene.camera.far)
    names = [o.name for o in p.step.scene.objects]
    blends = [e for e in events if e.blend is not None and names[e.object_index] == v["object"]]
    return float(blends[-1].blend.result[v["channel"]]) if blends else float("nan")


def right_order(ex: Exercise, p: StepPipelines) -> list[str]:
    """The ``order`` exercise's items as the pipelines order them (items the pipelines do not draw or
    trace go last)."""
    if ex.args["by"] == "ray_tree_colours":
        computed = [path for path, _ in p.tree(ex.args["pixel"]).colour_order()]
        return sorted(ex.args["items"], key=lambda item: computed.index(item) if item in computed
                      else len(computed))
    draw = p.raster.draw
    names = [p.step.scene.objects[k].name for k in draw.object_index.tolist()]
    return sorted(ex.args["items"], key=lambda item: names.index(item) if item in names else len(names))


def pictures(ex: Exercise, p: StepPipelines) -> dict[str, np.ndarray]:
    """The pictures a ``pick_picture`` exercise offers, drawn by object order as the Four views tab
    draws them: the front, side and top orthographic views and the observer's, by key."""
    from dataclasses import replace

    from core.object_order.four_views import four_cameras, inked_view

    scene = p.step.scene
    small = replace(scene, camera=scene.camera.replace(width=PICTURE_SIZE[0], height=PICTURE_SIZE[1]))
    return {key: inked_view(small, camera)[0] for key, camera in four_cameras(small).items()}


#: Facts whose computed words, at a wrongly clicked pixel, would name the right one (where the point lands).
_SAYS_WHERE = ("projects_to",)


def judge(ex: Exercise, p: StepPipelines, given) -> Verdict:
    """Right or wrong, with one sentence: ``given`` is a choice index, a pixel ``(x, y)``, a number,
    or a list of the items in order.  A right answer gets the exercise's ``why``; a wrong one only
    what is wrong with it (what the clicked pixel shows, whether a number is too high or too low,
    how many items stand in their place), never the answer: the student tries again or asks for it
    (Reveal)."""
    why = f" {ex.why}" if ex.why else ""
    if ex.kind == "choose_one":
        name = choice_label(ex.args["choices"][given])
        if given in right_choices(ex, p):
            return Verdict(True, f"Right: {name}.{why}")
        return Verdict(False, f"“{name}” is not the answer.")
    if ex.kind == "click_pixel":
        holds, computed = pixel_is_right(ex, p, given)
        if holds:
            return Verdict(True, f"Right: at pixel {tuple(given)} {computed}.{why}")
        if _facts(ex)[0]["fact"] in _SAYS_WHERE:
            return Verdict(False, f"Not there: it does not land at pixel {tuple(given)}.")
        return Verdict(False, f"Not there: at pixel {tuple(given)} {computed}.")
    if ex.kind == "number":
        value, tol, given = number(ex, p), ex.args["tolerance"], float(given)
        if abs(given - value) <= tol:
            return Verdict(True, f"Right: the pipelines compute {value:.6g} (within {tol:g}).{why}")
        near = abs(given - value) <= max(10 * tol, 0.1 * abs(value))
        return Verdict(False, f"{'Not quite' if near else 'No'}: {given:.6g} is too "
                              f"{'high' if given > value else 'low'}.")
    if ex.kind == "pick_picture":
        if given == ex.args["view"]:
            return Verdict(True, f"Right: that is the {_view_words(given)}.{why}")
        # Not which view it is: the next question on the same pictures may ask for that one.
        return Verdict(False, f"Not that one: it is not the {_view_words(ex.args['view'])}.")
    order = right_order(ex, p)
    if list(given) == order:
        return Verdict(True, f"Right: {' → '.join(order)}.{why}")
    placed = sum(a == b for a, b in zip(given, order, strict=True))
    return Verdict(False, f"Not that order: {placed} of {len(order)} in {'its' if placed == 1 else 'their'} "
                          "place.")


def _order_problem(ex: Exercise, p: StepPipelines) -> str | None:
    """Why the pipelines cannot order ``ex``'s items one way, or None."""
    if ex.args["by"] == "drawing_order":
        drawn = {p.step.scene.objects[k].name for k in p.raster.draw.object_index.tolist()}
        missing = [item for item in ex.args["items"] if item not in drawn]
        return f"not drawn: {', '.join(missing)}" if missing else None
    traced = {path for path, _ in p.tree(ex.args["pixel"]).colour_order()}
    missing = [item for item in ex.args["items"] if item not in traced]
    if missing:
        return f"not traced at pixel {ex.args['pixel']}: {', '.join(missing)}"
    order = right_order(ex, p)  # the last hits first: each ray's parent path comes after it
    apart = [f"{a} and {b}" for a, b in zip(order, order[1:], strict=False) if not a.startswith(b + "/")]
    return f"on separate branches, so in no one order: {', '.join(apart)}" if apart else None


def _view_words(key: str) -> str:
    return "observer's own view" if key == "observer" else f"{key} view"


def check_exercises(lesson) -> list[str]:
    """One line per exercise the pipelines cannot answer as asked (no right choice, or several; no
    right pixel; no number; an item not drawn), or whose answer a step of the lesson states
    (:func:`stated_answers`: the exercise would be recall, not application)."""
    lines = []
    pipelines = {}
    for ex in (v for e in lesson.exercises for v in (e.variants or (e,))):
        p = pipelines.setdefault(ex.step, StepPipelines(lesson.steps[ex.step]))
        problem = None
        if ex.kind == "choose_one":
            right = right_choices(ex, p)
            if len(right) != 1:
                names = ", ".join(choice_label(ex.args["choices"][i]) for i in right)
                problem = f"{len(right)} choices are right ({names})"
        elif ex.kind == "click_pixel" and a_right_pixel(ex, p) is None:
            problem = "no pixel makes the answer right"
        elif ex.kind == "number" and not np.isfinite(number(ex, p)):
            problem = "the pipelines give no number"
        elif ex.kind == "order":
            problem = _order_problem(ex, p)
        elif ex.kind == "pick_picture":
            shown = list(pictures(ex, p).items())
            alike = [f"{a} and {b}" for i, (a, x) in enumerate(shown) for b, y in shown[i + 1:]
                     if np.mean(np.abs(x - y) > 0.05) < 0.01]  # under 1 % of pixels differ
            problem = f"pictures alike: {', '.join(alike)}" if alike else None
        if problem:
            lines.append(f"lesson {lesson.id}, {ex.path} ({ex.question}): {problem}")
        else:
            lines += [f"lesson {lesson.id}, {ex.path} ({ex.question}): a step states the answer: {stated}"
                      for stated in stated_answers(lesson, ex, p)]
    return lines


# --- answers a step states ----------------------------------------------------------------------

_WRITTEN_PIXEL = re.compile(r"\((\d+),\s*(\d+)\)")
_THIS_PIXEL = re.compile(r"\b(this|the picked) pixel\b", re.IGNORECASE)


def _sentences(text: str) -> list[str]:
    return [s for s in re.split(r"(?<=[.!?])\s+", text) if s]


def _words(step) -> list[tuple[str, str]]:
    """What a step says to the student: (where, text) for its title, its text and each formula."""
    return [("title", step.title), ("text", step.text)] + [
        (f"formulas[{i}]", f) for i, f in enumerate(step.formulas)]


def _pixels_spoken_of(said: str, step) -> set[tuple[int, int]]:
    """The pixels words of ``step`` speak of: written as ``(x, y)``, and the step's picked pixel when
    they say "this pixel" or "the picked pixel"."""
    pixels = {(int(x), int(y)) for x, y in _WRITTEN_PIXEL.findall(said)}
    if step.pixel is not None and _THIS_PIXEL.search(said):
        pixels.add(tuple(step.pixel))
    return pixels


def _number_stated(lesson, ex: Exercise, p: StepPipelines) -> list[str]:
    value, tol = number(ex, p), ex.args["tolerance"]
    places = {}
    for k, step in enumerate(lesson.steps):
        for where, said in _words(step):
            for n, decimals in written_numbers(said):
                if writes(n, decimals, value, tol):
                    places.setdefault(n, {})[f"steps[{k}].{where}"] = None  # each place once
    return [f"{', '.join(where)} write{'s' if len(where) == 1 else ''} {n:g}, the answer {value:.6g}"
            for n, where in places.items()]


def _choice_stated(lesson, ex: Exercise, p: StepPipelines) -> list[str]:
    pixel, lines = named_pixel(ex), []
    labels = [c if isinstance(c, str) else ("background" if c is None else None) for c in ex.args["choices"]]
    for right in (labels[i] for i in right_choices(ex, p) if labels[i] is not None):
        for k, step in enumerate(lesson.steps):
            for sentence in _sentences(step.text):
                named = [label for label in labels if label is not None and says(sentence, label)]
                if pixel in _pixels_spoken_of(sentence, step) and right in named and len(named) < len(labels):
                    lines.append(f"steps[{k}].text says of pixel {pixel} the answer {right!r}: “{sentence}”")
    return lines


def _pixel_stated(lesson, ex: Exercise, p: StepPipelines) -> list[str]:
    cam, lines = p.step.scene.camera, []
    for k, step in enumerate(lesson.steps):
        pointed = set().union(*(_pixels_spoken_of(said, step) for _, said in _words(step)))
        for pixel in sorted(pointed):
            if 0 <= pixel[0] < cam.width and 0 <= pixel[1] < cam.height and pixel_is_right(ex, p, pixel)[0]:
                lines.append(f"steps[{k}] points at pixel {pixel}, a right answer")
    return lines


def stated_answers(lesson, ex: Exercise, p: StepPipelines) -> list[str]:
    """Where a step of ``lesson`` states the answer of ``ex`` (one drawn exercise, a variant), one
    line each; empty when none does.

    - a ``number``: a step's title, text or a formula writes the answer, either sign, rounded to the
      decimals written and within the tolerance (:func:`writes`), integers below
      :data:`core.lessons.numbers_said.TRIVIAL_INTEGER` without decimals left out;
    - a ``choose_one`` about a pixel: a sentence of a step's text that speaks of that pixel (its
      ``(x, y)``, or "this pixel" for the step's picked pixel) names the right choice, and not every
      choice;
    - a ``click_pixel``: a step's words point at a pixel (written, or "this pixel") that is a right
      answer.
    Other questions (a yes or no, an object named without a pixel, an order, a picture) are not
    searched: the words that give those away are not told apart from the words that teach them."""
    if ex.kind == "number":
        return _number_stated(lesson, ex, p)
    if ex.kind == "choose_one" and named_pixel(ex) is not None:
        return _choice_stated(lesson, ex, p)
    if ex.kind == "click_pixel":
        return _pixel_stated(lesson, ex, p)
    return []
