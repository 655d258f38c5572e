"""``python -m app intersect``: cross one ray with a sphere or a triangle, worked step by step.

Examples::

    python -m app intersect sphere --origin 2,1,2 --end 10,6,6 --center 6,4,6 --radius 10
    python -m app intersect sphere --origin -5,1,0 --direction 1,0,0 --center 0,0,0 --radius 1 --json
    python -m app intersect triangle --origin 0,0,0 --direction 1,1,1 --a 3,0,0 --b 0,3,0 --c 0,0,3

Without ``--json`` it prints the worked solution; with ``--json`` one JSON
object (``null`` for values that do not exist, never NaN).  This module imports
only :mod:`core` and the standard library, so it answers without Qt or VTK.
"""

from __future__ import annotations

import argparse
import json
import math
import re

from app.usage import UsageError
from core.image_order import intersect_sphere as sphere_mod
from core.image_order import intersect_triangle as triangle_mod

VEC = "X,Y,Z"


def add_parser(sub) -> argparse.ArgumentParser:
    """Add the ``intersect`` command (with ``sphere`` and ``triangle``) to ``sub``."""
    parser = sub.add_parser(
        "intersect",
        help="cross a ray with a sphere or a triangle and show the worked solution",
        description="Cross one ray with a sphere or a triangle, step by step as in the lecture.",
    )
    shapes = parser.add_subparsers(dest="shape", metavar="SHAPE", required=True)

    sph = _leaf(shapes, "sphere", "the ray (or the lecture's segment) against a sphere")
    sph.add_argument("--origin", required=True, metavar=VEC, help="start point (x1, y1, z1)")
    way = sph.add_mutually_exclusive_group(required=True)
    way.add_argument("--direction", metavar=VEC, help="ray direction d; the ray is o + t d, t >= 0")
    way.add_argument("--end", metavar=VEC,
                     help="end point (x2, y2, z2); the segment is o + (end - o) t, 0 <= t <= 1")
    sph.add_argument("--center", required=True, metavar=VEC, help="centre (l, m, n)")
    sph.add_argument("--radius", required=True, metavar="R", help="radius r > 0")
    sph.add_argument("--json", action="store_true", help="print one JSON object")
    sph.set_defaults(run=run_sphere)

    tri = _leaf(shapes, "triangle", "the ray o + t d against the triangle A, B, C")
    tri.add_argument("--origin", required=True, metavar=VEC, help="ray start point o")
    tri.add_argument("--direction", required=True, metavar=VEC, help="ray direction d")
    for name in "abc":
        tri.add_argument(f"--{name}", required=True, metavar=VEC, help=f"vertex {name.upper()}")
    tri.add_argument("--json", action="store_true", help="print one JSON object")
    tri.set_defaults(run=run_triangle)
    return parser


def _leaf(shapes, name: str, help_text: str) -> argparse.ArgumentParser:
    parser = shapes.add_parser(name, help=help_text, description=help_text.capitalize() + ".",
                               epilog="Vectors are three comma-separated numbers, e.g. -5,1,0.")
    # Let option values such as "-5,1,0" start with a minus sign (argparse would
    # otherwise take them for options; Python 3.13 accepts them on its own).
    parser._negative_number_matcher = re.compile(r"^-\.?\d")
    return parser


def parse_vec3(option: str, text: str) -> tuple[float, float, float]:
    """``"X,Y,Z"`` to three finite floats; a :class:`UsageError` naming ``option`` otherwise."""
    parts = text.split(",")
    try:
        values = tuple(float(p) for p in parts)
    except ValueError:
        values = ()
    if len(values) != 3 or not all(math.isfinite(v) for v in values):
        raise UsageError(f"{option}: expected three numbers X,Y,Z, got {text!r}")
    if max(abs(v) for v in values) > sphere_mod.LIMIT:
        raise UsageError(f"{option}: coordinates must be at most 1e60 in size, got {text!r}")
    return values


