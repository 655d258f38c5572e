"""Ray-triangle crossings: hand-worked cases, exact Fraction references, watertightness."""

import warnings
from fractions import Fraction

import numpy as np
import pytest
from brute_force import exact_triangle_solve
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from core.image_order.intersect_triangle import cramer_solve, intersect_triangle


@pytest.fixture
def strict_numerics():
    """Turn every numpy floating-point problem and every warning into an error."""
    with warnings.catch_warnings(), np.errstate(all="raise"):
        warnings.simplefilter("error")
        yield


# --- hand-worked cases --------------------------------------------------------------------


def test_hand_worked_lecture_case():
    # Plane x + y + z = 3 through A = (3,0,0), B = (0,3,0), C = (0,0,3); the ray t(1,1,1)
    # meets it where 3t = 3, so t = 1 and P = (1,1,1) = (A + B + C) / 3.
    h = intersect_triangle((0, 0, 0), (1, 1, 1), (3, 0, 0), (0, 3, 0), (0, 0, 3))
    assert h.hit and h.reason.startswith("inside")
    assert h.t == pytest.approx(1, rel=1e-15)
    assert (h.alpha, h.beta, h.gamma) == pytest.approx((1 / 3, 1 / 3, 1 / 3), rel=1e-15)
    assert h.point == pytest.approx((1, 1, 1), rel=1e-15)
    # M = [A - C | B - C | -d] = [[3,0,-1],[0,3,-1],[-3,-3,-1]], det = 3(-3-3) - 0 - 1(0+9) = -27
    assert h.determinant == -27


def test_weights_follow_the_lecture_naming():
    # Straight down onto z = 0 at P = (0.5, 0.25): P = 0.25 A + 0.5 B + 0.25 C.
    h = intersect_triangle((0.5, 0.25, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 1, 0))
    assert h.hit and (h.t, h.alpha, h.beta, h.gamma) == (1, 0.25, 0.5, 0.25)


def test_cramer_solve_by_hand():
    # det M = -27 as above; M_alpha = [o - C | B - C | -d] with o - C = (0,0,-3):
    # det = 0·(..) - 0 + (-3)·(0·(-1) - 3·(-1))... = -3·3 = -9, so α = -9 / -27 = 1/3.
    s = cramer_solve((0, 0, 0), (1, 1, 1), (3, 0, 0), (0, 3, 0), (0, 0, 3))
    assert s.det == -27 and s.det_alpha == -9 and s.det_beta == -9 and s.det_t == -27
    assert s.t == 1
    assert s.rhs.tolist() == [0, 0, -3]
    assert s.matrix.tolist() == [[3, 0, -1], [0, 3, -1], [-3, -3, -1]]


def test_outside_names_the_negative_weight():
    # P = (2, 0.2, 0) = -1.2 A + 2 B + 0.2 C: alpha < 0
    h = intersect_triangle((2, 0.2, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 1, 0))
    assert not h.hit and h.reason == "outside: alpha < 0"
    assert (h.alpha, h.beta, h.gamma) == pytest.approx((-1.2, 2, 0.2), rel=1e-14)
    assert h.t == 1 and h.point is None
    h = intersect_triangle((-1, -1, 1), (0, 0, -1), (0, 0, 0), (1, 0, 0), (0, 1, 0))
    assert h.reason == "outside: beta < 0 and gamma < 0"


def test_triangle_behind_the_origin():
    h = intersect_triangle((0.2, 0.2, 1), (0, 0, 1), (0, 0, 0), (1, 0, 0), (0, 1, 0))
    assert not h.hit and h.reason == "behind the origin: t < 0"
    assert h.t == -1 and h.point is None


@pytest.mark.usefixtures("strict_numerics")
@pytest.mark.parametrize(
    ("origin", "direction"),
    [
        ((0.2, 0.2, 1), (1, 0.3, 0)),  # above the plane z = 0, moving along it
        ((0.2, 0.2, 0), (1, 0.3, 0)),  # in the plane itself
    ],
)
def test_ray_parallel_to_an_axis_plane_is_a_clean_miss(origin, direction):
    h = intersect_triangle(origin, direction, (0, 0, 0), (1, 0, 0), (0, 1, 0))
    assert not h.hit and "parallel" in h.reason
    assert h.determinant == 0
    assert h.t is None and h.alpha is None and h.point is None
    assert all(np.isfinite(h.edge_functions))
    assert any("parallel" in line for line in h.explain())


@pytest.mark.usefixtures("strict_numerics")
def test_ray_parallel_to_a_tilted_triangle_is_a_clean_miss():
    rng = np.random.default_rng(3)
    for _ in range(200):
        A, B, C = rng.normal(size=(3, 3))
        normal = np.cross(B - A, C - A)
        direction = rng.uniform(-1, 1) * (B - A) + rng.uniform(-1, 1) * (C - A)
        origin = (A + B + C) / 3 + rng.choice([-1, 1]) * rng.uniform(0.1, 1) * normal
        h = intersect_triangle(origin, direction, A, B, C)
        assert not h.hit and "parallel" in h.reason, h.reason
        assert h.t is None and h.alpha is None


