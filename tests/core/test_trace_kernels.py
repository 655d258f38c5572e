"""The compiled intersection kernels agree with the scalar reference functions, and are watertight."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from numba import njit

from core import shapes
from core.image_order.intersect_sphere import intersect_sphere
from core.image_order.intersect_triangle import intersect_triangle
from core.image_order.kernels.intersect import difference_of_products, ray_shear, sphere_hit, triangle_hit
from core.image_order.kernels.intrinsics.triangle4 import UNSURE, triangle_test4


@njit
def four_at_a_time(o, d, groups, start):
    kx, ky, kz, sx, sy, sz = ray_shear(d[0], d[1], d[2])
    return triangle_test4(groups, start, kx, ky, kz, o[kx], o[ky], o[kz], sx, sy, sz, 0.0, math.inf)


def kernel_triangle(o, d, tri):
    return triangle_hit(tuple(map(float, o)), ray_shear(*map(float, d)), np.asarray(tri, float).reshape(1, 9),
                        0, 0.0, math.inf)


def test_sphere_kernel_matches_the_reference_on_random_rays():
    rng = np.random.default_rng(7)
    hits = 0
    for _ in range(3000):
        o = rng.normal(size=3) * rng.choice([0.5, 3.0, 100.0])
        c = rng.normal(size=3) * 2
        r = float(rng.uniform(0.1, 4.0))
        d = c - o + rng.normal(size=3) * 1.2 * r  # aimed near the sphere: about half hit
        ref = intersect_sphere(o, d, c, r)
        t = sphere_hit(*o, *d, *c, r, 0.0, math.inf)
        if ref.t is None:
            assert t == math.inf
        else:
            hits += 1
            assert t == pytest.approx(ref.t, rel=1e-13, abs=1e-300)
    assert 1000 < hits < 2500


def test_sphere_kernel_from_inside_finds_the_exit():
    # From the centre of a unit sphere, straight out: the exit at t = 1 (the lecture's t_far case).
    assert sphere_hit(0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, math.inf) == 1.0
    assert sphere_hit(0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.5) == math.inf


def test_triangle_kernel_matches_the_reference_on_random_rays():
    rng = np.random.default_rng(11)
    hits = 0
    for _ in range(3000):
        o = rng.normal(size=3) * 2
        tri = rng.normal(size=9)
        aim = tri.reshape(3, 3).mean(axis=0) + rng.normal(size=3) * 0.4  # about a third hit
        d = aim - o
        ref = intersect_triangle(o, d, tri[:3], tri[3:6], tri[6:])
        t, b0, b1, b2 = kernel_triangle(o, d, tri)
        assert (t < math.inf) == ref.hit
        if ref.hit:
            hits += 1
            assert t == pytest.approx(ref.t, rel=1e-12)
            assert (b0, b1, b2) == pytest.approx((ref.alpha, ref.beta, ref.gamma), abs=1e-12)
    assert hits > 700


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


def test_rays_through_a_shared_edge_hit_a_triangle():
    # Two triangles sharing the diagonal of the unit square; rays straight down through it.
    a, b, c, d = (0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (1.0, 1.0, 0.0), (0.0, 1.0, 0.0)
    first, second = np.array([a, b, c]).ravel(), np.array([a, c, d]).ravel()
    for s in np.linspace(0.0, 1.0, 101):
        o = (s, s, 1.0)
        hit = [kernel_triangle(o, (0.0, 0.0, -1.0), tri)[0] for tri in (first, second)]
        assert min(hit) == 1.0


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
    lane UNSURE; rays aimed exactly at vertices and edge midpoints need the exact fallback."""
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=12, segments=16)
    rng = np.random.default_rng(9)
    corners = (ball.vertices * (1 + 0.05 * rng.standard_normal((len(ball.vertices), 1))))[ball.triangles]
    corners = corners[: len(corners) // 4 * 4]
    rows = corners.reshape(-1, 9)
    # Group g, corner v, axis a, lane q at g * 36 + v * 12 + a * 4 + q.
    groups = np.ascontiguousarray(corners.reshape(-1, 4, 3, 3).transpose(0, 2, 3, 1)).reshape(-1)
    unsure = decided = 0
    for _ in range(300):
        o = rng.normal(size=3) * 0.2
        g = int(rng.integers(len(rows) // 4))
        tri = corners[4 * g + int(rng.integers(4))]
        target = (tri[0], (tri[0] + tri[1]) / 2, tri.mean(axis=0))[int(rng.integers(3))]
        d = target - o
        lanes = four_at_a_time(tuple(o), tuple(d), groups, g * 36)
        shear = ray_shear(*map(float, d))
        for q in range(4):
            scalar = triangle_hit(tuple(o), shear, rows, 4 * g + q, 0.0, math.inf)[0]
            if lanes[q] == UNSURE:
                unsure += 1
            else:
                decided += 1
                assert lanes[q] == scalar or (math.isinf(lanes[q]) and math.isinf(scalar))
    assert unsure > 0 and decided > 3 * unsure


def test_the_stale_cache_guard_hashes_every_core_module_a_kernel_compiles_in():
    """numba checks a cached kernel only against its own file; ``SOURCES`` must name the rest."""
    import ast

    from core.image_order.kernels import jit as kernel_jit

    listed = {p.resolve() for p in kernel_jit.SOURCES}
    kernel_files = sorted(Path(kernel_jit.__file__).resolve().parent.rglob("*.py"))
    assert kernel_files and set(kernel_files) <= listed
    root = Path(kernel_jit.__file__).resolve().parents[3]
    for path in kernel_files:
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.ImportFrom) and (node.module or "").startswith("core."):
                target = root / (node.module.replace(".", "/") + ".py")
                if not target.exists():  # a package: the names imported are its modules
                    target = None
                    for alias in node.names:
                        module = root / node.module.replace(".", "/") / f"{alias.name}.py"
                        assert module.resolve() in listed, f"{path.name} compiles in {module}"
                if target is not None:
                    assert target.resolve() in listed, f"{path.name} compiles in {target}, not in SOURCES"
