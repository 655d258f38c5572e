"""Property tests that the robust methods hold over the whole space of inputs (pbrt's manner).

Each test draws seeded inputs with hypothesis (``derandomize=True``, bounded
``max_examples``), compares with a reference that does not share the code
under test (exact rationals, mpmath at 50+ digits, a ray caster, a point-in-
polygon test), and states its tolerance with the rounding bound it comes from.
Hypothesis prints the counterexample of any failure.
"""

import math
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from hypothesis import HealthCheck, assume, given, settings
from hypothesis import strategies as st

from core import shapes
from core.camera import Camera
from core.hard_cases import shadow_acne
from core.hard_cases.ray_cast_reference import reference
from core.image_order.flat_scene import TraceSettings
from core.image_order.intersect_sphere import TANGENT_TOLERANCE, intersect_sphere
from core.image_order.intersect_triangle import intersect_triangle
from core.image_order.ray_offset import error_bound, offset_ray_origin
from core.image_order.ray_tracing import render_trace
from core.object_order import fragments, zbuffer
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Mesh, PointLight, Scene, Sphere

U = 2.0**-53


def prop(examples: int) -> settings:
    """Seeded, bounded hypothesis settings: the same examples on every run, no time limit per example."""
    return settings(max_examples=examples, deadline=None, derandomize=True, database=None,
                    suppress_health_check=[HealthCheck.too_slow])


def _unit(v) -> np.ndarray:
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


units = st.tuples(*[st.floats(-1.0, 1.0)] * 3).filter(lambda v: np.linalg.norm(v) > 0.1).map(_unit)


def decades(lo, hi):
    return st.floats(lo, hi).map(lambda e: 10.0**e)


# ---------------------------------------------------------------------------- ray-sphere


def _exact_line(origin, direction, center, radius):
    """``(|f|, |d|, r² - |v|², roots)`` of the float inputs: rationals, square roots at 60 digits."""
    o, d, c = ([Fraction(float(x)) for x in v] for v in (origin, direction, center))
    r = Fraction(float(radius))
    f = [p - q for p, q in zip(o, c, strict=True)]
    a = sum(x * x for x in d)
    hb = sum(x * y for x, y in zip(f, d, strict=True))
    ff = sum(x * x for x in f)
    s2 = r * r - (ff - hb * hb / a)  # r² - |v|², exactly
    with mpmath.workdps(60):
        to = lambda q: mpmath.mpf(q.numerator) / q.denominator  # noqa: E731
        roots = None
        if s2 > 0:
            root = mpmath.sqrt(to(s2 * a))
            roots = ((-to(hb) - root) / to(a), (-to(hb) + root) / to(a))
        return (float(mpmath.sqrt(to(ff))), float(mpmath.sqrt(to(a))), s2, r, roots)


@prop(300)
@given(decades(-6, 9), units, decades(-6, 9), units, decades(-3, 6), st.floats(0.0, 1.5), units)
def test_ray_sphere_roots_agree_with_mpmath(center_mag, center_dir, origin_mag, origin_dir, radius, aim,
                                            aim_dir):
    """Robust roots within 64 u (|f| + r)(1 + r / s) / |d| of the exact ones, s = √(r² - |v|²).

    Tolerance: ``f``, ``f·d`` and ``|v|`` each carry a few units of rounding of
    ``|f| + r``; a root moves by that over ``|d|``, amplified by ``r / s`` through the
    square root (the problem's own condition number near tangency).
    """
    center = center_mag * center_dir
    origin = origin_mag * origin_dir
    direction = center + aim * radius * aim_dir - origin
    assume(np.max(np.abs(direction)) > 1e-50)
    s = intersect_sphere(origin, direction, center, radius)
    for value in (s.a, s.b, s.c, s.discriminant, s.line_distance):
        assert math.isfinite(value)
    for value in (s.t_near, s.t_far, s.t):
        assert value is None or math.isfinite(value)
    f_norm, d_norm, s2, r, roots = _exact_line(origin, direction, center, radius)
    band = TANGENT_TOLERANCE * (f_norm + radius)
    # Classification: never contradicts the exact geometry beyond twice the tangent band.
    if s2 > 0 and math.sqrt(float(s2)) > 0 and float(r) - math.sqrt(max(0.0, float(r * r - s2))) > 2 * band:
        assert s.classification == "crosses"
    if s2 < 0 and math.sqrt(float(r * r - s2)) - float(r) > 2 * band:
        assert s.classification == "misses"
    if s.classification == "crosses" and roots is not None:
        root_s = math.sqrt(float(s2))
        tol = 64 * U * (f_norm + radius) * (1 + radius / root_s) / d_norm
        assert abs(s.t_near - float(roots[0])) <= tol
        assert abs(s.t_far - float(roots[1])) <= tol


