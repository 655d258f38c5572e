"""Shadow acne: shadow rays that start on their own surface and find it again.

A lit, tilted square is seen by the eye and lit by a light on the same side;
nothing else is in the scene, so in exact arithmetic every pixel of it is
lit.  The primary ray's hit point ``o + t d`` is rounded, though, by about a
unit of rounding of its coordinates: at ``distance`` from the origin about
``distance × 10^-16``, half the time on the far side of the surface.  A
shadow ray from there towards the light crosses the square itself at a tiny
``t`` and the pixel turns dark.

- no offset: every such pixel is self-shadowed;
- a fixed ``ε`` (Ray Tracing in One Weekend): crossings closer than ``ε`` are
  ignored, which works while ``ε`` exceeds the rounding and fails once the
  scene is far enough from the origin (or ``ε`` small enough);
- the scaled offset (the app's :mod:`core.image_order.ray_offset`): the hit
  point is recomputed from the triangle's corners and pushed off the surface
  by a bound that grows with the coordinates, so it works at any distance.

The primary and the shadow rays are crossed with the square by the textbook
Möller–Trumbore test (:func:`core.hard_cases.triangle_cases.textbook_moller_trumbore`);
only the start of the shadow ray differs between the three methods.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.hard_cases.result import CaseImage, CaseResult, Parameter, Row
from core.hard_cases.triangle_cases import textbook_moller_trumbore
from core.image_order.ray_offset import error_bound, offset_ray_origin

#: The fixed epsilons a user can pick (scene units); 0 is "no offset".
EPSILONS = (0.0, 1e-9, 1e-6, 1e-4, 1e-2)
PLACE = np.array([0.6, 0.48, 0.64])
NORMAL = np.array([0.3, 0.9, 0.3164])
WIDTH, HEIGHT = 96, 72
LIT, SHADOWED, BACKGROUND = (0.85, 0.8, 0.6), (0.12, 0.1, 0.08), (0.04, 0.05, 0.08)


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def lit_square(distance: float):
    """The scene moved ``distance`` from the origin: the square's two triangles, the eye, the light.

    Returns
    -------
    triangles : (2, 3, 3) float64, world space, counter-clockwise seen from the light's side.
    camera : Camera looking at the square's centre from 6.5 units away.
    light : (3,) float64, world space.
    """
    n = _unit(NORMAL)
    u = _unit(np.cross(n, (0.0, 0.0, 1.0)))
    v = np.cross(n, u)
    center = distance * PLACE + np.array([0.13, -0.27, 0.41])
    a, b, c, d = (center + 3.0 * (su * u + sv * v) for su, sv in ((-1, -1), (1, -1), (1, 1), (-1, 1)))
    triangles = np.array([(a, c, b), (a, d, c)]) if np.dot(np.cross(c - a, b - a), n) > 0 \
        else np.array([(a, b, c), (a, c, d)])
    eye = center + 6.5 * _unit(n + 0.9 * u - 0.4 * v)
    camera = Camera(eye=tuple(eye), target=tuple(center), up=tuple(n), fov_y_deg=70.0, near=0.1,
                    far=50.0, width=WIDTH, height=HEIGHT)
    light = center + 5.0 * _unit(n - 0.5 * u + 0.3 * v)
    return triangles, camera, light


def self_shadowed(distance: float, epsilon: float) -> dict[str, np.ndarray]:
    """Per pixel of the square: self-shadowed with no offset, a fixed ``epsilon``, the scaled offset.

    Returns
    -------
    dict with ``"on_square"`` (H, W) bool and ``"none"``, ``"fixed"``, ``"scaled"`` (H, W) bool.
    """
    triangles, camera, light = lit_square(distance)
    A, B, C = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    origins, directions = camera.primary_rays()
    o, d = origins.reshape(-1, 3), directions.reshape(-1, 3)
    hit, t = textbook_moller_trumbore(o, d, A, B, C, eps=0.0)
    on = hit.any(axis=1)
    k = np.argmax(hit, axis=1)[on]
    t_hit = t[on, k]
    naive_point = o[on] + t_hit[:, None] * d[on]
    # The barycentric point, from the same solve, recomputed from the triangle's corners.
    e1, e2 = (B - A)[k], (C - A)[k]
    rel = naive_point - A[k]
    g = np.einsum("rk,rk->r", e1, e1), np.einsum("rk,rk->r", e1, e2), np.einsum("rk,rk->r", e2, e2)
    p1, p2 = np.einsum("rk,rk->r", rel, e1), np.einsum("rk,rk->r", rel, e2)
    det = g[0] * g[2] - g[1] * g[1]
    beta, gamma = (g[2] * p1 - g[1] * p2) / det, (g[0] * p2 - g[1] * p1) / det
    surface_point = (1 - beta - gamma)[:, None] * A[k] + beta[:, None] * B[k] + gamma[:, None] * C[k]
    normal = _unit(np.cross(B[0] - A[0], C[0] - A[0]))
    magnitude = float(np.abs(triangles).max())
    scaled_origin = np.array([offset_ray_origin(p, normal, error_bound(magnitude), light - p)
                              for p in surface_point])

    def blocked(start, t_min):
        to_light = light - start
        length = np.linalg.norm(to_light, axis=1)
        w = to_light / length[:, None]
        h, ts = textbook_moller_trumbore(start, w, A, B, C, eps=t_min)
        return (h & (ts < length[:, None])).any(axis=1)

    out = {"on_square": on.reshape(HEIGHT, WIDTH)}
    for name, start, t_min in (("none", naive_point, 0.0), ("fixed", naive_point, epsilon),
                               ("scaled", scaled_origin, 0.0)):
        mask = np.zeros(len(o), dtype=bool)
        mask[on] = blocked(start, t_min)
        out[name] = mask.reshape(HEIGHT, WIDTH)
    return out


def _picture(on, dark) -> np.ndarray:
    image = np.empty((HEIGHT, WIDTH, 3))
    image[:] = BACKGROUND
    image[on] = LIT
    image[dark] = SHADOWED
    return image


def shadow_acne(distance: float = 1e11, epsilon: float = 1e-6) -> CaseResult:
    """Self-shadowed pixels of a lit square ``distance`` from the origin.

    Parameters
    ----------
    distance : float >= 0, scene units.
    epsilon : float >= 0, the fixed offset to compare (scene units).
    """
    masks = self_shadowed(distance, epsilon)
    on = int(masks["on_square"].sum())
    counts = {k: int(masks[k].sum()) for k in ("none", "fixed", "scaled")}
    rounding = 2.0**-53 * max(distance, 1.0)
    rows = (
        Row(f"self-shadowed pixels (of {on} on the square)", counts["fixed"], counts["scaled"], 0),
        Row("  with no offset at all", counts["none"], None, 0),
        Row("rounding of a hit point's coordinate (about)", rounding, rounding, None),
        Row("offset used", epsilon, error_bound(float(np.abs(lit_square(distance)[0]).max())), None),
    )
    return CaseResult(
        name="shadow_acne", title="9. Shadow acne: fixed ε against the scaled offset",
        parameter=Parameter("distance", "distance of the scene from the origin", distance, 1.0, 1e13),
        naive_method=f"fixed ε = {epsilon:g}", robust_method="scaled offset (ray_offset)",
        reference_method="exact: nothing but the square, lit from its own side",
        rows=rows, naive_error=float(counts["fixed"]), robust_error=float(counts["scaled"]),
        error_unit="self-shadowed pixels", tolerance=0.0,
        tolerance_reason="nothing can shadow a lone lit plane",
        explanation=(
            f"The computed hit point o + t d is rounded by up to about {rounding:.0e} units at this "
            "distance; about half the points land just behind the surface, and a shadow ray from there "
            "meets the surface itself. A fixed ε hides those crossings only while ε is larger than the "
            "rounding, so the same ε that works near the origin fails far away. The scaled offset "
            "recomputes the point from the triangle's corners and pushes it off the surface by 256 units "
            "of rounding of the coordinates, wherever the scene is."
        ),
        images=(CaseImage("the lit square: dark pixels are self-shadowed",
                          _picture(masks["on_square"], masks["fixed"]),
                          _picture(masks["on_square"], masks["scaled"])),),
    )
