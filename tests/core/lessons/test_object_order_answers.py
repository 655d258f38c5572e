"""The object-order lessons' exercises, each answered without the pipelines and judged by them.

The references: the frustum's planes, the faces' normals and each pixel's ray are built by hand
(:mod:`hand_rays`), crossings are found by testing every triangle (brute force), and the flat
colours come from the lecture's Lambert formula.  Object order draws in the scene file's order,
opaque objects before transparent ones, and keeps, at a pixel, the front face nearest along the
pixel's ray (depth grows along a ray, so the nearest crossing is the smallest depth).
"""

from dataclasses import replace
from fractions import Fraction

import numpy as np
import pytest
from brute_force import hit_triangle
from hand_rays import frame, frustum_distances, hits, image_hits, inner_pixel, nearest, pixel_ray, rays
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


def test_observer_a_the_right_plane_clips_object_4():
    # Observer A: object 4 has corners on both sides of the right plane (so some polygon crosses it)
    # and every corner inside the five other planes: only the right plane cuts it.  The step says
    # objects 1 and 4 reach over the edges, not which edge.
    ex, p = exercise("observer", 0)
    scene = _scene(p)
    corners = next(o for o in scene.objects if o.name == "object 4").vertices
    d = frustum_distances(scene.camera, corners)
    planes = list(ex.args["choices"])  # left, right, bottom, top, near, far: the columns' order
    assert planes == ["left", "right", "bottom", "top", "near", "far"]
    straddled = [plane for plane, column in zip(planes, d.T, strict=True)
                 if (column < 0).any() and (column > 0).any()]
    assert straddled == ["right"]
    assert (np.delete(d, 1, axis=1) > 0).all()
    assert_only(ex, p, "right")


def _bounding_sphere(vertices):
    """A sphere around the corners: the centre of their box, the farthest corner's distance."""
    v = np.asarray(vertices, float)
    centre = (v.min(axis=0) + v.max(axis=0)) / 2
    return centre, float(np.linalg.norm(v - centre, axis=1).max())


def test_observer_b_only_object_3s_bounding_sphere_lies_inside():
    # Observer B: object 3's sphere (box centre, farthest corner) is farther than its radius inside
    # all six planes; object 1's centre is nearer a side plane than its radius (it straddles it), and
    # all of object 5's corners lie beyond the left plane.
    ex, p = exercise("observer", 1)
    scene = _scene(p)
    objects = {o.name: o for o in scene.objects}
    centre, radius = _bounding_sphere(objects["object 3"].vertices)
    assert (frustum_distances(scene.camera, [centre])[0] > radius).all()
    centre, radius = _bounding_sphere(objects["object 1"].vertices)
    assert (np.abs(frustum_distances(scene.camera, [centre])[0][:4]) < radius).any()
    assert (frustum_distances(scene.camera, objects["object 5"].vertices)[:, 0] < 0).all()
    assert_only(ex, p, "object 3")


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
    box = next(o for o in scene.objects if o.name == "box")
    forward = frame(scene.camera)[2]
    centre_depth = (np.mean(box.vertices, axis=0) - scene.camera.eye) @ forward
    assert centre_depth == pytest.approx((1.5 * -6 - 3.4 * -3.2 + 3 * -9) / np.sqrt(127.24))
    assert (frustum_distances(scene.camera, box.vertices)[:, 4] < 0).all()  # near plane
    for obj in scene.objects:  # every other object has a point inside all six planes
        if obj is box:
            continue
        points = [obj.center] if isinstance(obj, Sphere) else np.vstack([obj.vertices, obj.vertices.mean(0)])
        assert (frustum_distances(scene.camera, points) >= 0).all(axis=1).any(), obj.name
    assert_only(ex, p, "box")


def test_frustum_only_the_right_plane_cuts_the_sphere():
    # The sphere's centre is 0.019 inside the right plane (radius 1: it crosses it) and more than
    # its radius inside the five others (the least: 2.65 from the bottom plane).
    ex, p = exercise("frustum", 1)
    scene = _scene(p)
    sphere = next(o for o in scene.objects if o.name == "sphere")
    distances = frustum_distances(scene.camera, [sphere.center])[0]
    cut = [plane for plane, d in zip(ex.args["choices"], distances, strict=True) if abs(d) < sphere.radius]
    assert cut == ["right"]
    assert_only(ex, p, "right")


