"""Ray-sphere crossings against hand-worked numbers and exact (Fraction/Decimal) references."""

import math
from decimal import Decimal, localcontext
from fractions import Fraction

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from core.image_order.intersect_sphere import intersect_sphere, intersect_sphere_segment


def exact_quadratic(origin, direction, center, radius):
    """``a, b, c`` and ``Δ = b² - 4ac`` of the lecture's quadratic, in exact rationals."""
    f = [Fraction(o) - Fraction(c) for o, c in zip(origin, center, strict=True)]
    d = [Fraction(x) for x in direction]
    a = sum(x * x for x in d)
    b = 2 * sum(fi * di for fi, di in zip(f, d, strict=True))
    c = sum(fi * fi for fi in f) - Fraction(radius) ** 2
    return a, b, c, b * b - 4 * a * c


def dec(q: Fraction) -> Decimal:
    return Decimal(q.numerator) / Decimal(q.denominator)


def reference_roots(origin, direction, center, radius):
    """Both roots ``(-b ∓ √Δ) / 2a`` to 50 digits (``None`` when Δ < 0)."""
    a, b, c, disc = exact_quadratic(origin, direction, center, radius)
    if disc < 0:
        return None
    with localcontext() as ctx:
        ctx.prec = 50
        root = dec(disc).sqrt()
        return (-dec(b) - root) / (2 * dec(a)), (-dec(b) + root) / (2 * dec(a))


def exact_line_distance(origin, direction, center) -> float:
    """Distance from ``center`` to the line, |f|² - (f·d)²/(d·d) exactly, rooted to 50 digits."""
    f = [Fraction(o) - Fraction(c) for o, c in zip(origin, center, strict=True)]
    d = [Fraction(x) for x in direction]
    fd = sum(fi * di for fi, di in zip(f, d, strict=True))
    v2 = sum(fi * fi for fi in f) - fd * fd / sum(x * x for x in d)
    with localcontext() as ctx:
        ctx.prec = 50
        return float(dec(v2).sqrt())


# --- the lecture's exercise --------------------------------------------------------------

LECTURE = dict(start=(2, 1, 2), end=(10, 6, 6), center=(6, 4, 6), radius=10)


def test_lecture_exercise_by_hand():
    # f = (2-6, 1-4, 2-6) = (-4, -3, -4), (i, j, k) = (8, 5, 4)
    # a = 64 + 25 + 16 = 105, b = 2(-32 - 15 - 16) = -126, c = 16 + 9 + 16 - 100 = -59
    # Δ = 126² + 4·105·59 = 15876 + 24780 = 40656
    assert exact_quadratic((2, 1, 2), (8, 5, 4), (6, 4, 6), 10) == (105, -126, -59, 40656)


def test_lecture_exercise_segment_does_not_cross():
    s = intersect_sphere_segment(**LECTURE)
    assert (s.a, s.b, s.c) == (105.0, -126.0, -59.0)
    assert s.half_b == -63.0
    assert s.discriminant == pytest.approx(40656, rel=1e-13)
    assert s.classification == "crosses"
    t_near, t_far = reference_roots((2, 1, 2), (8, 5, 4), (6, 4, 6), 10)
    assert round(t_near, 4) == Decimal("-0.3602") and round(t_far, 4) == Decimal("1.5602")
    assert s.t_near == pytest.approx(float(t_near), rel=1e-14)
    assert s.t_far == pytest.approx(float(t_far), rel=1e-14)
    # Both end points are inside the sphere, so the segment never reaches the surface.
    assert s.origin_inside
    assert s.is_segment and s.t_max == 1.0
    assert not s.hit
    assert s.t is None and s.point is None and s.normal is None and s.chosen is None
    assert "both ends of the segment are inside" in s.reason
    # The infinite ray leaves the sphere at t_far.
    assert s.ray_hit_t == pytest.approx(float(t_far), rel=1e-14)


def test_lecture_exercise_as_a_ray_exits_at_t_far():
    s = intersect_sphere((2, 1, 2), (8, 5, 4), (6, 4, 6), 10)
    assert s.hit and s.chosen == "t_far" and not s.front_face
    assert s.t == s.t_far == s.ray_hit_t
    assert "start point is inside" in s.reason
    assert np.linalg.norm(s.point - (6, 4, 6)) == pytest.approx(10, rel=1e-14)
    assert np.allclose(s.normal, (s.point - (6, 4, 6)) / 10)
    assert s.normal @ s.direction > 0  # outward, although the ray comes from inside