@prop(60)
@given(decades(-6, 9), units, decades(-3, 6), units, decades(-16, -2), st.integers(0, 2**32 - 1))
def test_moving_a_ray_outward_never_turns_a_miss_into_a_crossing(center_mag, center_dir, radius, d,
                                                                  step, seed):
    """Rays swept across tangency, ordered by their exact distance from the centre: the verdict
    goes crosses → tangent → misses and never back (no tolerance: a verdict is exact)."""
    center = center_mag * center_dir
    side = _unit(np.cross(d, np.eye(3)[np.argmin(np.abs(d))]))  # perpendicular to d
    rng = np.random.default_rng(seed)
    ks = np.sort(rng.uniform(-20, 20, 16))
    rays = []
    for k in ks:
        origin = center - 3 * radius * d + radius * (1 + k * step) * side
        s = intersect_sphere(origin, d, center, radius)
        _, _, s2, _, _ = _exact_line(origin, d, center, radius)
        rays.append((-s2, s.classification))
    rank = {"crosses": 0, "tangent": 1, "misses": 2}
    ordered = [rank[c] for _, c in sorted(rays, key=lambda item: item[0])]
    assert ordered == sorted(ordered), sorted(rays, key=lambda item: item[0])


# ---------------------------------------------------------------------------- ray-triangle


def _perturbed_sphere(rng, offset):
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=5, segments=8)
    bump = 1.0 + 0.1 * rng.uniform(-1, 1, (len(ball.vertices), 1))
    return ball.vertices * bump + offset, ball.triangles


def _hits(origin, direction, vertices, triangles):
    return [(i, h) for i, tri in enumerate(triangles)
            if (h := intersect_triangle(origin, direction, *vertices[tri])).hit]


@prop(40)
@given(st.integers(0, 2**32 - 1), st.sampled_from([0.0, 1e4, 1e6]), st.sampled_from(["random", "vertex",
                                                                                       "edge"]))
def test_rays_from_inside_a_closed_mesh_always_hit_and_spawned_rays_never_rehit(seed, shift, aim):
    """No tolerance: a closed mesh has no holes, and the scaled offset leaves the surface for good."""
    rng = np.random.default_rng(seed)
    offset = shift * _unit(rng.normal(size=3))
    vertices, triangles = _perturbed_sphere(rng, offset)
    origin = offset + 0.5 * rng.uniform(-1, 1, 3)  # the perturbed radius is >= 0.9
    if aim == "vertex":
        direction = vertices[rng.integers(len(vertices))] - origin
    elif aim == "edge":
        tri = triangles[rng.integers(len(triangles))]
        a, b = vertices[tri[0]], vertices[tri[1]]
        direction = a + rng.uniform() * (b - a) - origin
    else:
        direction = rng.normal(size=3)
    hits = _hits(origin, direction, vertices, triangles)
    assert hits, (origin.tolist(), direction.tolist())
    i, h = min(hits, key=lambda item: item[1].t)
    A, B, C = vertices[triangles[i]]
    normal = _unit(np.cross(B - A, C - A))
    for w in (rng.normal(size=3), -direction, direction):
        magnitude = float(np.abs(vertices[triangles[i]]).max())
        spawned = offset_ray_origin(h.point, normal, error_bound(magnitude), w)
        again = intersect_triangle(spawned, w, A, B, C)
        assert not again.hit, (h.point.tolist(), w.tolist(), again.t)


