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
from hand_rays import crossings, hits, image_hits, inner_pixel, nearest, pixel_ray, rays, shadow_blockers
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


def test_two_orders_without_acceleration_every_ray_is_tested_against_every_triangle():
    # The scene's meshes hold 12 + 96 + 2 = 110 triangles (and no sphere); with no acceleration a
    # ray must try them all to know which crossing comes first: the one hitting the cube, the one
    # hitting the ground and the one hitting nothing alike.
    ex, p = exercise("two_orders", 2)
    scene = _scene(p)
    assert p.step.image_order.accel == "none"
    every = sum(len(o.triangles) for o in scene.objects)
    assert every == 110 and "110 triangles" in ex.question
    met = [[name for _, name in hits(scene, *pixel_ray(scene.camera, *v.args["value"]["pixel"]))][:1]
           for v in ex.variants]
    assert met == [["cube"], ["ground"], []]
    for v in ex.variants:
        assert number(v, p) == every
        assert judge(v, p, every).right and not judge(v, p, 12).right


def test_ray_casting_a_click_where_the_cube_blocks_the_light_is_right():
    # Every ground pixel's shadow ray is tested against the cube: the pixels where it is blocked
    # are the cube's shadow.  (The step's own pixel, (230, 155), lies in the cone's: its words say so.)
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
    shadows = {}
    for name in ("cube", "cone"):
        obj = next(o for o in scene.objects if o.name == name)
        blocked = crossings(obj, points + 1e-6 * to_light, to_light / distance[:, None]) < distance
        shadows[name] = np.zeros_like(ground)
        shadows[name][ys[blocked], xs[blocked]] = True
    inside = inner_pixel(shadows["cube"])
    assert inside is not None and judge(ex, p, inside).right
    lit = inner_pixel(ground & ~shadows["cube"] & ~shadows["cone"])
    assert not judge(ex, p, lit).right
    assert not judge(ex, p, inner_pixel(shadows["cone"] & ~shadows["cube"])).right
    assert not judge(ex, p, (230, 155)).right


def test_ray_casting_a_click_where_the_cube_is_met_first_is_right():
    # Every object crossed along each pixel's ray, brute force: where the cube's crossing is the
    # nearest the pixel shows the cube; where the cone's is nearer, in front of the cube, it does not.
    ex, p = exercise("ray_casting", 2)
    t = image_hits(_scene(p))
    first = nearest(t)
    assert judge(ex, p, inner_pixel(first == "cube")).right
    assert not judge(ex, p, inner_pixel((first == "cone") & np.isfinite(t["cube"]))).right
    assert not judge(ex, p, inner_pixel(first == "ground")).right


@pytest.mark.parametrize("variant", range(3))
def test_ray_sphere_the_line_misses_touches_or_crosses_by_its_distance_from_the_centre(variant):
    # In exact fractions: the centre's squared distance from the line, |c - o|² - ((c - o)·d)² / d·d,
    # against r²: larger, the line misses; equal, it touches; smaller, it crosses.  (The first two
    # variants: c - o = (2, -2, 1) is perpendicular to d = (1, 2, 2), 9 from the line, r² = 9 and 16;
    # the third: (2, -2, -1) perpendicular to (2, 1, 2), 9 against 4.)
    ex, p = exercise("ray_sphere", 9, variant)
    fact = ex.args["fact"]
    o, d, c = ([Fraction(v) for v in fact[key]] for key in ("origin", "direction", "center"))
    f = [ci - oi for ci, oi in zip(c, o, strict=True)]
    along = sum(fi * di for fi, di in zip(f, d, strict=True))
    squared = sum(fi * fi for fi in f) - along * along / sum(di * di for di in d)
    r2 = Fraction(fact["radius"]) ** 2
    answer = "misses" if squared > r2 else "tangent" if squared == r2 else "crosses"
    assert answer == ("tangent", "crosses", "misses")[variant]
    assert_only(ex, p, answer)


@pytest.mark.parametrize("variant", range(4))
def test_ray_casting_what_blocks_each_variants_shadow_ray(variant):
    # Each variant's ray meets the ground; from there the shadow ray towards the light meets one
    # object before the light: the cube for the first two pixels, the cone for the last two (none
    # of them (230, 155), whose blocker the step names).
    ex, p = exercise("ray_casting", 1, variant)
    pixel = ex.args["fact"]["pixel"]
    assert tuple(pixel) != (230, 155)
    name, blockers = shadow_blockers(_scene(p), *pixel)
    assert name == "ground"
    assert blockers == (["cube"] if variant < 2 else ["cone"])
    assert_only(ex, p, blockers[0])


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