def test_frustum_only_the_sphere_reaches_across_a_side_of_the_pyramid():
    # Each object's bounding sphere (box centre, farthest corner; a sphere is its own) against the
    # six planes: the cube's and the cone's lie more than their radius inside all of them, the box's
    # wholly beyond the near plane, and the sphere's centre is nearer the right plane than its radius.
    ex, p = exercise("frustum", 2)
    scene = _scene(p)
    objects = {o.name: o for o in scene.objects}
    for name in ("cube", "cone"):
        centre, radius = _bounding_sphere(objects[name].vertices)
        assert (frustum_distances(scene.camera, [centre])[0] > radius).all(), name
    centre, radius = _bounding_sphere(objects["box"].vertices)
    assert frustum_distances(scene.camera, [centre])[0][4] < -radius  # beyond the near plane
    sphere = objects["sphere"]
    distances = frustum_distances(scene.camera, [sphere.center])[0]
    assert (np.abs(distances) < sphere.radius).sum() == 1 and (distances > -sphere.radius).all()
    assert_only(ex, p, "sphere")


def _facing(corners, eye):
    a, b, c = np.asarray(corners)
    return float(np.cross(b - a, c - a) @ (np.asarray(eye) - a))


def _asked_corners(question):
    """The corners a back-face question gives: ``"... corners ((x, y, z), (x, y, z), (x, y, z)), ..."``."""
    listed = question.split("corners ((")[1].split(")), ")[0]
    return [[float(v) for v in corner.split(", ")] for corner in listed.split("), (")]


def test_back_faces_the_students_faces_by_the_sign_of_n_dot_e_minus_a():
    # Pyramid, the face with corners A = (-1.2, 0, -1.2), B = (-1.2, 0, 1.2), C = (0, 2.2, 0):
    # B - A = (0, 0, 2.4), C - A = (1.2, 2.2, 1.2); N = (B - A) × (C - A) = (-5.28, 2.88, 0);
    # E - A = (2.5, 3.2, 6.5) - A = (3.7, 3.2, 7.7); N · (E - A) = -19.536 + 9.216 = -10.32 < 0: culled.
    # (The steps' own faces, pyramid triangle 2 and the notch's wall, are no variants: their words
    # say which side they show.)
    assert _facing([[-1.2, 0, -1.2], [-1.2, 0, 1.2], [0, 2.2, 0]], (2.5, 3.2, 6.5)) == pytest.approx(-10.32)
    for index, name in ((0, "pyramid"), (1, "notched prism")):
        culled = []
        for k in range(4):
            ex, p = exercise("back_faces", index, k)
            scene = _scene(p)
            assert "E = (2.5, 3.2, 6.5)" in ex.question and scene.camera.eye == pytest.approx((2.5, 3.2, 6.5))
            asked = _asked_corners(ex.question)
            corners = next(o for o in scene.objects if o.name == name).corners[ex.args["fact"]["triangle"]]
            assert corners == pytest.approx(np.array(asked))  # the question's corners are the face's
            facing = _facing(asked, (2.5, 3.2, 6.5))
            assert abs(facing) > 0.1  # far from edge-on: no rounding decides it
            culled.append(facing < 0)
            assert_only(ex, p, facing < 0)
        assert sorted(culled) == [False, False, True, True]  # two faces culled, two drawn


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


@pytest.mark.parametrize("variant", range(3))
def test_zbuffer_after_green_alone_stores_greens_distance_or_the_far_planes(variant):
    # Only green drawn: where its crossing lies on the pixel's ray the entry holds its distance along
    # the viewing axis (blue and yellow, nearer there, come later); elsewhere the cleared value, the
    # far plane's 12.  By brute force, green alone: (87, 74) and (77, 86) cross it, (104, 57) does not.
    ex, p = exercise("zbuffer", 3, variant)
    scene = _scene(p)
    green = replace(scene, objects=tuple(o for o in scene.objects if o.name == "green"))
    origin, direction = pixel_ray(scene.camera, *ex.args["value"]["pixel"])
    crossed = hits(green, origin, direction)
    depth = crossed[0][0] * (direction @ frame(scene.camera)[2]) if crossed else scene.camera.far
    assert bool(crossed) == (variant < 2)
    assert number(ex, p) == pytest.approx(depth, abs=1e-6)
    assert judge(ex, p, depth - 0.009).right and not judge(ex, p, depth - 0.02).right


@pytest.mark.parametrize("variant", range(2))
def test_piercing_the_nearer_of_the_two_planes_is_seen_on_each_side_of_the_crossing(variant):
    ex, p = exercise("zbuffer_piercing", 0, variant)
    scene = _scene(p)
    assert _all_face_the_eye(scene)
    pixel = ex.args["fact"]["pixel"]
    (t_near, first), (t_far, _) = hits(scene, *pixel_ray(scene.camera, *pixel))
    assert t_far - t_near > 0.5  # far from the crossing line: no rounding decides it
    assert_only(ex, p, first)