def test_lecture_exercise_explanation():
    lines = intersect_sphere_segment(**LECTURE).explain()
    text = "\n".join(lines)
    assert "  i = x2 - x1 = 8,  j = y2 - y1 = 5,  k = z2 - z1 = 4" in lines
    assert "  x = 2 + 8t,  y = 1 + 5t,  z = 2 + 4t" in lines
    assert "  (2 + 8t - 6)² + (1 + 5t - 4)² + (2 + 4t - 6)² = 10²" in lines
    assert "  a = i² + j² + k² = 105" in lines
    assert "  c = (x1 - l)² + (y1 - m)² + (z1 - n)² - r² = 41 - 100 = -59" in lines
    assert "Discriminant: Δ = b² - 4ac = 40656" in lines
    assert "Δ > 0" in text and "t_near = -0.360159,  t_far = 1.56016" in text
    assert "start point is inside" in text
    assert "No crossing for 0 <= t <= 1." in lines
    assert "infinite ray (t >= 0) the first crossing is at t = 1.56016" in text


# --- hand-worked cases --------------------------------------------------------------------


def test_ray_from_outside_takes_the_near_root():
    # a = 1, b = -10, c = 24, Δ = 4, roots (10 ∓ 2) / 2 = 4, 6
    s = intersect_sphere((0, 0, 5), (0, 0, -1), (0, 0, 0), 1)
    assert (s.a, s.b, s.c, s.discriminant) == (1, -10, 24, 4)
    assert (s.t_near, s.t_far) == (4, 6)
    assert s.hit and s.t == 4 and s.chosen == "t_near" and s.front_face
    assert s.point.tolist() == [0, 0, 1] and s.normal.tolist() == [0, 0, 1]
    assert not s.origin_inside


def test_segment_entering_the_sphere():
    # d = (0, 0, -5): a = 25, b = -50, c = 24, Δ = 100, roots (50 ∓ 10) / 50 = 0.8, 1.2
    s = intersect_sphere_segment((0, 0, 5), (0, 0, 0), (0, 0, 0), 1)
    assert s.discriminant == 100
    assert s.t_near == pytest.approx(0.8, rel=1e-15) and s.t_far == pytest.approx(1.2, rel=1e-15)
    assert s.hit and s.chosen == "t_near" and s.t == s.t_near
    assert np.allclose(s.point, (0, 0, 1), rtol=0, atol=1e-15)


def test_segment_that_stops_short_of_the_sphere():
    # d = (0, 0, -2): a = 4, b = -20, c = 24, Δ = 16, roots (20 ∓ 4) / 8 = 2, 3
    s = intersect_sphere_segment((0, 0, 5), (0, 0, 3), (0, 0, 0), 1)
    assert (s.t_near, s.t_far) == (2, 3)
    assert not s.hit and "beyond" in s.reason
    assert s.ray_hit_t == 2


def test_sphere_behind_the_ray_misses():
    # a = 1, b = 10, c = 24: roots -6 and -4, both behind the start point
    s = intersect_sphere((0, 0, 5), (0, 0, 1), (0, 0, 0), 1)
    assert s.classification == "crosses"
    assert (s.t_near, s.t_far) == (-6, -4)
    assert not s.hit and s.t is None and s.ray_hit_t is None
    assert "behind" in s.reason


def test_line_passing_beside_the_sphere_misses():
    # a = 1, b = -10, c = 4 + 25 - 1 = 28, Δ = 100 - 112 = -12
    s = intersect_sphere((0, 2, 5), (0, 0, -1), (0, 0, 0), 1)
    assert s.classification == "misses" and s.discriminant == -12
    assert s.t_near is None and s.t_far is None and not s.hit
    assert s.line_distance == 2
    assert "Δ < 0" in s.reason


def test_hand_tangent_ray():
    # a = 1, b = -10, c = 25 + 1 - 1 = 25, Δ = 100 - 100 = 0, double root t = 5
    s = intersect_sphere((-5, 1, 0), (1, 0, 0), (0, 0, 0), 1)
    assert s.classification == "tangent" and s.discriminant == 0
    assert s.t_near == s.t_far == 5
    assert s.hit and s.t == 5
    assert s.point.tolist() == [0, 1, 0] and s.normal.tolist() == [0, 1, 0]
    assert any("tangent" in line for line in s.explain())


def test_ray_from_inside_picks_the_exit_root():
    rng = np.random.default_rng(7)
    center = np.array([1.5, -2.0, 0.25])
    for _ in range(50):
        origin = center + rng.uniform(-0.5, 0.5, 3)
        direction = rng.normal(size=3)
        s = intersect_sphere(origin, direction, center, 2.0)
        assert s.origin_inside and s.hit and s.chosen == "t_far" and s.t > 0 > s.t_near
        assert np.linalg.norm(s.point - center) == pytest.approx(2.0, rel=1e-14)
        assert np.linalg.norm(s.normal) == pytest.approx(1.0, rel=1e-15)
        assert s.normal @ direction > 0


