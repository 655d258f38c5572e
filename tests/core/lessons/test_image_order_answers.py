"""The image-order lessons' exercises, each answered without the tracer and judged by it.

The references: each pixel's ray built by hand (:mod:`hand_rays`), every triangle and sphere
tested along it (brute force), shadow rays from the hit toward the light, Snell's law written out
here, and the lecture's triangle system solved in exact fractions.
"""

import math
from fractions import Fraction

import numpy as np
import pytest
from brute_force import exact_triangle_solve
from hand_rays import crossings, hits, image_hits, inner_pixel, nearest, pixel_ray, rays
from shipped_exercises import assert_only, exercise

from core.lessons.exercises import judge, number


def _scene(p):
    return p.step.scene


def test_two_orders_the_ray_meets_the_cube_first():
    # Brute force at (132, 93): the cube at t ≈ 12.15, then the ground at 19.49; the cone is missed.
    ex, p = exercise("two_orders", 1)
    crossed = hits(_scene(p), *pixel_ray(_scene(p).camera, 132, 93))
    assert [name for _, name in crossed] == ["cube", "ground"]
    assert_only(ex, p, "cube")


def _blockers(scene, point, light=0):
    """The objects between ``point`` and the light, nearest first (the shadow ray p + s (l - p),
    0 < s < 1)."""
    to_light = np.asarray(scene.lights[light].position) - point
    distance = np.linalg.norm(to_light)
    return [name for t, name in hits(scene, point, to_light / distance, t_min=1e-6) if t < distance]


def test_ray_casting_a_click_where_the_cone_blocks_the_light_is_right():
    # Every ground pixel's shadow ray is tested against the cone: the pixels where it is blocked
    # are the cone's shadow.
    ex, p = exercise("ray_casting", 0)
    scene = _scene(p)
    cam = scene.camera
    t = image_hits(scene)
    ground = nearest(t) == "ground"
    ys, xs = np.nonzero(ground)
    origins, directions = rays(cam, xs, ys)
    points = origins + t["ground"][ys, xs, None] * directions
    to_light = np.asarray(scene.lights[0].position) - points
    distance = np.linalg.norm(to_light, axis=1)
    cone = next(o for o in scene.objects if o.name == "cone")
    blocked = crossings(cone, points + 1e-6 * to_light, to_light / distance[:, None]) < distance
    shadow = np.zeros_like(ground)
    shadow[ys[blocked], xs[blocked]] = True
    inside = inner_pixel(shadow)
    assert inside is not None and judge(ex, p, inside).right
    lit = inner_pixel(ground & ~shadow)
    assert not judge(ex, p, lit).right


def test_ray_casting_the_cone_blocks_the_shadow_ray_of_230_155():
    # The ray of (230, 155) meets the ground at t ≈ 10.63; from there the light is 19.19 away and
    # the cone stands 2.56 along the way; nothing else does.
    ex, p = exercise("ray_casting", 1)
    scene = _scene(p)
    origin, direction = pixel_ray(scene.camera, 230, 155)
    ((t, name),) = hits(scene, origin, direction)
    assert name == "ground"
    assert _blockers(scene, origin + t * direction) == ["cone"]
    assert_only(ex, p, "cone")


def _refract(d, n, eta):
    """Snell's law for unit ``d`` meeting unit normal ``n`` (facing ``d``'s origin), ``eta = n1 / n2``:
    the refracted unit direction and the sine of the refraction angle (above 1: total reflection)."""
    cos_i = -d @ n
    sin_t = eta * math.sqrt(max(0.0, 1 - cos_i * cos_i))
    if sin_t > 1:
        return None, sin_t
    return eta * d + (eta * cos_i - math.sqrt(1 - sin_t * sin_t)) * n, sin_t


def _glass_path(scene):
    """Pixel (205, 132)'s path through the glass ball: ``[(point, name, sine of the refraction
    angle), ...]`` for A (entering), B (leaving), and C, where the ray leaving meets."""
    ball = next(o for o in scene.objects if o.name == "glass ball")
    centre, eta = np.asarray(ball.center), ball.material.ior
    origin, d = pixel_ray(scene.camera, 205, 132)
    t, name = hits(scene, origin, d)[0]
    a = origin + t * d
    inside, sin_a = _refract(d, (a - centre) / ball.radius, 1 / eta)
    t, name_b = hits(scene, a, inside, t_min=1e-6)[0]
    b = a + t * inside
    out, sin_b = _refract(inside, -(b - centre) / ball.radius, eta)
    t, name_c = hits(scene, b, out, t_min=1e-6)[0]
    return [(a, name, sin_a), (b, name_b, sin_b), (b + t * out, name_c, None)]