@pytest.mark.parametrize(("variant", "first"), list(enumerate(["ball 2", "pyramid", "slab 1", "slab 2"])))
def test_acceleration_the_students_pixel_meets_its_first_object(variant, first):
    # Brute force over every object, no bounding sphere nor grid, for the pixel this student draws
    # (none of them a pixel a step picks: (225, 122) and (150, 118) are shown with their ray trees).
    ex, p = exercise("acceleration", 0, variant)
    x, y = ex.args["fact"]["pixel"]
    assert (x, y) not in {(225, 122), (150, 118)}
    crossed = hits(_scene(p), *pixel_ray(_scene(p).camera, x, y))
    assert crossed[0][1] == first
    assert_only(ex, p, first)


@pytest.mark.parametrize("variant", range(4))
def test_acceleration_the_distance_to_the_first_object(variant):
    ex, p = exercise("acceleration", 1, variant)
    x, y = ex.args["value"]["pixel"]
    assert (x, y) not in {(225, 122), (150, 118)}
    ((t, name), *_) = hits(_scene(p), *pixel_ray(_scene(p).camera, x, y))
    assert name in {"ball 2", "pyramid", "slab 1", "slab 2"}
    assert number(ex, p) == pytest.approx(t, abs=1e-9)
    assert judge(ex, p, t + 0.009).right and not judge(ex, p, t + 0.02).right


@pytest.mark.parametrize("variant", range(4))
def test_ray_triangle_the_students_ray_hits_when_all_three_weights_are_positive(variant):
    # Exact fractions (Gauss-Jordan on o + t d = αA + βB + γC).  By hand for the first variant:
    # A = (-2, 2, 2), B = (2, -1, 3), C = (-3, 0, 3), o = (0, 0, 4), d = (-2, 0, -3): with α = 1/5,
    # β = 2/5, γ = 2/5, αA + βB + γC = (-0.4 + 0.8 - 1.2, 0.4 - 0.4 + 0, 0.4 + 1.2 + 1.2)
    # = (-0.8, 0, 2.8) = o + (2/5) d: t = 2/5, all weights positive, a hit.  The lecture's own ray
    # (α ≈ 0.30873, worked in the step) is no variant.
    ex, p = exercise("ray_triangle", 3, variant)
    f = ex.args["fact"]
    alpha, beta, gamma, t = exact_triangle_solve(*(f[key] for key in ("origin", "direction", "a", "b", "c")))
    hit = min(alpha, beta, gamma) >= 0 and t >= 0
    assert_only(ex, p, hit)
    if variant == 0:
        assert (alpha, beta, gamma, t) == (Fraction(1, 5), Fraction(2, 5), Fraction(2, 5), Fraction(2, 5))
    assert list(f["origin"]) != [0.5, 0.3, 6]


@pytest.mark.parametrize("variant", range(4))
def test_ray_sphere_the_segment_crosses_when_an_end_lies_on_each_side(variant):
    # A segment crosses a sphere's surface when one end lies inside (squared distance from the
    # centre below r²) and the other outside; with both inside it never reaches the surface (a ball
    # is convex).  With both outside it may still pass through: then a root lies in (0, 1).  First
    # variant by hand: |(4, 3, 5) - (1, 8, 5)|² = 9 + 25 + 0 = 34 < 36 (inside) and
    # |(3, 2, 3) - (1, 8, 5)|² = 4 + 36 + 4 = 44 > 36 (outside): it crosses.
    ex, p = exercise("ray_sphere", 6, variant)
    f = ex.args["fact"]
    centre = np.asarray(f["center"])
    inside = [float(np.sum((np.asarray(f[k]) - centre) ** 2)) < f["radius"] ** 2 for k in ("origin", "end")]
    if inside[0] != inside[1]:
        crosses = True
    elif all(inside):
        crosses = False
    else:  # both outside: does the line pass within r of the centre between the ends?
        o, e = np.asarray(f["origin"], float), np.asarray(f["end"], float)
        s = np.clip((centre - o) @ (e - o) / ((e - o) @ (e - o)), 0, 1)
        crosses = float(np.sum((o + s * (e - o) - centre) ** 2)) < f["radius"] ** 2
    assert_only(ex, p, crosses)
    if variant == 0:
        assert inside == [True, False]


def _cells_listed_along(boxes, listed, origins, directions, ends, slack=1e-9):
    """For each segment ``origins + t directions``, 0 <= t <= ``ends``: the primitives listed in every
    cell box it meets (touching, within ``slack``, counts; a negative ``slack`` counts only the boxes
    it passes that far inside), each cell's list counted in full; (N,)."""
    total = np.zeros(len(origins))
    for start in range(0, len(origins), 4096):
        o, d = origins[start:start + 4096, None, :], directions[start:start + 4096, None, :]
        with np.errstate(divide="ignore", invalid="ignore"):
            t0, t1 = (boxes[None, :, 0] - o) / d, (boxes[None, :, 1] - o) / d
        enter = np.nanmax(np.minimum(t0, t1), axis=2)
        leave = np.nanmin(np.maximum(t0, t1), axis=2)
        met = ((enter <= leave + slack) & (leave >= -slack)
               & (enter <= ends[start:start + 4096, None] + slack))
        total[start:start + 4096] = met.astype(float) @ listed
    return total