@pytest.mark.parametrize("variant", range(4))
def test_piercing_drawn_blue_first_green_fails_where_blue_is_nearer(variant):
    # Blue is drawn first and fills its pixels; green comes second and its fragment fails wherever
    # blue's crossing is nearer along the pixel's ray (asked while the picture shows blue alone).
    ex, p = exercise("zbuffer_piercing", 1, variant)
    scene = _scene(p)
    assert [o.name for o in scene.objects] == ["blue", "green"]  # drawn blue first
    assert p.step.zbuffer_step == 1  # the picture: blue alone
    crossed = dict((name, t) for t, name in hits(scene, *pixel_ray(scene.camera, *ex.args["fact"]["pixel"])))
    assert set(crossed) == {"blue", "green"}  # both cover the pixel
    assert abs(crossed["blue"] - crossed["green"]) > 0.5  # far from the crossing line
    assert_only(ex, p, crossed["blue"] < crossed["green"])


@pytest.mark.parametrize(("index", "first", "second"), [(2, "green", "blue"), (3, "blue", "green")])
def test_piercing_the_polygon_drawn_second_fails_where_the_first_is_nearer(index, first, second):
    # Green first (the first step) or blue first (the last step, both drawn): the second polygon's
    # fragment fails where the first's crossing is nearer along the pixel's ray, and passes where its
    # own is nearer or where the first does not cover the pixel.
    ex, p = exercise("zbuffer_piercing", index)
    scene = _scene(p)
    assert [o.name for o in scene.objects] == [first, second]
    t = image_hits(scene)
    assert judge(ex, p, inner_pixel(t[first] < t[second])).right
    assert not judge(ex, p, inner_pixel((t[second] < t[first]) & np.isfinite(t[first]))).right
    alone = inner_pixel(np.isfinite(t[second]) & ~np.isfinite(t[first]))
    assert alone is None or not judge(ex, p, alone).right


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


@pytest.mark.parametrize("variant", range(2))
def test_transparency_drawn_nearest_first_the_pane_behind_fails(variant):
    # Unsorted, the panes are drawn in the file's order, red (z = 1.4, nearest) first, then green,
    # then blue: of the two panes a pixel's ray crosses, the farther, drawn later, fails.  At
    # (128, 125) the ray crosses red and green (green fails: the step says so, "green under red");
    # the other variant's pixel crosses green and blue but not red.
    ex, p = exercise("transparency", 2, variant)
    scene = _scene(p)
    assert [o.name for o in scene.objects][:3] == ["red pane", "green pane", "blue pane"]
    crossed = [name for _, name in hits(scene, *pixel_ray(scene.camera, *ex.args["fact"]["pixel"]))]
    panes = [name for name in crossed if name.endswith("pane")]
    assert len(panes) == 2
    assert_only(ex, p, panes[1])
    assert panes == (["red pane", "green pane"] if variant == 0 else ["green pane", "blue pane"])


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


def _side(a, b, q):
    """(B − A) × (Q − A): zero when Q lies on the line AB; its sign tells the side."""
    return (b[0] - a[0]) * (q[1] - a[1]) - (b[1] - a[1]) * (q[0] - a[0])


def _owns(corners, centre):
    """Does the triangle own the pixel centre?  Inside every edge, or on an edge that is a top edge
    (horizontal, the interior below it: y grows downward) or a left edge (the interior to its
    right): the top-left rule, written out here in exact fractions."""
    owned = True
    for a, b in zip(corners, corners[1:] + corners[:1], strict=True):
        third = next(c for c in corners if c not in (a, b))
        here = _side(a, b, centre)
        if here * _side(a, b, third) < 0:
            return False
        if here == 0:
            top = a[1] == b[1] and third[1] > a[1]
            left = a[1] != b[1] and third[0] > a[0] + (b[0] - a[0]) * (third[1] - a[1]) / (b[1] - a[1])
            owned = owned and (top or left)
    return owned