def test_ray_tracing_the_glass_ball_refracts_in_and_out():
    # Entering glass from air (1 → 1.5): sin θt = sin θi / 1.5 ≤ 2/3, never above 1, so never total
    # reflection.  Inside a ball the chord meets the surface again at the same angle θt, and
    # leaving (1.5 → 1) sin θ = 1.5 sin θt = sin θi ≤ 1: it refracts out.
    (a, name_a, sin_a), (b, name_b, sin_b), _ = _glass_path(_scene(exercise("ray_tracing", 0)[1]))
    assert (name_a, name_b) == ("glass ball", "glass ball")
    assert sin_a < 2 / 3 and sin_b < 1
    ex, p = exercise("ray_tracing", 0)
    assert_only(ex, p, False)
    ex, p = exercise("ray_tracing", 1)
    assert_only(ex, p, True)


def test_ray_tracing_the_colours_are_computed_c_then_b_then_a():
    # A and B on the glass ball, C where the ray leaving it lands: the cone.  A colour needs its
    # children's first, so the deepest ray's comes first: C, B, A.
    ex, p = exercise("ray_tracing", 2)
    (_, a, _), (_, b, _), (_, c, _) = _glass_path(_scene(p))
    assert (a, b, c) == ("glass ball", "glass ball", "cone")
    primary, refracted, leaving = ex.args["items"]
    assert judge(ex, p, [leaving, refracted, primary]).right
    assert not judge(ex, p, [primary, refracted, leaving]).right


def test_acceleration_the_pyramid_is_hit_and_ball_2_at_its_distance():
    # Brute force over every object, no bounding sphere nor grid: (225, 122) meets only the pyramid;
    # (150, 118) meets ball 2 first, at t ≈ 6.371 along the unit direction.
    ex, p = exercise("acceleration", 0)
    crossed = hits(_scene(p), *pixel_ray(_scene(p).camera, 225, 122))
    assert [name for _, name in crossed] == ["pyramid"]
    assert_only(ex, p, "pyramid")
    ex, p = exercise("acceleration", 1)
    ((t, name), *_) = hits(_scene(p), *pixel_ray(_scene(p).camera, 150, 118))
    assert name == "ball 2"
    assert number(ex, p) == pytest.approx(t, abs=1e-9)
    assert judge(ex, p, t + 0.009).right and not judge(ex, p, t + 0.02).right


def test_ray_triangle_the_ray_hits_because_all_three_weights_are_positive():
    # Exact fractions: α = 481/1558, β = 957/3116, so γ = 1 - α - β = 1197/3116 > 0, and t = 784/779 > 0.
    ex, p = exercise("ray_triangle", 3)
    f = ex.args["fact"]  # the lecture's decimals, read as the exact numbers they write
    alpha, beta, gamma, t = exact_triangle_solve(
        *([Fraction(str(x)) for x in f[key]] for key in ("origin", "direction", "a", "b", "c")))
    assert min(alpha, beta, gamma) > 0 and t > 0
    assert (alpha, beta, gamma, t) == (Fraction(481, 1558), Fraction(957, 3116), Fraction(1197, 3116),
                                    Fraction(784, 779))
    assert_only(ex, p, True)


def test_ray_sphere_the_segment_stays_inside_the_sphere():
    # |(2, 1, 2) - (6, 4, 6)|² = 16 + 9 + 16 = 41 and |(10, 6, 6) - (6, 4, 6)|² = 16 + 4 + 0 = 20, both
    # below r² = 100: both ends are inside, and a segment between two inside points never meets the
    # surface of a ball (it is convex).
    ex, p = exercise("ray_sphere", 6)
    f = ex.args["fact"]
    centre = np.asarray(f["center"])
    assert [float(np.sum((np.asarray(f[k]) - centre) ** 2)) for k in ("origin", "end")] == [41, 20]
    assert_only(ex, p, False)
