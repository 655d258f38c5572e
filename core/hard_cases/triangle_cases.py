"""Hard cases of crossing a ray with a triangle: cracks between neighbours, parallel rays.

The textbook test is Möller–Trumbore: solve the lecture's system
``o + t d = (1 - u - v)A + uB + vC`` with cross products, reject the ray as
parallel when ``|det| < ε`` and accept it when ``u, v, u + v`` lie in
``[0, 1]`` and ``t > ε``.  Two things go wrong: rounding makes ``u`` of a ray
through a shared edge come out slightly negative on *both* triangles (the ray
slips through a crack of a closed mesh), and the absolute ``ε`` on ``det``
throws away real hits of grazing rays.  The app's
:func:`core.image_order.intersect_triangle.intersect_triangle` is
watertight: it decides the side of each edge with an exactly consistent,
exactly signed edge function, and it has no ``ε`` at all.
"""

from __future__ import annotations

import math
from fractions import Fraction

import numpy as np

from core import shapes
from core.barycentric_crossings import crossings, nearest
from core.camera import Camera
from core.hard_cases.result import CaseImage, CaseResult, Parameter, Row
from core.image_order.intersect_triangle import intersect_triangle

#: The epsilon of the textbook Möller–Trumbore code (its usual value).
MT_EPSILON = 1e-8


def textbook_moller_trumbore(origins, directions, A, B, C, eps: float = MT_EPSILON):
    """Möller–Trumbore as the textbook writes it, for R rays against T triangles at once.

    The solve is :func:`core.barycentric_crossings.crossings`; the textbook's
    tests on its result are these.

    Parameters
    ----------
    origins, directions : (R, 3) float64, world space.
    A, B, C : (T, 3) float64, the triangles' corners.
    eps : rays with ``|det| < eps`` count as parallel; hits need ``t > eps``.

    Returns
    -------
    hit : (R, T) bool
    t : (R, T) float64 (NaN or inf where ``det`` is 0)
    """
    det, u, v, t = crossings(origins, directions, A, B, C)
    hit = (np.abs(det) >= eps) & (u >= 0) & (u <= 1) & (v >= 0) & (u + v <= 1) & (t > eps)
    return hit, t


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v, axis=-1, keepdims=True)


MESH_DIRECTION = _unit((0.6, 0.48, 0.64))
EYE_OFFSET = np.array([-2.1, 3.3, 3.9])
SAMPLES_PER_EDGE = 15
IMAGE_SIZE = 96


def _adjacency(triangles):
    """Edges (sorted vertex pairs) and vertices -> the triangles that share them."""
    edges: dict[tuple[int, int], list[int]] = {}
    corners: dict[int, list[int]] = {}
    for ti, tri in enumerate(triangles.tolist()):
        for k in range(3):
            edges.setdefault(tuple(sorted((tri[k], tri[(k + 1) % 3]))), []).append(ti)
            corners.setdefault(tri[k], []).append(ti)
    return edges, corners


def _aimed_rays(vertices, triangles, normals, eye):
    """Rays from ``eye`` aimed at points of shared edges and at vertices, all on the seen side.

    Only edges and vertices all of whose triangles face the eye are aimed at,
    so that every ray enters the closed mesh right there: it must hit one of
    those triangles.
    """
    edges, corners = _adjacency(triangles)
    facing = np.einsum("tk,tk->t", normals, eye - vertices[triangles[:, 0]]) > 0
    targets, near, kind = [], [], []
    for (i, j), tris in edges.items():
        if facing[tris].all():
            for s in (np.arange(SAMPLES_PER_EDGE) + 0.5) / SAMPLES_PER_EDGE:
                targets.append(vertices[i] + s * (vertices[j] - vertices[i]))
                near.append(tris)
                kind.append("edge")
    for v, tris in corners.items():
        if facing[tris].all():
            targets.append(vertices[v])
            near.append(tris)
            kind.append("vertex")
    return np.array(targets), near, np.array(kind)


def _shade(vertices, triangles, normals, camera, light):
    """A grey picture of the mesh (first hit per pixel by the textbook test), linear RGB."""
    origins, directions = camera.primary_rays()
    o, d = origins.reshape(-1, 3), directions.reshape(-1, 3)
    A, B, C = (vertices[triangles[:, k]] for k in range(3))
    first, _ = nearest(*textbook_moller_trumbore(o, d, A, B, C))
    seen = first >= 0
    lambert = np.clip(normals[first] @ light, 0.0, 1.0)
    grey = np.where(seen, 0.15 + 0.6 * lambert, 0.03)
    return np.repeat(grey.reshape(camera.height, camera.width, 1), 3, axis=2)