# ---------------------------------------------------------------------------- clipping

CLIP_CAMERA = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=60.0, near=0.5, far=40.0,
                     width=48, height=36)


@prop(40)
@given(st.integers(0, 2**32 - 1), st.integers(1, 2))
def test_clipped_triangles_cover_what_the_ray_caster_sees(seed, n_behind):
    """Triangles with one or two corners behind the eye: the rasterized coverage equals the ray
    cast one on every pixel whose centre is more than 1/64 pixel from an edge (the rasterizer
    snaps corners to 1/256 pixel)."""
    rng = np.random.default_rng(seed)
    corners = np.column_stack([rng.uniform(-4, 4, 3), rng.uniform(-3, 3, 3), rng.uniform(-12, -1, 3)])
    corners[:n_behind, 2] = rng.uniform(0.05, 6.0, n_behind)  # view z > 0: behind the eye
    mesh = Mesh(corners, [[0, 1, 2]], Material(ambient=1.0, diffuse=0.0))
    result = render_raster(Scene(camera=CLIP_CAMERA, objects=(mesh,)),
                           RasterSettings(back_face_culling=False))
    seen, certain = reference(CLIP_CAMERA, corners[None])
    covered = result.zbuffer < zbuffer.FAR_DEPTH
    wrong = (covered != (seen >= 0)) & certain
    assert not wrong.any(), (corners.tolist(), np.argwhere(wrong)[:5].tolist())


# ---------------------------------------------------------------------------- fill rule


def _inside_polygon(px, py, poly):
    """Even-odd test of points against a closed polygon, and their distance from its outline."""
    inside = np.zeros(px.shape, dtype=bool)
    dist = np.full(px.shape, np.inf)
    for (x0, y0), (x1, y1) in zip(poly, np.roll(poly, -1, axis=0), strict=True):
        crosses = (y0 > py) != (y1 > py)
        with np.errstate(divide="ignore", invalid="ignore"):
            x_at = x0 + (py - y0) * (x1 - x0) / (y1 - y0)
        inside ^= crosses & (px < x_at)
        ex, ey = x1 - x0, y1 - y0
        s = np.clip(((px - x0) * ex + (py - y0) * ey) / (ex * ex + ey * ey), 0, 1)
        dist = np.minimum(dist, np.hypot(px - x0 - s * ex, py - y0 - s * ey))
    return inside, dist