@pytest.mark.parametrize(("index", "variant"), [(i, k) for i in (0, 1) for k in range(3)])
def test_rasterization_the_top_left_rule_on_the_new_triangles_edges(index, variant):
    # The last step's triangle, 16 x 12 pixels over 16 x 12 units: world (x, y) is pixel
    # (x + 8, 6 - y); corners (-5.5, 3.5), (0.5, -4.5), (4.5, 3.5) are the centres of pixels (2, 2),
    # (8, 10) and (12, 2).  E.g. pixel (10, 6)'s centre (10.5, 6.5): on the edge from (12.5, 2.5) to
    # (8.5, 10.5) at s = 1/2 (x = 12.5 - 4 s, y = 2.5 + 8 s); the third corner (2.5, 2.5) lies to
    # its left, so it is a right edge and the pixel keeps the background.  (5, 6): on the edge from
    # (2.5, 2.5) to (8.5, 10.5) at s = 1/2, interior to its right: a left edge, the triangle's.
    # (6, 2): on the top edge y = 2.5, interior below: the triangle's.
    ex, p = exercise("rasterization", index, variant)
    assert p.step.zbuffer_step == 0  # asked before it is filled: the picture shows none of it
    world = _scene(p).objects[0].vertices.tolist()
    corners = [(Fraction(x) + 8, 6 - Fraction(y)) for x, y, _ in world]
    assert corners == [(Fraction(5, 2), Fraction(5, 2)), (Fraction(17, 2), Fraction(21, 2)),
                       (Fraction(25, 2), Fraction(5, 2))]
    x, y = ex.args["fact"]["pixel"]
    centre = (Fraction(x) + Fraction(1, 2), Fraction(y) + Fraction(1, 2))
    on_edge = [(a, b) for a, b in zip(corners, corners[1:] + corners[:1], strict=True)
               if _side(a, b, centre) == 0]
    assert len(on_edge) == 1  # the question says so: exactly on one edge, not at a corner
    assert_only(ex, p, "triangle" if _owns(corners, centre) else None)
    expected = {(10, 6): None, (5, 6): "triangle", (9, 8): None, (6, 2): "triangle", (11, 4): None,
                (3, 2): "triangle"}
    assert ("triangle" if _owns(corners, centre) else None) == expected[(x, y)]


@pytest.mark.parametrize("variant", range(3))
def test_rasterization_the_top_left_rule_at_the_new_triangles_corners(variant):
    # A corner's centre lies on two edges, and the pixel is the triangle's only when both are top or
    # left edges: (2, 2) joins the top edge and the left edge, so it is filled; (12, 2) joins the top
    # edge and the right edge, and (8, 10) the left and the right edge, so they keep the background.
    ex, p = exercise("rasterization", 2, variant)
    assert p.step.zbuffer_step == 0
    corners = [(Fraction(x) + 8, 6 - Fraction(y)) for x, y, _ in _scene(p).objects[0].vertices.tolist()]
    x, y = ex.args["fact"]["pixel"]
    centre = (Fraction(x) + Fraction(1, 2), Fraction(y) + Fraction(1, 2))
    assert centre in corners
    on_edge = [(a, b) for a, b in zip(corners, corners[1:] + corners[:1], strict=True)
               if _side(a, b, centre) == 0]
    assert len(on_edge) == 2
    owned = "triangle" if _owns(corners, centre) else None
    assert owned == {(2, 2): "triangle", (12, 2): None, (8, 10): None}[(x, y)]
    assert_only(ex, p, owned)


def test_rasterization_the_other_half_of_the_third_triangles_face_fills_the_pixels_it_covers():
    # Object order draws the scene's objects in order, the cube first, and its triangles in order,
    # skipping the back faces: the cube's front faces (the eye on the side its corners turn
    # counter-clockwise to) are triangles 2, 3, 4, 5, 8, 9 here, so the third drawn is triangle 4 and the
    # fifth triangle 8, which shares an edge of triangle 4 and its plane: the same face's other half.  It
    # fills the pixels whose rays cross it (brute force); by step 5 nothing else covers them: the
    # triangles drawn before it are front faces of the same convex cube, beside it, not in front.
    ex, p = exercise("rasterization", 3)
    assert p.step.zbuffer_step == 3  # asked with the third triangle drawn, the fifth not yet
    scene = _scene(p)
    cube = scene.objects[0]
    assert cube.name == "cube"
    front = [k for k, corners in enumerate(cube.corners) if _facing(corners, scene.camera.eye) > 0]
    assert front == [2, 3, 4, 5, 8, 9]
    third, fifth = (cube.corners[k] for k in (front[2], front[4]))
    assert sum(any(np.array_equal(a, b) for b in third) for a in fifth) == 2  # an edge shared
    normal = np.cross(third[1] - third[0], third[2] - third[0])
    assert np.allclose((fifth - third[0]) @ normal, 0)  # in the same plane
    ys, xs = np.mgrid[0:scene.camera.height, 0:scene.camera.width]
    o, d = rays(scene.camera, xs.ravel(), ys.ravel())
    shape = (scene.camera.height, scene.camera.width)
    crossed = {k: np.isfinite(hit_triangle(o, d, *cube.corners[k])).reshape(shape) for k in front[:5]}
    assert crossed[8].sum() > 100
    assert judge(ex, p, inner_pixel(crossed[8])).right
    for k in front[:4]:  # the triangles drawn before it, the half outlined among them, and the background
        elsewhere = inner_pixel(crossed[k] & ~crossed[8])
        assert elsewhere is not None and not judge(ex, p, elsewhere).right, k
    assert not judge(ex, p, (0, 0)).right
