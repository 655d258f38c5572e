"""The object-order lessons' exercises, each answered without the pipelines and judged by them.

The references: the frustum's planes, the faces' normals and each pixel's ray are built by hand
(:mod:`hand_rays`), crossings are found by testing every triangle (brute force), and the flat
colours come from the lecture's Lambert formula.  Object order draws in the scene file's order,
opaque objects before transparent ones, and keeps, at a pixel, the front face nearest along the
pixel's ray (depth grows along a ray, so the nearest crossing is the smallest depth).
"""

from fractions import Fraction

import numpy as np
import pytest
from brute_force import hit_triangle
from hand_rays import frame, frustum_distances, hits, image_hits, inner_pixel, nearest, pixel_ray
from shipped_exercises import assert_only, exercise

from core.lessons.exercises import judge, number
from core.scene import Sphere


def _scene(p):
    return p.step.scene


def test_two_orders_the_z_buffer_keeps_the_nearest_crossing():
    # Brute force at (155, 110): the cone at t ≈ 9.68, the cube at 12.60, the ground at 15.63.
    ex, p = exercise("two_orders", 0)
    (_, first), *behind = hits(_scene(p), *pixel_ray(_scene(p).camera, 155, 110))
    assert sorted(name for _, name in behind) == ["cube", "ground"]
    assert_only(ex, p, first)
    assert first == "cone"


@pytest.mark.parametrize("index", [0, 1])
def test_observer_object_5_is_outside_and_every_other_object_has_a_corner_inside(index):
    # Observer A, by hand: A = (0, 1, 8) looks down -z; the left plane has slope tan 20° · 4/3 =
    # 0.485.  Object 5's corners have x ≤ -4.9 at depths 8 - z ≤ 8 - 5.9 = 2.1, and 4.9 > 0.485 · 2.1
    # = 1.02: every corner is beyond the left plane.  Observer B's distances are computed the same way.
    ex, p = exercise("observer", index)
    scene = _scene(p)
    outside = [o.name for o in scene.objects
               if (frustum_distances(scene.camera, o.vertices) < 0).all(axis=0).any()]
    a_corner_in = [o.name for o in scene.objects
                   if (frustum_distances(scene.camera, o.vertices) >= 0).all(axis=1).any()]
    assert outside == ["object 5"]
    assert a_corner_in == ["object 1", "object 2", "object 3", "object 4"]
    assert_only(ex, p, "object 5")


def test_observer_a_object_2_hides_object_3_where_both_cross_the_ray_and_2_is_nearer():
    # Object 2 comes before object 3 in the scene, so it is drawn first: where both cover a pixel
    # and object 2 is nearer, object 3's fragment meets a nearer stored depth and fails.
    ex, p = exercise("observer", 2)
    t = image_hits(_scene(p))
    hidden = inner_pixel((t["object 2"] < t["object 3"]) & np.isfinite(t["object 3"]))
    assert hidden is not None and judge(ex, p, hidden).right
    alone = inner_pixel((nearest(t) == "object 2") & ~np.isfinite(t["object 3"]))  # 3 not behind
    assert alone is not None and not judge(ex, p, alone).right


def test_frustum_the_box_behind_the_observer_is_dropped():
    # By hand: the eye (6, 4, 9) looks toward (0, 0.8, 0), forward = (-6, -3.2, -9) / 11.28.  The
    # box's centre (7.5, 0.6, 12) is (1.5, -3.4, 3) from the eye: depth (-9 + 10.88 - 27) / 11.28 =
    # -2.23, behind the eye; its corners are at most 0.6 (6 + 3.2 + 9) / 11.28 = 0.92 nearer the
    # front, so all lie before the near plane (depth 1).
    ex, p = exercise("frustum", 0)
    scene = _scene(p)
    box = next(o for o in scene.objects if o.name == "box behind the observer")
    forward = frame(scene.camera)[2]
    centre_depth = (np.mean(box.vertices, axis=0) - scene.camera.eye) @ forward
    assert centre_depth == pytest.approx((1.5 * -6 - 3.4 * -3.2 + 3 * -9) / np.sqrt(127.24))
    assert (frustum_distances(scene.camera, box.vertices)[:, 4] < 0).all()  # near plane
    for obj in scene.objects:  # every other object has a point inside all six planes
        if obj is box:
            continue
        points = [obj.center] if isinstance(obj, Sphere) else np.vstack([obj.vertices, obj.vertices.mean(0)])
        assert (frustum_distances(scene.camera, points) >= 0).all(axis=1).any(), obj.name
    assert_only(ex, p, "box behind the observer")