def _mark(image, pixels, color, radius):
    out = image.copy()
    h, w, _ = out.shape
    for x, y in pixels:
        out[max(0, y - radius):min(h, y + radius + 1), max(0, x - radius):min(w, x + radius + 1)] = color
    return out


def shared_edges(distance: float = 1e4) -> CaseResult:
    """Rays through shared edges and vertices of a closed tessellated sphere, ``distance`` from the origin.

    Parameters
    ----------
    distance : float >= 0, scene units; the mesh and the eye are moved this far.
    """
    center = distance * MESH_DIRECTION + np.array([0.1, 0.2, 0.3])
    mesh = shapes.uv_sphere(center, 1.0, rings=8, segments=12)
    vertices, triangles, normals = mesh.vertices, mesh.triangles, mesh.normals
    eye = center + EYE_OFFSET
    targets, near, kind = _aimed_rays(vertices, triangles, normals, eye)
    directions = _unit(targets - eye)
    origins = np.broadcast_to(eye, directions.shape).copy()
    A, B, C = (vertices[triangles[:, k]] for k in range(3))
    naive_hit, _ = textbook_moller_trumbore(origins, directions, A, B, C)
    naive_crack = np.array([not naive_hit[r, tris].any() for r, tris in enumerate(near)])
    robust_crack = np.array([
        not any(intersect_triangle(eye, directions[r], A[i], B[i], C[i]).hit for i in tris)
        for r, tris in enumerate(near)
    ])

    camera = Camera(eye=tuple(eye), target=tuple(center), fov_y_deg=32.0, near=0.5, far=20.0,
                    width=IMAGE_SIZE, height=IMAGE_SIZE)
    base = _shade(vertices, triangles, normals, camera, _unit(EYE_OFFSET + (2.0, 3.0, 0.0)))
    pixels = [camera.project(p).pixel for p in targets]
    where = [(int(x), int(y)) for x, y in pixels]
    aimed = _mark(base, where, (0.25, 0.45, 0.95), 0)
    naive_img = _mark(aimed, [p for p, c in zip(where, naive_crack, strict=True) if c], (1.0, 0.1, 0.05), 1)
    robust_img = _mark(aimed, [p for p, c in zip(where, robust_crack, strict=True) if c],
                       (1.0, 0.1, 0.05), 1)
    rows = []
    for label, mask in (("rays aimed at shared edges", kind == "edge"),
                        ("rays aimed at shared vertices", kind == "vertex")):
        rows.append(Row(f"{label} ({int(mask.sum())}): through a crack", int(naive_crack[mask].sum()),
                        int(robust_crack[mask].sum()), 0))
    return CaseResult(
        name="shared_edges", title="4. Rays through shared edges: cracks in a closed mesh",
        parameter=Parameter("distance", "distance of the mesh and the eye from the origin", distance,
                            1.0, 1e8),
        naive_method=f"Möller–Trumbore, ε = {MT_EPSILON:g}",
        robust_method="watertight test (intersect_triangle)",
        reference_method="closed mesh: every aimed ray must hit",
        rows=tuple(rows), naive_error=float(naive_crack.sum()), robust_error=float(robust_crack.sum()),
        error_unit="rays through a crack", tolerance=0.0,
        tolerance_reason="a closed mesh has no holes: no ray may pass",
        explanation=(
            "A ray aimed exactly at an edge that two triangles share has, in exact arithmetic, one "
            "barycentric weight exactly 0 in each of them; Möller–Trumbore computes the two weights from "
            "different cross products, and when both round to a tiny negative number the ray misses both "
            "triangles and slips through the surface (red squares). The watertight test looks along the "
            "ray and decides the side of each edge with one edge function whose sign is exact and which "
            "is exactly the negative for the neighbour, so exactly one side, or both, owns the ray."
        ),
        images=(CaseImage("rays aimed at edges and vertices (blue); through a crack (red)", naive_img,
                          robust_img),),
    )


PLANE_Z = 0.25
TRIANGLE = (np.array([-1.3, -0.9, PLANE_Z]), np.array([1.7, -0.6, PLANE_Z]), np.array([-0.2, 1.4, PLANE_Z]))