def _grid_cells(scene):
    """The boxes of the grid's cells (C, 2, 3) and how many primitives each lists (C,)."""
    from core.image_order.flat_scene import trace_scene

    grid = trace_scene(scene).geometry.accel("grid")[0]
    nx, ny, nz = grid.resolution
    cells = np.array([(i, j, k) for k in range(nz) for j in range(ny) for i in range(nx)])
    return grid.cell_boxes(cells), np.array([len(grid.prims_in_cell(*c)) for c in cells], float)


def _every_pixels_ray(scene):
    """Every pixel's ray, row by row: origins and unit directions (N, 3), and the t of its first hit
    among all the objects, brute force (+inf: none) (N,)."""
    cam = scene.camera
    ys, xs = np.mgrid[0:cam.height, 0:cam.width]
    origins, directions = rays(cam, xs.ravel(), ys.ravel())
    return origins, directions, np.stack([t.ravel() for t in image_hits(scene).values()]).min(axis=0)


def test_acceleration_the_grid_costs_a_pixel_fewer_primitive_tests_than_the_spheres_alone():
    # Bounds from the scene, not the tracer's counts.  The spheres alone: every primary ray tests each
    # of the three balls (a ball is its own bounding sphere), so a pixel costs at least 3.  The grid: a
    # ray tests at most what the cells it crosses list (each cell's list counted in full, whether or not
    # a primitive met in one cell is tested again in the next), up to its first hit; a pixel's rays are
    # its primary ray and at most one shadow ray, to the one light (no material reflects or refracts).
    # That bound, brute force over every pixel and every cell, comes to about 1.6 a pixel.
    from core.scene import Sphere

    ex, p = exercise("acceleration", 2)
    scene = _scene(p)
    assert p.step.image_order.accel == "grid" and len(scene.lights) == 1
    assert all(o.material.reflectivity == 0 and o.material.transparency == 0 for o in scene.objects)
    assert sum(isinstance(o, Sphere) for o in scene.objects) == 3
    boxes, listed = _grid_cells(scene)
    origins, directions, first = _every_pixels_ray(scene)
    primary = _cells_listed_along(boxes, listed, origins, directions, first)
    hit = np.isfinite(first)
    points = origins[hit] + first[hit, None] * directions[hit]
    to_light = np.asarray(scene.lights[0].position) - points
    shadow = _cells_listed_along(boxes, listed, points, to_light, np.ones(len(points)))
    grid_bound = (primary.sum() + shadow.sum()) / len(primary)
    assert grid_bound < 3, grid_bound
    assert_only(ex, p, True)


def test_acceleration_a_click_on_a_ray_that_misses_yet_is_tested_on_its_way_through_the_grid():
    # A ray with no hit walks every cell it crosses, to the grid's far side, and tests what each
    # lists: it makes some test exactly when some cell it crosses lists a primitive.  Brute force:
    # the misses by testing every object, the cells crossed by slab tests against every cell's box.
    # Pixels whose ray grazes a cell's side (counted as met within 1e-9 of it and not 1e-9 inside)
    # are left out.  The pixels right to click ring the objects, where a cell they reach into is
    # crossed; the rest of the sky is crossed through empty cells or none.
    ex, p = exercise("acceleration", 3)
    scene = _scene(p)
    assert p.step.image_order.accel == "grid"
    boxes, listed = _grid_cells(scene)
    origins, directions, first = _every_pixels_ray(scene)
    miss = ~np.isfinite(first)
    touching = _cells_listed_along(boxes, listed, origins, directions, first)
    inside = _cells_listed_along(boxes, listed, origins, directions, first, slack=-1e-9)
    width = scene.camera.width
    kinds = {"right": miss & (inside > 0), "untested miss": miss & (touching == 0), "hit": ~miss}
    assert kinds["right"].sum() > 1000 and kinds["untested miss"].sum() > 1000
    rng = np.random.default_rng(5)
    for kind, where in kinds.items():
        for k in rng.choice(np.flatnonzero(where), 15, replace=False):
            pixel = (int(k % width), int(k // width))
            assert judge(ex, p, pixel).right == (kind == "right"), (kind, pixel)
    # A wrong click is told what its ray cost, in words a student reads ("0 primitive test(s)" before).
    told = judge(ex, p, (10, 10)).sentence
    assert "0 primitive tests" in told and "(s)" not in told, told