def test_degenerate_triangle_is_a_miss():
    h = intersect_triangle((0, 0, 1), (0, 0, -1), (0, 0, 0), (1, 1, 0), (2, 2, 0))
    assert not h.hit and "degenerate" in h.reason


@pytest.mark.parametrize("bad", [dict(direction=(0, 0, 0)), dict(a=(0, 0)), dict(c=(0, np.nan, 0))])
def test_bad_input_is_a_value_error(bad):
    args = dict(origin=(0, 0, 1), direction=(0, 0, -1), a=(0, 0, 0), b=(1, 0, 0), c=(0, 1, 0)) | bad
    with pytest.raises(ValueError):
        intersect_triangle(**args)


def test_explanation_writes_out_the_system():
    lines = intersect_triangle((0, 0, 0), (1, 1, 1), (3, 0, 0), (0, 3, 0), (0, 0, 3)).explain()
    text = "\n".join(lines)
    assert "  x: (3)α + (0)β + (-1)t = 0" in lines
    assert "  z: (-3)α + (-3)β + (-1)t = -3" in lines
    assert "Determinant det M = det[A - C, B - C, -d] = -27" in lines
    assert "  α = det M_α / det M = -9 / -27 = 0.333333" in lines
    assert "  t = det M_t / det M = -27 / -27 = 1" in lines
    assert "α >= 0, β >= 0, γ >= 0, t >= 0" in text
    assert text.splitlines()[-1].startswith("Hit: ")


# --- against the exact solution -----------------------------------------------------------

coords = st.one_of(
    st.integers(-640, 640).map(lambda i: i / 64),  # a grid: rays exactly through edges
    st.floats(-10, 10).filter(lambda x: x == 0 or abs(x) > 1e-6),
)
points = st.tuples(coords, coords, coords)


def length(v) -> float:
    return float(np.linalg.norm(np.asarray(v, dtype=float)))


@settings(max_examples=400, deadline=None)
@given(origin=points, direction=points, a=points, b=points, c=points)
def test_matches_the_exact_barycentric_solution(origin, direction, a, b, c):
    assume(np.linalg.norm(direction) > 1e-3)
    assume(np.linalg.norm(np.cross(np.subtract(b, a), np.subtract(c, a))) > 1e-3)
    exact = exact_triangle_solve(origin, direction, a, b, c)
    assume(exact is not None)
    # Well conditioned only: far from parallel (|det M| relative to its columns' lengths).
    det = cramer_solve(origin, direction, a, b, c).det
    size = length(direction) * length(np.subtract(a, c)) * length(np.subtract(b, c))
    assume(abs(det) > 1e-4 * size)
    alpha, beta, gamma, t = exact
    h = intersect_triangle(origin, direction, a, b, c)
    assert h.t is not None
    margin = Fraction(1, 10**6)
    if min(alpha, beta, gamma) > margin and t > margin:
        assert h.hit
    if min(alpha, beta, gamma) < -margin or t < -margin:
        assert not h.hit
    if h.hit:
        assert h.alpha + h.beta + h.gamma == pytest.approx(1, abs=1e-12)
        ref = [float(alpha), float(beta), float(gamma), float(t)]
        assert [h.alpha, h.beta, h.gamma, h.t] == pytest.approx(ref, rel=1e-6, abs=1e-6)
        weighted = h.alpha * np.array(a) + h.beta * np.array(b) + h.gamma * np.array(c)
        assert h.point == pytest.approx(weighted, abs=1e-9)
        along_ray = np.array(origin) + h.t * np.array(direction)
        assert h.point == pytest.approx(along_ray, rel=1e-6, abs=1e-6)
    elif min(alpha, beta, gamma) < -margin and t > margin:
        assert h.reason.startswith("outside: ")
        for name, w in zip(("alpha", "beta", "gamma"), (alpha, beta, gamma), strict=True):
            if w < -margin:
                assert f"{name} < 0" in h.reason
            if w > margin:
                assert f"{name} < 0" not in h.reason


# --- watertightness -----------------------------------------------------------------------


def perturbed_icosphere(rng, subdivisions=0):
    """A closed triangle mesh around the origin, radially perturbed (star-shaped from 0).

    Returns vertices (N, 3) and faces (M, 3) of vertex indices, wound consistently.
    """
    g = (1 + 5**0.5) / 2
    verts = [(-1, g, 0), (1, g, 0), (-1, -g, 0), (1, -g, 0), (0, -1, g), (0, 1, g),
             (0, -1, -g), (0, 1, -g), (g, 0, -1), (g, 0, 1), (-g, 0, -1), (-g, 0, 1)]
    faces = [(0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4),
             (11, 10, 2), (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8),
             (3, 8, 9), (4, 9, 5), (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1)]
    verts = [np.array(v, float) / np.linalg.norm(v) for v in verts]
    for _ in range(subdivisions):
        middle = {}

        def mid(i, j, middle=middle):
            key = (min(i, j), max(i, j))
            if key not in middle:
                m = verts[i] + verts[j]
                verts.append(m / np.linalg.norm(m))
                middle[key] = len(verts) - 1
            return middle[key]

        new = []
        for a, b, c in faces:
            ab, bc, ca = mid(a, b), mid(b, c), mid(c, a)
            new += [(a, ab, ca), (b, bc, ab), (c, ca, bc), (ab, bc, ca)]
        faces = new
    return np.array(verts) * rng.uniform(0.8, 1.2, size=(len(verts), 1)), np.array(faces)


