"""A picked pixel's ray tree as JSON: every ray, what it hit, and what its colour adds to the pixel.

One object per ray (:class:`core.image_order.ray_tree.RayNode`), its
children nested under ``"children"``.  Points and directions are world
space; ``t`` is the distance along the unit ``direction`` from ``origin`` to
the hit (``null`` on a miss).  Under ``"colour"``: ``returned`` is the colour
the ray hands back to its parent (local colour plus the coefficients times the
children's colours; the background on a miss), ``coefficient`` its factor in
the parent's colour, ``weight`` its factor in the pixel, and ``to_pixel``
what the ray adds to the pixel by itself: ``weight`` times its local colour
(times the background on a miss).  Summed over the reflection, refraction
and primary rays, ``to_pixel`` gives the pixel's colour before clipping — the
lecture's second stage of ray tracing, written out.  Shadow rays carry the
light's part of their parent's local colour as ``returned``.
"""

from __future__ import annotations

import json

import numpy as np

from core.image_order.ray_tree import RayNode


def _vector(v) -> list[float] | None:
    return None if v is None else [float(c) for c in v]


def _to_pixel(node: RayNode) -> list[float] | None:
    if node.kind == "shadow" or not node.traced:
        return None
    own = node.color if node.hit is None else node.local_color
    return _vector(node.weight * np.asarray(own))


def node_record(node: RayNode) -> dict:
    """One ray and all below it, as plain JSON values."""
    return {
        "kind": node.kind,
        "generation": node.generation,
        "traced": node.traced,
        "status": node.status,
        "origin": _vector(node.origin),
        "direction": _vector(node.direction),
        "t_min": float(node.t_min),
        "t_max": None if not np.isfinite(node.t_max) else float(node.t_max),
        "t": None if node.t is None else float(node.t),
        "hit": None if node.hit is None else {"index": int(node.hit), "name": node.hit_name},
        "point": _vector(node.point),
        "normal": _vector(node.normal),
        "front_face": node.front_face,
        "light": node.light,
        "colour": {
            "returned": _vector(node.color),
            "local": _vector(node.local_color),
            "ambient": _vector(node.ambient),
            "k_reflect": float(node.k_reflect),
            "k_refract": float(node.k_refract),
            "fresnel": _vector(node.fresnel),
            "total_internal_reflection": node.total_internal_reflection,
            "coefficient": float(node.coefficient),
            "weight": float(node.weight),
            "to_pixel": _to_pixel(node),
        },
        "tests": {"primitives": int(node.tests), "bounding_volumes": int(node.bounds_tests)},
        "children": [node_record(child) for child in node.children],
    }


def ray_tree_json(x: int, y: int, root: RayNode, mode: str) -> bytes:
    """The file's bytes: the pixel ``(x, y)``, the tracing ``mode``, its colour and its ray tree."""
    document = {"pixel": [int(x), int(y)], "mode": mode,
                "pixel_colour": _vector(root.pixel_color), "tree": node_record(root)}
    return (json.dumps(document, indent=2) + "\n").encode()