def test_frustum_only_the_right_plane_cuts_the_sphere():
    # The sphere's centre is 0.019 inside the right plane (radius 1: it crosses it) and more than
    # its radius inside the five others (the least: 2.65 from the bottom plane).
    ex, p = exercise("frustum", 1)
    scene = _scene(p)
    sphere = next(o for o in scene.objects if o.name == "sphere half outside")
    distances = frustum_distances(scene.camera, [sphere.center])[0]
    cut = [plane for plane, d in zip(ex.args["choices"], distances, strict=True) if abs(d) < sphere.radius]
    assert cut == ["right"]
    assert_only(ex, p, "right")


def _facing(corners, eye):
    a, b, c = np.asarray(corners)
    return float(np.cross(b - a, c - a) @ (np.asarray(eye) - a))


def test_back_faces_by_the_sign_of_n_dot_e_minus_p():
    # Pyramid triangle 2: A = (1.2, 0, -1.2), B = (-1.2, 0, -1.2), C = (0, 2.2, 0);
    # N = (B - A) × (C - A) = (-2.4, 0, 0) × (-1.2, 2.2, 1.2) = (0, 2.88, -5.28);
    # E - A = (2.5, 3.2, 6.5) - A = (1.3, 3.2, 7.7); N · (E - A) = 9.216 - 40.656 = -31.44 < 0: a back face.
    ex, p = exercise("back_faces", 0)
    corners = _scene(p).objects[0].corners[2]
    assert corners.tolist() == [[1.2, 0, -1.2], [-1.2, 0, -1.2], [0, 2.2, 0]]
    assert _facing(corners, _scene(p).camera.eye) == pytest.approx(-31.44)
    assert_only(ex, p, True)
    # Notched prism triangle 13, the notch's inner wall on z = 0.1: A = (-1.3, 0, 0.1),
    # B = (-0.1, 0, 0.1), C = (-0.1, 1.6, 0.1); N = (1.2, 0, 0) × (1.2, 1.6, 0) = (0, 0, 1.92);
    # E - A = (3.8, 3.2, 6.4); N · (E - A) = 1.92 · 6.4 = 12.288 > 0: a front face, not culled.
    ex, p = exercise("back_faces", 1)
    corners = _scene(p).objects[0].corners[13]
    assert corners == pytest.approx(np.array([[-1.3, 0, 0.1], [-0.1, 0, 0.1], [-0.1, 1.6, 0.1]]))
    assert _facing(corners, _scene(p).camera.eye) == pytest.approx(12.288)
    assert_only(ex, p, False)


def _all_face_the_eye(scene):
    return all(_facing(c, scene.camera.eye) > 0 for o in scene.objects for c in o.corners)


@pytest.mark.parametrize("variant", range(5))
def test_zbuffer_keeps_the_nearest_polygon_at_each_variants_pixel(variant):
    ex, p = exercise("zbuffer", 0, variant)
    scene = _scene(p)
    assert _all_face_the_eye(scene)  # none is culled: the nearest crossing is kept
    assert_only(ex, p, hits(scene, *pixel_ray(scene.camera, *ex.args["fact"]["pixel"]))[0][1])