def edges_of(faces):
    return sorted({(min(f[i], f[i - 1]), max(f[i], f[i - 1])) for f in faces for i in range(3)})


def test_closed_mesh_has_no_cracks():
    """Rays from inside a closed mesh through shared edges and vertices always hit.

    The aim points (edge midpoints and other points on edges, rounded to floats, and the
    vertices themselves) put the rays on or within rounding of the shared edges.  The mesh is
    star-shaped from its centre, so every ray from there leaves it exactly once: all the
    triangles that report a hit must report the same t.
    """
    rng = np.random.default_rng(2024)
    rays = plain_cramer_leaks = 0
    for mesh in range(10):
        verts, faces = perturbed_icosphere(rng, subdivisions=1 if mesh == 0 else 0)
        scale = 10.0 ** rng.uniform(-3, 3)
        shift = rng.normal(size=3) * scale * 10.0 ** rng.uniform(0, 3)  # far from the origin
        verts = verts * scale + shift
        edges = edges_of(faces)
        fractions = (0.5,) if mesh == 0 else (0.5, rng.uniform(), rng.uniform())
        targets = [verts[i] + s * (verts[j] - verts[i]) for i, j in edges for s in fractions]
        targets += list(verts)
        targets += list(shift + rng.normal(size=(20, 3)))
        for target in targets:
            origin = shift
            direction = target - origin
            hits = [intersect_triangle(origin, direction, *verts[f]) for f in faces]
            hits = [h for h in hits if h.hit]
            rays += 1
            assert hits, f"ray through {target} leaked through the mesh"
            assert len({h.t for h in hits}) == 1, [h.t for h in hits]
            for h in hits:
                assert h.alpha + h.beta + h.gamma == pytest.approx(1, abs=1e-12)
                weighted = h.alpha * h.vertices[0] + h.beta * h.vertices[1] + h.gamma * h.vertices[2]
                assert np.allclose(h.point, weighted, rtol=1e-12, atol=0)
                assert np.allclose(h.point, origin + h.t * direction, rtol=1e-12,
                                   atol=1e-12 * scale)
            # The lecture's plain Cramer solve with "all weights >= 0" is not watertight.
            solutions = [cramer_solve(origin, direction, *verts[f]) for f in faces]
            plain_cramer_leaks += not any(
                s.t is not None and min(s.alpha, s.beta, s.gamma) >= 0 and s.t >= 0
                for s in solutions
            )
    assert rays > 1000
    assert plain_cramer_leaks > 0  # so these rays really do test the cracks


def test_rays_from_off_centre_points_never_leak():
    rng = np.random.default_rng(99)
    for _ in range(6):
        verts, faces = perturbed_icosphere(rng)
        scale = 10.0 ** rng.uniform(-2, 2)
        verts = verts * scale
        for i, j in edges_of(faces):
            origin = rng.uniform(-0.3, 0.3, 3) * scale  # inside: the inradius is > 0.6
            target = (verts[i] + verts[j]) / 2
            hits = [intersect_triangle(origin, target - origin, *verts[f]) for f in faces]
            assert any(h.hit for h in hits)


@settings(max_examples=300, deadline=None)
@given(
    corners=st.lists(points, min_size=4, max_size=4),
    origin=points,
    s=st.floats(0.01, 0.99),
)
def test_shared_edge_hits_one_triangle_or_both_at_the_same_t(corners, origin, s):
    """Two triangles P, Q, R and Q, P, S share the edge PQ (a hinge).

    Aim at a point on PQ.  Seen from the origin, if R and S lie on opposite sides of the edge
    (the hinge is not folded over), the ray must hit one triangle, or both with equal t.
    """
    P, Q, R, S = (np.array(c) for c in corners)
    origin = np.array(origin)
    target = P + s * (Q - P)
    direction = target - origin
    assume(np.linalg.norm(direction) > 1e-3)
    first = exact_triangle_solve(origin, direction, P, Q, R)
    second = exact_triangle_solve(origin, direction, Q, P, S)
    assume(first is not None and second is not None)
    assume(first[3] > Fraction(1, 1000) and second[3] > Fraction(1, 1000))  # t > 0 for both
    # Equal signs of det M (same winding as seen along the ray): R and S project on
    # opposite sides of the edge, the hinge is not folded over.
    det1 = cramer_solve(origin, direction, P, Q, R).det
    det2 = cramer_solve(origin, direction, Q, P, S).det
    assume(det1 * det2 > 0 and min(abs(det1), abs(det2)) > 1e-6)
    h1 = intersect_triangle(origin, direction, P, Q, R)
    h2 = intersect_triangle(origin, direction, Q, P, S)
    assert h1.hit or h2.hit
    if h1.hit and h2.hit:
        assert h1.t == h2.t