@prop(30)
@given(st.integers(0, 2**32 - 1), st.integers(2, 7), st.integers(2, 6))
def test_quads_split_into_triangle_pairs_cover_each_pixel_exactly_once(seed, nx, ny):
    """A jittered grid of quads, each split along a random diagonal: every pixel centre inside the
    grid's outline (by more than 1/128 pixel) gets exactly one fragment, every other one none.
    Corners are moved to pixel centres, so many shared edges pass exactly through pixel centres,
    where only the fill rule decides (no tolerance: coverage is exact integer arithmetic)."""
    rng = np.random.default_rng(seed)
    width, height = 64, 48
    gx, gy = np.meshgrid(np.linspace(5.3, 58.7, nx + 1), np.linspace(4.1, 43.9, ny + 1))
    cell = min(53.4 / nx, 39.8 / ny)
    xy = np.stack([gx, gy], axis=-1) + rng.uniform(-0.2, 0.2, (ny + 1, nx + 1, 2)) * cell
    xy = np.floor(xy) + 0.5
    index = np.arange((ny + 1) * (nx + 1)).reshape(ny + 1, nx + 1)
    tris = []
    for j in range(ny):
        for i in range(nx):
            a, b, c, d = index[j, i], index[j, i + 1], index[j + 1, i + 1], index[j + 1, i]
            tris += [(a, b, c), (a, c, d)] if rng.uniform() < 0.5 else [(a, b, d), (b, c, d)]
    corners = np.array(tris, dtype=np.int64)
    flat = xy.reshape(-1, 2)
    n = len(corners)
    zpass = fragments.draw(flat, np.full(len(flat), 0.5), corners, np.arange(n), np.ones((n, 3)), np.ones(n),
                         width, height, (0.0, 0.0, 0.0), record=True)
    count = np.bincount(zpass.fragments.pixel, minlength=width * height).reshape(height, width)
    outline = np.vstack([xy[0, :], xy[1:, -1], xy[-1, -2::-1], xy[-2:0:-1, 0]])
    px, py = np.meshgrid(np.arange(width) + 0.5, np.arange(height) + 0.5)
    inside, dist = _inside_polygon(px, py, outline)
    certain = dist > 1 / 128
    assert count.max() <= 1, np.argwhere(count > 1)[:5].tolist()
    assert (count[inside & certain] == 1).all(), np.argwhere(inside & certain & (count != 1))[:5].tolist()
    assert (count[~inside & certain] == 0).all()


# ---------------------------------------------------------------------------- shadow acne, in the tracer


def _darker(image, reference_image, mask):
    """Pixels of ``mask`` darker than the reference by more than 1e-6 (summed over RGB)."""
    return (image.sum(axis=2) < reference_image.sum(axis=2) - 1e-6) & mask


@pytest.mark.parametrize("distance", [0.0, 1e4, 1e6])
def test_lit_plane_has_no_self_shadowed_pixel_with_the_scaled_offset(distance):
    """The app's tracer on a lit square with a small ball 2.5 units above it (so that the tracer
    casts shadow rays at all, and one real shadow falls on the square).  The reference is the same
    render with shadow rays ignoring everything within 1 unit of their start: the ball's shadow is
    kept, self-shadowing cannot occur.  The scaled render may not be darker at any pixel of the
    square.  Tolerance 1e-6: the renders shade hit points that differ by rounding (about 1e-10 of
    the colour at 10^6), while a shadowed pixel loses its whole diffuse term (more than 0.1 here)."""
    triangles, camera, light = shadow_acne.lit_square(distance)
    mesh = Mesh(triangles.reshape(-1, 3), [[0, 1, 2], [3, 4, 5]], Material(color=(0.8, 0.8, 0.7)))
    center = triangles[0].mean(axis=0) * 0.5 + triangles[1].mean(axis=0) * 0.5
    normal = _unit(np.cross(triangles[0, 1] - triangles[0, 0], triangles[0, 2] - triangles[0, 0]))
    normal = normal if np.dot(normal, light - center) > 0 else -normal
    ball = Sphere(tuple(center + 2.5 * normal), 0.4)
    scene = Scene(camera=camera, objects=(mesh, ball), lights=(PointLight(tuple(light)),))
    first = render_trace(scene, TraceSettings(mode="raycast"))
    assert first.stats["rays"]["shadow"] > 0
    on_square = first.object_index == 0
    assert on_square.sum() > 1000
    scaled = render_trace(scene, TraceSettings(mode="raycast", offset="scaled")).color
    reference_image = render_trace(scene, TraceSettings(mode="raycast", offset="fixed", epsilon=1.0)).color
    assert not _darker(scaled, reference_image, on_square).any(), \
        np.argwhere(_darker(scaled, reference_image, on_square))[:5].tolist()
    # The comparison can fail: with no offset at all the same scene does show acne.
    bare = render_trace(scene, TraceSettings(mode="raycast", offset="fixed", epsilon=0.0)).color
    assert _darker(bare, reference_image, on_square).sum() > 100