def test_zbuffer_yellow_wins_over_green_only_where_green_was_there_first():
    # Drawn green, blue, yellow: yellow wins over green where it is the nearest of the three and
    # green lies behind it, nearer than blue (so green, not blue or nothing, held the pixel before).
    ex, p = exercise("zbuffer", 1)
    t = image_hits(_scene(p))
    shown = nearest(t)
    over_green = (shown == "yellow") & np.isfinite(t["green"]) & (t["green"] < t["blue"])
    assert judge(ex, p, inner_pixel(over_green)).right
    over_nothing = (shown == "yellow") & ~np.isfinite(t["green"]) & ~np.isfinite(t["blue"])
    assert inner_pixel(over_nothing) is not None  # yellow alone: it wins over no one there
    assert not judge(ex, p, inner_pixel(over_nothing)).right
    assert not judge(ex, p, inner_pixel(shown == "green")).right
    assert not judge(ex, p, inner_pixel(shown == "blue")).right


@pytest.mark.parametrize("variant", range(3))
def test_zbuffer_stores_the_nearest_crossings_distance_along_the_viewing_axis(variant):
    # The distance along the viewing axis is the ray's t times cos of its angle to the axis, d · forward;
    # e.g. at the centre (80, 60) the ray is nearly the axis and meets blue at t = 5.3182.
    ex, p = exercise("zbuffer", 2, variant)
    scene = _scene(p)
    origin, direction = pixel_ray(scene.camera, *ex.args["value"]["pixel"])
    t = hits(scene, origin, direction)[0][0]
    depth = t * (direction @ frame(scene.camera)[2])
    assert number(ex, p) == pytest.approx(depth, abs=1e-6)
    assert judge(ex, p, depth + 0.009).right and not judge(ex, p, depth + 0.02).right


@pytest.mark.parametrize("variant", range(2))
def test_piercing_the_nearer_of_the_two_planes_is_seen_on_each_side_of_the_crossing(variant):
    ex, p = exercise("zbuffer_piercing", 0, variant)
    scene = _scene(p)
    assert _all_face_the_eye(scene)
    pixel = ex.args["fact"]["pixel"]
    (t_near, first), (t_far, _) = hits(scene, *pixel_ray(scene.camera, *pixel))
    assert t_far - t_near > 0.5  # far from the crossing line: no rounding decides it
    assert_only(ex, p, first)


def test_piercing_drawn_blue_first_the_same_polygon_is_seen():
    ex, p = exercise("zbuffer_piercing", 1)
    scene = _scene(p)
    assert [o.name for o in scene.objects] == ["blue", "green"]  # drawn blue first
    assert_only(ex, p, hits(scene, *pixel_ray(scene.camera, 108, 65))[0][1])


def test_piercing_blue_fails_where_green_drawn_first_is_nearer():
    ex, p = exercise("zbuffer_piercing", 2)
    scene = _scene(p)
    assert [o.name for o in scene.objects] == ["green", "blue"]
    t = image_hits(scene)
    assert judge(ex, p, inner_pixel(t["green"] < t["blue"])).right
    assert not judge(ex, p, inner_pixel((t["blue"] < t["green"]) & np.isfinite(t["green"]))).right


def _flat_colour(scene, obj, triangle):
    """The lecture's flat Lambert colour of one triangle, lit at its centroid (two-sided normal)."""
    a, b, c = obj.corners[triangle]
    n = np.cross(b - a, c - a)
    n /= np.linalg.norm(n)
    centroid = (a + b + c) / 3
    if n @ (np.asarray(scene.camera.eye) - centroid) < 0:
        n = -n
    to_light = np.asarray(scene.lights[0].position) - centroid
    m = obj.material
    return np.asarray(m.color) * (m.ambient + m.diffuse * max(0.0, n @ to_light / np.linalg.norm(to_light)))


def _crossed_triangle(obj, origin, direction):
    """The triangle of ``obj`` the ray crosses first (brute force)."""
    return int(np.argmin([hit_triangle(origin[None], direction[None], *corners)[0]
                          for corners in obj.corners]))