def _parse_radius(text: str) -> float:
    try:
        radius = float(text)
    except ValueError:
        radius = math.nan
    if not (math.isfinite(radius) and radius > 0):
        raise UsageError(f"--radius: expected a finite number > 0, got {text!r}")
    if not 1 / sphere_mod.LIMIT <= radius <= sphere_mod.LIMIT:
        # The bound is 1 / 1e60, one rounding step above the float 1e-60 itself.
        raise UsageError(f"--radius: must be > 1e-60 and <= 1e60, got {text!r}")
    return radius


def _parse_direction(text: str, option: str = "--direction") -> tuple[float, float, float]:
    d = parse_vec3(option, text)
    if max(abs(x) for x in d) < 1 / sphere_mod.LIMIT:
        raise UsageError(f"{option}: must not be the zero vector, got {text!r}")
    return d


def _num(x) -> float | None:
    return None if x is None else float(x) + 0.0  # -0.0 (a start on the surface) printed as 0


def _list(v) -> list[float] | None:
    return None if v is None else [float(x) for x in v]


def _emit(result, payload: dict, as_json: bool) -> int:
    if as_json:
        print(json.dumps(payload, allow_nan=False))
    else:
        print("\n".join(result.explain()))
    return 0


def run_sphere(args) -> int:
    origin = parse_vec3("--origin", args.origin)
    center = parse_vec3("--center", args.center)
    radius = _parse_radius(args.radius)
    try:
        if args.end is not None:
            end = parse_vec3("--end", args.end)
            if max(abs(e - o) for e, o in zip(end, origin, strict=True)) < 1 / sphere_mod.LIMIT:
                raise UsageError(f"--end: must differ from --origin, got {args.end!r}")
            s = sphere_mod.intersect_sphere_segment(origin, end, center, radius)
        else:
            direction = _parse_direction(args.direction)
            s = sphere_mod.intersect_sphere(origin, direction, center, radius)
    except ValueError as exc:
        raise UsageError(str(exc)) from exc
    ray_point = None if s.ray_hit_t is None else s.origin + s.ray_hit_t * s.direction
    payload = {
        "shape": "sphere",
        "form": "segment" if s.is_segment else "ray",
        "origin": _list(s.origin),
        "direction": _list(s.direction),
        "end": _list(s.end),
        "center": _list(s.center),
        "radius": s.radius,
        "a": s.a,
        "b": s.b,
        "c": s.c,
        "half_b": s.half_b,
        "line_distance": s.line_distance,
        "discriminant": s.discriminant,
        "classification": s.classification,
        "roots": None if s.t_near is None else [s.t_near, s.t_far],
        "t_near": _num(s.t_near),
        "t_far": _num(s.t_far),
        "origin_inside": s.origin_inside,
        "hit": s.hit,
        "t": _num(s.t),
        "chosen": s.chosen,
        "reason": s.reason,
        "point": _list(s.point),
        "normal": _list(s.normal),
        "ray": {"hit": s.ray_hit_t is not None, "t": _num(s.ray_hit_t),
                "point": _list(ray_point), "reason": s.ray_reason},
    }
    return _emit(s, payload, args.json)


def run_triangle(args) -> int:
    origin = parse_vec3("--origin", args.origin)
    direction = _parse_direction(args.direction)
    a, b, c = (parse_vec3(f"--{n}", getattr(args, n)) for n in "abc")
    try:
        h = triangle_mod.intersect_triangle(origin, direction, a, b, c)
    except ValueError as exc:
        raise UsageError(str(exc)) from exc
    payload = {
        "shape": "triangle",
        "origin": _list(h.origin),
        "direction": _list(h.direction),
        "a": list(a),
        "b": list(b),
        "c": list(c),
        "determinant": h.determinant,
        "edge_functions": list(h.edge_functions),
        "hit": h.hit,
        "t": _num(h.t),
        "alpha": _num(h.alpha),
        "beta": _num(h.beta),
        "gamma": _num(h.gamma),
        "point": _list(h.point),
        "reason": h.reason,
    }
    return _emit(h, payload, args.json)
