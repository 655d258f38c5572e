"""The compiled intersection kernels: right against exact references, watertight, one formula with
the worked solutions, and ties decided one way."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from brute_force import exact_sphere_roots, exact_triangle_solve
from checkout import ROOT
from numba import njit

from core import shapes
from core.image_order.intersect_sphere import intersect_sphere
from core.image_order.intersect_triangle import difference_of_products, intersect_triangle, ray_shear
from core.image_order.kernels.intersect import sphere_hit, triangle_hit
from core.image_order.kernels.intrinsics.triangle4 import UNSURE, triangle_test4, triangle_test4x2


@njit
def four_at_a_time(o, d, groups, start):
    kx, ky, kz, sx, sy, sz = ray_shear(d[0], d[1], d[2])
    return triangle_test4(groups, start, kx, ky, kz, o[kx], o[ky], o[kz], sx, sy, sz, 0.0, math.inf)


@njit
def two_at_a_time(ray_a, ray_b, groups, start):
    """``triangle_test4x2`` of two rays, each ``(o, d, t_max)``, and ``triangle_test4`` of each alone."""
    tests = []
    for o, d, t_max in (ray_a, ray_b):
        kx, ky, kz, sx, sy, sz = ray_shear(d[0], d[1], d[2])
        tests.append((kx, ky, kz, o[kx], o[ky], o[kz], sx, sy, sz, 0.0, t_max))
    a, b = tests[0], tests[1]
    alone = (triangle_test4(groups, start, *a), triangle_test4(groups, start, *b))
    return triangle_test4x2(groups, start, a, b), alone


@njit
def compiled_shear(dx, dy, dz):
    return ray_shear(dx, dy, dz)

#: The stale-cache guard itself runs at import; none of its code is compiled into a kernel.
GUARD = "core.compiling.kernel_cache"


def kernel_triangle(o, d, tri):
    return triangle_hit(tuple(map(float, o)), ray_shear(*map(float, d)), np.asarray(tri, float).reshape(1, 9),
                        0, 0.0, math.inf)


def test_sphere_kernel_finds_the_exact_first_crossing_on_random_rays():
    rng = np.random.default_rng(7)
    hits = 0
    for _ in range(3000):
        o = rng.normal(size=3) * rng.choice([0.5, 3.0, 100.0])
        c = rng.normal(size=3) * 2
        r = float(rng.uniform(0.1, 4.0))
        d = c - o + rng.normal(size=3) * 1.2 * r  # aimed near the sphere: about half hit
        exact = exact_sphere_roots(o, d, c, r)
        t = sphere_hit(*o, *d, *c, r, 0.0, math.inf)
        if exact is not None and abs(exact[2] - r) <= 1e-6 * r:
            continue  # nearly tangent: the roots themselves are ill-conditioned
        admissible = [root for root in (exact or ())[:2] if root >= 0]
        if not admissible:
            assert t == math.inf
        else:
            hits += 1
            size = (np.linalg.norm(o - c) + r) / np.linalg.norm(d)  # the scene's size in units of t
            assert abs(t - admissible[0]) <= 1e-13 * size
    assert 1000 < hits < 2500


def test_sphere_kernel_from_inside_finds_the_exit():
    # From the centre of a unit sphere, straight out: the exit at t = 1 (the lecture's t_far case).
    assert sphere_hit(0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, math.inf) == 1.0
    assert sphere_hit(0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.5) == math.inf


def test_a_ray_leaving_a_sphere_gets_the_answer_of_the_roots_without_them():
    # A mirror's reflected ray and a glass ball's ray out start just outside their own ball, by
    # the scaled offset, and move away from it; sphere_hit answers them before the roots
    # (_behind).  Its answer is the roots' formula's own, bit for bit, for such rays (down to
    # grazing ones) and for rays from anywhere, at scales from 1e-200 to 1e200 and from t_min 0
    # or more; and the rays leaving a ball are the ones answered early.
    from core.image_order.intersect_sphere import sphere_roots as formula
    from core.image_order.kernels.intersect import _behind
    from core.image_order.ray_offset import error_bound

    # Outside, moving away, and yet a root rounds to -0.0, which t_min = 0 admits: a tiny ball
    # and a huge direction, where sphere_hit must not answer early.
    tiny = (-1.2555846465087333e-151, -3.0330689096012106e-151, 1.5348381102441408e-151,
            -2.626556290259407e+153, -6.3448738764486705e+153, 3.2107263370901447e+153, 0.0, 0.0, 0.0,
            2.659854650400948e-151)
    assert formula(*tiny)[7] == 0.0 and math.copysign(1.0, formula(*tiny)[7]) == -1.0
    assert math.copysign(1.0, sphere_hit(*tiny, 0.0, math.inf)) == -1.0
    rng = np.random.default_rng(36)
    early = leaving = 0
    for case in range(6000):
        scale = 10.0 ** rng.uniform(-200, 200) if case % 3 == 0 else 10.0 ** rng.uniform(-3, 4)
        c = rng.normal(size=3) * scale * rng.uniform(0, 20)
        r = scale * rng.uniform(0.1, 2.0)
        n = rng.normal(size=3)
        n /= np.linalg.norm(n)
        if case % 2 == 0:  # from the ball's surface, out by the offset, away from the ball
            leaving += 1
            p = c + r * n
            o = p + error_bound(float(np.max(np.abs(c)) + r)) * n
            side = np.cross(n, rng.normal(size=3))
            d = side / np.linalg.norm(side) + 10.0 ** rng.uniform(-18, 1) * n
        else:
            o = c + rng.normal(size=3) * r * rng.uniform(0, 3)
            d = rng.normal(size=3)
        d = d * 10.0 ** rng.uniform(-3, 3)
        t_min = float(rng.choice([0.0, 1e-4 * scale, r]))
        t_max = float(rng.choice([math.inf, 2.0 * r]))
        ray = (*map(float, o), *map(float, d), *map(float, c), float(r))
        t0, t1 = formula(*ray)[6:]
        expected = t0 if t_min <= t0 < t_max else t1 if t_min <= t1 < t_max else math.inf
        assert sphere_hit(*ray, t_min, t_max) == expected
        assert math.copysign(1.0, sphere_hit(*ray, t_min, t_max)) == math.copysign(1.0, expected)
        early += _behind(*ray, t_min)
    assert early > 0.9 * leaving


def test_triangle_kernel_matches_the_exact_barycentric_solution_on_random_rays():
    rng = np.random.default_rng(11)
    hits = misses = 0
    for _ in range(3000):
        o = rng.normal(size=3) * 2
        tri = rng.normal(size=9)
        aim = tri.reshape(3, 3).mean(axis=0) + rng.normal(size=3) * 0.4  # about a third hit
        d = aim - o
        exact = exact_triangle_solve(o, d, tri[:3], tri[3:6], tri[6:])
        t, b0, b1, b2 = kernel_triangle(o, d, tri)
        margin = Fraction(1, 10**9)
        if min(exact) > margin:
            hits += 1
            assert t == pytest.approx(float(exact[3]), rel=1e-12)
            assert (b0, b1, b2) == pytest.approx([float(w) for w in exact[:3]], abs=1e-12)
        elif min(exact) < -margin:
            misses += 1
            assert t == math.inf
    assert hits > 700 and misses > 1000


@pytest.mark.parametrize(("direction", "axis"), [
    ((1.0, 1.0, 0.0), 1), ((1.0, -1.0, 0.0), 1), ((-2.0, 2.0, 1.0), 1), ((1.0, 1.0, 1.0), 2),
    ((1.0, 0.0, -1.0), 2), ((0.0, -3.0, 3.0), 2), ((-1.0, -1.0, -1.0), 2), ((2.0, 1.0, 1.0), 0),
])
def test_on_a_tie_the_later_axis_becomes_the_ray_axis(direction, axis):
    """The largest |d| component is z in ray space; of equal ones the later axis (z, then y, then x)."""
    for shear in (ray_shear(*direction), compiled_shear(*direction)):
        kx, ky, kz, sx, sy, sz = shear
        assert kz == axis and (kx, ky) == ((axis + 1) % 3, (axis + 2) % 3)
        # The shear maps the direction exactly onto +z: (d_kx + sx d_kz, d_ky + sy d_kz, sz d_kz) = (0, 0, 1).
        assert (direction[kx] + sx * direction[kz], direction[ky] + sy * direction[kz]) == (0.0, 0.0)
        assert sz * direction[kz] == 1.0


@pytest.mark.parametrize("direction", [(1.0, 1.0, 0.0), (1.0, -1.0, 0.0), (1.0, 1.0, 1.0), (-1.0, 0.0, 1.0)])
def test_the_worked_solution_and_the_tracer_agree_bit_for_bit_on_tie_directions(direction):
    """One formula: the explanation of ``python -m app intersect triangle`` is the tracer's crossing.

    (The two used to pick different axes for such directions, and so rounded differently.)
    """
    rng = np.random.default_rng(17)
    d = np.array(direction)
    compared = 0
    for _ in range(200):
        tri = rng.normal(size=9)
        aim = tri.reshape(3, 3).mean(axis=0) + rng.normal(size=3) * 0.3
        o = aim - rng.uniform(0.5, 4.0) * d
        h = intersect_triangle(o, d, tri[:3], tri[3:6], tri[6:])
        t, b0, b1, b2 = kernel_triangle(o, d, tri)
        assert (t < math.inf) == h.hit
        if h.hit:
            compared += 1
            assert (t, b0, b1, b2) == (h.t, h.alpha, h.beta, h.gamma)
    assert compared > 50


def test_the_worked_solution_and_the_tracer_agree_bit_for_bit_on_spheres():
    rng = np.random.default_rng(23)
    for _ in range(300):
        o, c, d = rng.normal(size=3) * 3, rng.normal(size=3), rng.normal(size=3)
        r = float(rng.uniform(0.2, 3.0))
        s = intersect_sphere(o, d, c, r)
        t = sphere_hit(*o, *d, *c, r, 0.0, math.inf)
        assert t == (math.inf if s.t is None else s.t)


def test_difference_of_products_has_the_exact_sign_and_is_antisymmetric():
    rng = np.random.default_rng(3)
    for _ in range(2000):
        a, b = rng.normal(size=2)
        # c*d equal to a*b up to the last bits: the rounded difference is untrustworthy here.
        c = float(np.nextafter(a, np.inf)) if rng.random() < 0.5 else a
        d = b * (1 + rng.integers(-3, 4) * 2.0**-52)
        exact = Fraction(a) * Fraction(b) - Fraction(c) * Fraction(d)
        value = difference_of_products(a, b, c, d)
        assert np.sign(value) == np.sign(exact)
        assert difference_of_products(c, d, a, b) == -value


def test_a_ray_through_a_shared_edge_hits_both_triangles_at_the_same_exact_t():
    """The tie rule for edges: closed triangles, so both own the shared edge, with one t and one point."""
    # Two triangles sharing the diagonal of the unit square; rays straight down and slanted through it.
    a, b, c, d = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)
    first, second = np.array([a, b, c]), np.array([a, c, d])
    for s in np.linspace(0.0, 1.0, 101):
        for direction in ((0.0, 0.0, -1.0), (0.25, 0.25, -1.0), (-0.5, -0.5, -0.75)):
            o = np.array((s, s, 0.0)) - 1.5 * np.array(direction)
            hits = [kernel_triangle(o, direction, tri.ravel()) for tri in (first, second)]
            records = [intersect_triangle(o, direction, *tri) for tri in (first, second)]
            assert all(h.hit for h in records) and all(h[0] < math.inf for h in hits), s
            assert hits[0][0] == hits[1][0] == records[0].t == records[1].t
            assert records[0].point.tolist() == records[1].point.tolist()
            exact = exact_triangle_solve(o, direction, *first)[3]
            assert abs(hits[0][0] - float(exact)) <= 2 * math.ulp(float(exact))
    # Just off the edge, on either side: exactly one triangle.
    for s in np.linspace(0.05, 0.95, 19):
        for side in (-1e-12, 1e-12):
            o = (s + side, s - side, 1.0)
            hit = [kernel_triangle(o, (0.0, 0.0, -1.0), tri.ravel())[0] < math.inf for tri in (first, second)]
            assert sum(hit) == 1


def test_a_ray_through_a_shared_corner_hits_every_triangle_around_it_at_that_corner():
    fan = shapes.cone((0.25, 0.0, -0.5), 1.0, 2.0, segments=7)  # every side triangle meets at the apex
    apex = np.array([0.25, 2.0, -0.5])
    around = [tri for tri in fan.corners if any(np.array_equal(v, apex) for v in tri)]
    assert len(around) == 7
    # Directions and distances of powers of two: the ray passes exactly through the apex at t = k.
    for d in ((0.0, -1.0, 0.0), (0.5, -1.0, 0.25), (-0.25, -0.5, 0.125), (1.0, -1.0, 0.5)):
        for k in (0.5, 4.0, 64.0):
            o = apex - k * np.array(d)
            ts = {kernel_triangle(o, d, tri.ravel())[0] for tri in around}
            ts |= {intersect_triangle(o, d, *tri).t for tri in around}
            assert ts == {k}


def test_rays_from_inside_a_closed_mesh_always_hit():
    # pbrt's Triangle.Watertight: a perturbed tessellated sphere, rays from near its centre.
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=12, segments=16)
    rng = np.random.default_rng(5)
    corners = (ball.vertices * (1 + 0.05 * rng.standard_normal((len(ball.vertices), 1))))[ball.triangles]
    rows = corners.reshape(-1, 9)
    for _ in range(400):
        o = tuple(rng.normal(size=3) * 0.2)
        d = rng.normal(size=3)
        if rng.random() < 0.3:  # aim exactly at a vertex or an edge midpoint
            tri = corners[rng.integers(len(corners))]
            target = tri[0] if rng.random() < 0.5 else (tri[0] + tri[1]) / 2
            d = target - np.array(o)
        shear = ray_shear(*map(float, d))
        best = min(triangle_hit(o, shear, rows, k, 0.0, math.inf)[0] for k in range(len(rows)))
        assert best < math.inf


def test_four_triangles_at_a_time_give_the_scalar_test_bit_for_bit_or_defer_to_it():
    """The vector test either computes exactly the scalar test's t (inf for a miss) or marks the
    lane UNSURE; rays aimed exactly at vertices and edge midpoints need the exact fallback.  Where
    it decides a hit, its edge functions over their sum are the scalar test's barycentric weights,
    bit for bit (the walk takes a hit's weights from them)."""
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=12, segments=16)
    rng = np.random.default_rng(9)
    corners = (ball.vertices * (1 + 0.05 * rng.standard_normal((len(ball.vertices), 1))))[ball.triangles]
    corners = corners[: len(corners) // 4 * 4]
    rows = corners.reshape(-1, 9)
    # Group g, corner v, axis a, lane q at g * 36 + v * 12 + a * 4 + q.
    groups = np.ascontiguousarray(corners.reshape(-1, 4, 3, 3).transpose(0, 2, 3, 1)).reshape(-1)
    unsure = decided = hits = 0
    for _ in range(300):
        o = rng.normal(size=3) * 0.2
        g = int(rng.integers(len(rows) // 4))
        tri = corners[4 * g + int(rng.integers(4))]
        target = (tri[0], (tri[0] + tri[1]) / 2, tri.mean(axis=0))[int(rng.integers(3))]
        d = target - o
        lanes, *edges, _ = four_at_a_time(tuple(o), tuple(d), groups, g * 36)
        shear = ray_shear(*map(float, d))
        for q in range(4):
            scalar, *weights = triangle_hit(tuple(o), shear, rows, 4 * g + q, 0.0, math.inf)
            if lanes[q] == UNSURE:
                unsure += 1
            else:
                decided += 1
                assert lanes[q] == scalar or (math.isinf(lanes[q]) and math.isinf(scalar))
                if scalar < math.inf:
                    hits += 1
                    e = [edges[k][q] for k in range(3)]
                    assert [e[k] / (e[0] + e[1] + e[2]) for k in range(3)] == weights
    assert unsure > 0 and decided > 3 * unsure and hits > 50


def test_two_rays_at_a_time_give_each_ray_its_own_four_lanes_bit_for_bit():
    """The packets test a leaf's group against two rays in one vector of eight lanes: each ray's
    half must be exactly its own four-lane test (t, UNSURE marks, edge functions and the mask of
    the lanes that can matter), whatever
    shear axes and range the other ray has.  The rays start at different points, aim at corners,
    edge midpoints and centres of the group's triangles (so that some lanes are UNSURE), and one
    of each pair stops before its crossing half of the time."""
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=12, segments=16)
    rng = np.random.default_rng(11)
    corners = (ball.vertices * (1 + 0.05 * rng.standard_normal((len(ball.vertices), 1))))[ball.triangles]
    corners = corners[: len(corners) // 4 * 4]
    groups = np.ascontiguousarray(corners.reshape(-1, 4, 3, 3).transpose(0, 2, 3, 1)).reshape(-1)
    mixed_axes = unsure = hits = 0
    for _ in range(300):
        g = int(rng.integers(len(corners) // 4))
        rays = []
        for _ in range(2):
            o = rng.normal(size=3) * 0.2
            tri = corners[4 * g + int(rng.integers(4))]
            target = (tri[0], (tri[0] + tri[1]) / 2, tri.mean(axis=0))[int(rng.integers(3))]
            rays.append((tuple(o), tuple(target - o), float(rng.choice([math.inf, 0.5]))))
        pair, alone = two_at_a_time(rays[0], rays[1], groups, g * 36)
        for ray in range(2):
            *half, candidates = pair[5 * ray:5 * ray + 5]
            *own, own_candidates = alone[ray]
            assert np.array(half).tobytes() == np.array(own).tobytes()
            # The lanes that can matter: a crossing before t_max, or UNSURE.
            assert candidates == own_candidates == sum(1 << q for q in range(4) if half[0][q] < rays[ray][2])
            unsure += sum(t == UNSURE for t in half[0])
            hits += sum(math.isfinite(t) for t in half[0])
        mixed_axes += ray_shear(*rays[0][1])[:3] != ray_shear(*rays[1][1])[:3]
    assert mixed_axes > 30 and unsure > 0 and hits > 100


def test_the_stale_cache_guard_hashes_every_core_module_a_kernel_compiles_in():
    """numba checks a cached kernel only against its own file; ``SOURCES`` must name the rest.

    Every kernel file is listed, and the list is closed under ``core`` imports: a listed file's
    ``core`` imports (whose ``register_jitable`` formulas it may compile in) are listed too.
    """
    import ast

    from core.image_order.kernels import jit as kernel_jit

    listed = {p.resolve() for p in kernel_jit.SOURCES}
    kernel_files = sorted(Path(kernel_jit.__file__).resolve().parent.rglob("*.py"))
    assert kernel_files and set(kernel_files) <= listed
    root = Path(kernel_jit.__file__).resolve().parents[3]
    for path in sorted(listed):
        for node in ast.walk(ast.parse(path.read_text())):
            module = (node.module or "") if isinstance(node, ast.ImportFrom) else ""
            if module.startswith("core") and module != GUARD:
                target = root / (node.module.replace(".", "/") + ".py")
                if not target.exists():  # a package: the names imported are its modules
                    target = None
                    for alias in node.names:
                        module = root / node.module.replace(".", "/") / f"{alias.name}.py"
                        assert module.resolve() in listed, f"{path.name} compiles in {module}"
                if target is not None:
                    assert target.resolve() in listed, f"{path.name} compiles in {target}, not in SOURCES"
    # The flat arrays' layout and the formulas the kernels share with the worked solutions and the
    # camera are among them.
    names = {p.name for p in listed}
    assert {"flat_layout.py", "intersect_sphere.py", "intersect_triangle.py", "ray_casting.py",
            "camera.py"} <= names


_BORROWED_RETURNS = """
import json

from numba import types

import core.image_order.ray_tracing
import core.image_order.ray_tree
from core.image_order.kernels import render  # noqa: F401 -- every kernel module, so BORROWING is whole
from core.image_order.kernels.jit import BORROWING


def arrays_in(returned):
    if isinstance(returned, types.BaseTuple):
        return [a for part in returned.types for a in arrays_in(part)]
    return [returned] if isinstance(returned, types.Array) else []


signatures = []
for dispatcher in BORROWING:
    cache = dispatcher._cache
    for key in cache._cache_file._load_index():  # every version compiled on this machine
        compiled = cache.load_overload(key[0], dispatcher.targetctx)
        if compiled is not None:
            signatures.append((dispatcher.py_func.__name__, compiled.signature.return_type))
print(json.dumps({"compiled": len(signatures),
                  "returning arrays": [[name, str(r)] for name, r in signatures if arrays_in(r)]}))
"""


def test_no_kernel_that_borrows_its_arrays_returns_one():
    # A helper compiled without reference counting hands back an array its caller would count as its
    # own and free too early. The kernel cache holds every helper's compiled versions, written when
    # `python -m app compile` (in .ci/test.sh) compiled every kernel group from its warm-ups, which
    # render every method and mode and a ray tree: a process reads their signatures from there.
    import json
    import subprocess
    import sys

    done = subprocess.run([sys.executable, "-c", _BORROWED_RETURNS], cwd=ROOT, capture_output=True,
                          text=True, timeout=300)
    assert done.returncode == 0, done.stderr[-2000:]
    found = json.loads(done.stdout.splitlines()[-1])
    assert found["compiled"] >= 20
    assert found["returning arrays"] == []


def test_a_line_passed_over_as_far_from_a_sphere_is_one_the_sphere_test_finds_no_roots_for():
    # Shadow rays skip the roots of a possible blocker's bounding sphere when the line clearly
    # passes it by.  Near and far from tangency, on spheres of all sizes and distances, every line
    # so passed over is one sphere_roots calls a miss, and every line out by more than 1e-8 of
    # |f|^2 + r^2 in squared distance (f: the line's start minus the centre) is passed over.
    from core.image_order.kernels.accel_spheres import bounding_roots
    from core.image_order.kernels.shade import _far_from_line

    rng = np.random.default_rng(36)
    passed = 0
    for _ in range(4000):
        scale = 10.0 ** rng.uniform(-3, 4)
        centre = rng.normal(size=3) * scale * rng.uniform(0, 50)
        r = scale * rng.uniform(0.1, 1.0)
        d = rng.normal(size=3)
        d /= np.linalg.norm(d)
        side = np.cross(d, rng.normal(size=3))
        side /= np.linalg.norm(side)
        gap = r * (1.0 + 10.0 ** rng.uniform(-16, -1) * rng.choice([-1.0, 1.0]))
        origin = centre + gap * side - rng.uniform(-5, 5) * scale * d
        bounding = np.array([[*centre, r]])
        o, direction = tuple(origin), tuple(d)
        if _far_from_line(o, direction, bounding, 0):
            passed += 1
            assert bounding_roots(o, direction, bounding, 0) == (math.inf, math.inf)
        f2 = float(np.sum((origin - centre) ** 2))
        if gap**2 > r**2 + 1e-8 * (f2 + r**2):
            assert _far_from_line(o, direction, bounding, 0)
    assert passed > 500