def test_transparency_the_green_panes_c0_by_the_blending_formula():
    # At (128, 125) the ray crosses the red pane, the green pane and the opaque box (not the blue
    # pane).  Sorted far to near, the box is drawn first (opaque), then green blends over it:
    # c0 = α cs + (1 - α) cd with α = 0.5, cs green's flat colour, cd the box's.
    ex, p = exercise("transparency", 1)
    scene = _scene(p)
    origin, direction = pixel_ray(scene.camera, 128, 125)
    assert [name for _, name in hits(scene, origin, direction)] == ["red pane", "green pane", "opaque box"]
    objects = {o.name: o for o in scene.objects}
    cs, cd = (_flat_colour(scene, objects[n], _crossed_triangle(objects[n], origin, direction))
              for n in ("green pane", "opaque box"))
    c0 = 0.5 * cs[0] + 0.5 * cd[0]
    assert number(ex, p) == pytest.approx(c0, abs=1e-9)
    assert judge(ex, p, c0 + 0.009).right and not judge(ex, p, c0 + 0.02).right


def test_transparency_drawn_nearest_first_the_green_pane_fails_behind_the_red():
    # Unsorted, the panes are drawn in the file's order, red (z = 1.4, nearest) first; the ray of
    # (128, 125) crosses red and green but not blue, so green's fragment is the one that fails.
    ex, p = exercise("transparency", 2)
    scene = _scene(p)
    assert [o.name for o in scene.objects][:3] == ["red pane", "green pane", "blue pane"]
    crossed = [name for _, name in hits(scene, *pixel_ray(scene.camera, 128, 125))]
    assert crossed[:2] == ["red pane", "green pane"] and "blue pane" not in crossed
    assert_only(ex, p, "green pane")


def test_three_views_after_the_cubes_six_front_triangles_then_after_all():
    # The eye (6, 4, 9) is (7.7, 3.2, 10.1) from the cube's centre, positive on every axis, so its +x,
    # +y and +z faces (6 triangles) face the eye; the cube comes first: after 6 polygons only it is drawn.
    ex, p = exercise("three_views", 0)
    scene = _scene(p)
    cube = scene.objects[0]
    assert cube.name == "cube" and ex.args["fact"]["after"] == 6
    assert sum(_facing(c, scene.camera.eye) > 0 for c in cube.corners) == 6
    crossed = [name for _, name in hits(scene, *pixel_ray(scene.camera, 155, 110))]
    assert "cube" in crossed
    assert_only(ex, p, "cube")
    ex, p = exercise("three_views", 1)
    assert_only(ex, p, crossed[0])
    assert crossed[0] == "cone"


def test_rasterization_a_centre_on_the_left_edge_belongs_to_the_triangle():
    # 16 x 12 pixels over 16 x 12 units: pixel (3, 7)'s centre is (3.5 - 8, 6 - 7.5) = (-4.5, -1.5).
    # The edge from C = (-0.5, 4.5) to A = (-6.5, -4.5), x = -0.5 - 6 s, y = 4.5 - 9 s, reaches
    # y = -1.5 at s = 2/3, where x = -4.5: the centre is on it.  The centroid (-0.5, -1.5) lies on the
    # same row to its right, so it is a left edge, and the top-left rule gives the pixel to the triangle.
    ex, p = exercise("rasterization", 1)
    a, b, c = (np.asarray(v[:2]) for v in _scene(p).objects[0].vertices.tolist())
    assert (a.tolist(), b.tolist(), c.tolist()) == ([-6.5, -4.5], [5.5, -4.5], [-0.5, 4.5])
    s = Fraction(2, 3)
    centre = (Fraction(3) + Fraction(1, 2) - 8, 6 - (Fraction(7) + Fraction(1, 2)))
    assert centre == (Fraction(-1, 2) - 6 * s, Fraction(9, 2) - 9 * s)
    assert sum(Fraction(v[1]) for v in (a, b, c)) / 3 == centre[1]
    assert sum(Fraction(v[0]) for v in (a, b, c)) / 3 > centre[0]
    assert_only(ex, p, "triangle")