def _exact_hit(o, d, A, B, C):
    """The lecture's system solved in exact rationals: ``(hit, t)``; ``(False, None)`` if det = 0."""
    o, d, A, B, C = ([Fraction(float(x)) for x in v] for v in (o, d, A, B, C))
    cols = [[a - c for a, c in zip(A, C, strict=True)], [b - c for b, c in zip(B, C, strict=True)],
            [-x for x in d]]
    rhs = [p - c for p, c in zip(o, C, strict=True)]

    def det(c0, c1, c2):
        return (c0[0] * (c1[1] * c2[2] - c1[2] * c2[1]) - c1[0] * (c0[1] * c2[2] - c0[2] * c2[1])
                + c2[0] * (c0[1] * c1[2] - c0[2] * c1[1]))

    m = det(*cols)
    if m == 0:
        return False, None
    alpha = det(rhs, cols[1], cols[2]) / m
    beta = det(cols[0], rhs, cols[2]) / m
    t = det(cols[0], cols[1], rhs) / m
    hit = alpha >= 0 and beta >= 0 and 1 - alpha - beta >= 0 and t >= 0
    return hit, float(t)


def _cramer_no_check(o, d, A, B, C) -> float:
    """``t = det_t / det`` by the lecture's Cramer rule with no test of ``det`` (NaN or inf at 0)."""
    cols = np.column_stack([A - C, B - C, -d])
    m = float(np.dot(cols[:, 0], np.cross(cols[:, 1], cols[:, 2])))
    mt = float(np.dot(cols[:, 0], np.cross(cols[:, 1], o - C)))
    with np.errstate(divide="ignore", invalid="ignore"):
        return float(np.float64(mt) / np.float64(m))


def _verdict(hit: bool, t) -> str:
    return f"hit at t = {t:.6g}" if hit else "miss"


def parallel_rays(angle_deg: float = 1e-8) -> CaseResult:
    """A ray parallel to a triangle, one lying in its plane, and one grazing it at ``angle_deg``.

    Parameters
    ----------
    angle_deg : float > 0, degrees between the grazing ray and the triangle's plane.
    """
    A, B, C = TRIANGLE
    centroid = (A + B + C) / 3.0
    along = _unit((1.0, 0.35, 0.0))
    theta = math.radians(angle_deg)
    grazing = np.array([math.cos(theta) * along[0], math.cos(theta) * along[1], -math.sin(theta)])
    rays = (
        ("parallel, 0.5 above", centroid - 3.0 * along + (0.0, 0.0, 0.5), along),
        ("in the plane", centroid - 3.0 * along, along),
        (f"grazing at {angle_deg:g}°", centroid - 3.0 * grazing, grazing),
    )
    rows, verdicts, wrong_naive, wrong_robust = [], ([], [], []), 0, 0
    for name, o, d in rays:
        hit, t = textbook_moller_trumbore(o[None], d[None], A[None], B[None], C[None])
        naive_hit, naive_t = bool(hit[0, 0]), float(t[0, 0])
        robust = intersect_triangle(o, d, A, B, C)
        exact_hit, exact_t = _exact_hit(o, d, A, B, C)
        wrong_naive += naive_hit != exact_hit
        wrong_robust += robust.hit != exact_hit
        for column, hit in zip(verdicts, (naive_hit, robust.hit, exact_hit), strict=True):
            column.append("hit" if hit else "miss")
        rows += [
            Row(f"{name}: verdict", _verdict(naive_hit, naive_t), _verdict(robust.hit, robust.t),
                _verdict(exact_hit, exact_t)),
            Row(f"{name}: t (Cramer's rule with no check of det)", _cramer_no_check(o, d, A, B, C),
                robust.t if robust.hit else None,
                exact_t if exact_hit else "none: det = 0" if exact_t is None else "none: a miss"),
        ]
    return CaseResult(
        name="parallel", title="5. Rays parallel to a triangle, in its plane, and grazing it",
        parameter=Parameter("angle_deg", "angle between the grazing ray and the plane (degrees)",
                            angle_deg, 1e-12, 10.0),
        naive_method=f"Möller–Trumbore, |det| < {MT_EPSILON:g} is 'parallel'",
        robust_method="watertight test (intersect_triangle)",
        reference_method="exact rationals of the same inputs",
        rows=(Row("verdicts: parallel, in the plane, grazing", *(", ".join(v) for v in verdicts)), *rows),
        naive_error=float(wrong_naive), robust_error=float(wrong_robust),
        error_unit="wrong verdicts", tolerance=0.0, tolerance_reason="a verdict is right or wrong",
        explanation=(
            "Dividing by det without a check gives inf or NaN for a ray parallel to the plane (det = 0), "
            "and 0/0 = NaN for one lying in it. Möller–Trumbore guards with |det| < ε, but ε is an "
            "absolute number: a ray that grazes the triangle at a small angle (or any ray at a small "
            "triangle) has a small det too and is thrown away although it hits. The watertight test "
            "has no ε: the edge functions decide whether the ray passes inside, and only an exact "
            "det = 0 means parallel."
        ),
    )