@pytest.mark.parametrize(
    "bad",
    [
        dict(radius=0.0),
        dict(radius=-1.0),
        dict(radius=float("nan")),
        dict(direction=(0, 0, 0)),
        dict(origin=(1, 2)),
        dict(center=(0, float("inf"), 0)),
    ],
)
def test_bad_input_is_a_value_error(bad):
    args = dict(origin=(0, 0, 5), direction=(0, 0, -1), center=(0, 0, 0), radius=1.0) | bad
    with pytest.raises(ValueError):
        intersect_sphere(**args)


def test_segment_needs_two_different_points():
    with pytest.raises(ValueError, match="differ"):
        intersect_sphere_segment((1, 2, 3), (1, 2, 3), (0, 0, 0), 1)


# --- precision ----------------------------------------------------------------------------

FAR_SPHERES = [
    # origin, centre, radius, offset of the aim point from the centre
    ((0.1, 0.2, 0.3), (3.1e5, -4.7e5, 8.2e5), 1e-3, (2e-4, -3e-4, 1e-4)),  # r = 1e-3 at ~1e6
    ((1.25, -0.5, 3.0), (-4.1e7, 5.3e7, 7.3e7), 1.0, (0.3, 0.2, -0.1)),  # r = 1 at ~1e8
]


@pytest.mark.parametrize(("origin", "center", "radius", "aim"), FAR_SPHERES)
def test_small_far_sphere_keeps_full_precision(origin, center, radius, aim):
    origin, center = np.array(origin), np.array(center)
    direction = (center + aim) - origin
    direction /= np.linalg.norm(direction)  # t is then a distance, ~1e6 or ~1e8
    t_near, t_far = reference_roots(origin, direction, center, radius)
    s = intersect_sphere(origin, direction, center, radius)
    assert s.classification == "crosses" and s.chosen == "t_near"
    assert abs(s.t_near - float(t_near)) <= 1e-15 * float(t_near)  # a few ulp
    assert abs(s.t_far - float(t_far)) <= 1e-15 * float(t_far)
    # The textbook formula (-b - √(b² - 4ac)) / 2a loses the answer here.
    f = origin - center
    a, b, c = direction @ direction, 2 * f @ direction, f @ f - radius**2
    naive_disc = b * b - 4 * a * c
    if naive_disc >= 0:
        naive = (-b - math.sqrt(naive_disc)) / (2 * a)
        assert abs(naive - float(t_near)) > 1e-12 * float(t_near)


def vectors(lo, hi):
    return st.tuples(*[st.floats(lo, hi, allow_nan=False, allow_infinity=False)] * 3)


@settings(max_examples=300, deadline=None)
@given(
    origin=vectors(-1e3, 1e3),
    direction=vectors(-1, 1),
    center=vectors(-1e3, 1e3),
    scale=st.integers(-6, 6),
)
def test_constructed_tangent_rays_are_tangent(origin, direction, center, scale):
    origin, center = np.multiply(origin, 10.0**scale), np.multiply(center, 10.0**scale)
    assume(np.linalg.norm(direction) > 1e-3)
    radius = exact_line_distance(origin, direction, center)  # tangent by construction
    assume(radius >= 1e-60)  # the smallest radius intersect_sphere accepts
    s = intersect_sphere(origin, direction, center, radius)
    a, b, _, _ = exact_quadratic(origin, direction, center, radius)
    t_touch = float(-b / (2 * a))
    size = (np.linalg.norm(origin - center) + radius) / math.sqrt(a)  # scene size in units of t
    if s.classification != "tangent":  # allowed only if the two roots coincide to ~1e-6
        assert s.classification == "crosses"
        assert s.t_far - s.t_near <= 1e-6 * size
    assert abs(s.t_near - t_touch) <= 1e-6 * size


@settings(max_examples=300, deadline=None)
@given(origin=vectors(-10, 10), direction=vectors(-1, 1), center=vectors(-10, 10),
       radius=st.floats(1e-2, 20))
def test_random_rays_match_the_exact_roots(origin, direction, center, radius):
    assume(np.linalg.norm(direction) > 1e-3)
    s = intersect_sphere(origin, direction, center, radius)
    exact_distance = exact_line_distance(origin, direction, center)
    assume(abs(exact_distance - radius) > 1e-6 * radius)  # not nearly tangent
    roots = reference_roots(origin, direction, center, radius)
    if roots is None:
        assert s.classification == "misses" and not s.hit
        return
    assert s.classification == "crosses"
    size = (np.linalg.norm(np.subtract(origin, center)) + radius) / np.linalg.norm(direction)
    assert abs(s.t_near - float(roots[0])) <= 1e-12 * size
    assert abs(s.t_far - float(roots[1])) <= 1e-12 * size
    admissible = [t for t in (s.t_near, s.t_far) if t >= 0]
    assert s.hit == bool(admissible)
    if s.hit:
        assert s.t == admissible[0]
        assert np.linalg.norm(s.normal) == pytest.approx(1, rel=1e-14)
