"""Ray casting and ray tracing: images, ray trees, counts, offsets and depth."""

import json
from dataclasses import replace

import numba
import numpy as np
import pytest

from core import presets, presets_trace, shapes
from core.image_order.flat_scene import TraceSettings
from core.image_order.kernels.render import _row_rays
from core.image_order.ray_casting import camera_array, pixel_on_image_plane, primary_ray
from core.image_order.ray_tracing import merge_band_stats, render_trace
from core.image_order.ray_tree import trace_pixel
from core.presets_trace import GLASS, MIRROR, translated
from core.scene import Material, PointLight, Scene, Sphere


def small(scene: Scene, width=64, height=48, **camera) -> Scene:
    return replace(scene, camera=scene.camera.replace(width=width, height=height, **camera))


def pixel_of(scene: Scene, point) -> tuple[int, int]:
    x, y = scene.camera.project(point).pixel
    return int(x), int(y)


# --- primary rays ----------------------------------------------------------------------------


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_primary_rays_pass_through_their_pixel_centres_from_near_to_far(projection):
    """The ray of pixel (x, y), followed through the object-order projection, lands on (x + 0.5, y + 0.5)."""
    scene = small(presets.lecture_scene(), 16, 12, projection=projection)
    camera = scene.camera
    cam = camera_array(camera)
    origins, directions = camera.primary_rays()
    for y in range(12):
        for x in range(16):
            o, d, t_min, t_max = primary_ray(cam, float(x), float(y))
            # The camera's rays are the kernels' rays, bit for bit: one formula (core.camera.pixel_ray).
            assert (tuple(origins[y, x]), tuple(directions[y, x])) == (tuple(o), tuple(d))
            assert np.linalg.norm(d) == pytest.approx(1.0, rel=1e-15)
            for t in (t_min, 0.5 * (t_min + t_max), t_max):
                pixel = camera.project(np.add(o, np.multiply(t, d))).pixel
                np.testing.assert_allclose(pixel, (x + 0.5, y + 0.5), rtol=0, atol=1e-9)
            for t, plane in ((t_min, camera.near), (t_max, camera.far)):  # near to far plane
                depth = np.dot(np.add(o, np.multiply(t, d)) - camera.eye, camera.forward)
                assert depth == pytest.approx(plane, rel=1e-14)
            if projection == "perspective":
                assert tuple(o) == camera.eye
            else:
                np.testing.assert_array_equal(d, camera.forward)


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
@pytest.mark.parametrize("width", [1, 7, 13, 640])
def test_a_rows_primary_rays_worked_out_together_are_each_pixels_own_bit_for_bit(projection, width):
    """The shading works out a row's primary rays in one loop the compiler turns into vector
    instructions (eight pixels a time, then the ones left over); each is the ray the camera gives
    that pixel alone (numpy's arithmetic, pixel by pixel: its rays are the kernels' ones, above)."""
    camera = small(presets.lecture_scene(), width, 3, projection=projection).camera
    camera = camera.replace(eye=(3.3, 2.9, 7.1), target=(-0.7, 0.4, -1.3))  # every component of d odd
    cam = camera_array(camera)
    origins, directions = camera.primary_rays()
    pxs = np.array([pixel_on_image_plane(cam, float(x), 0.0)[0] for x in range(width)])
    rays = np.full((6, width), np.nan)
    for y in range(3):
        _row_rays(cam, pxs, pixel_on_image_plane(cam, 0.0, float(y))[1], rays)
        np.testing.assert_array_equal(rays[:3].T, origins[y])
        np.testing.assert_array_equal(rays[3:].T, directions[y])


def test_a_pixel_that_sees_nothing_returns_the_background():
    scene = small(presets.lecture_scene())
    root = trace_pixel(scene, 0, 0)  # top-left corner: sky
    assert root.hit is None and not root.children
    np.testing.assert_array_equal(root.color, scene.background)
    assert render_trace(scene).depth[0, 0] == np.inf


# --- the ray tree and the image tell the same story ------------------------------------------


@pytest.mark.parametrize("accel", ["bvh", "grid+spheres", "none"])
@pytest.mark.parametrize("offset", ["scaled", "fixed"])
def test_trace_pixel_colour_equals_the_rendered_pixel(accel, offset):
    scene = small(presets_trace.mirror_and_glass())
    settings = TraceSettings(accel=accel, offset=offset)
    image = render_trace(scene, settings)
    rng = np.random.default_rng(0)
    special = np.argwhere(np.isin(image.object_index, [3, 4]))  # mirror and glass ball pixels
    picks = [*special[rng.choice(len(special), 12, replace=False)], *rng.integers(0, (48, 64), (8, 2))]
    for y, x in picks:
        root = trace_pixel(scene, int(x), int(y), settings)
        np.testing.assert_allclose(root.pixel_color, image.color[y, x], rtol=0, atol=1e-12)


def test_an_overbright_pixel_is_clamped_to_one_and_the_rest_kept_exact():
    """The image's colour is the ray tree's sum clamped to [0, 1], per channel, in pixels with
    and without reflected or refracted rays alike."""
    scene = small(presets_trace.mirror_and_glass())
    scene = replace(scene, lights=tuple(replace(light, intensity=4.0) for light in scene.lights))
    image = render_trace(scene, TraceSettings(accel="bvh"))
    special = np.argwhere(np.isin(image.object_index, [3, 4]))  # mirror and glass: secondary rays
    plain = np.argwhere(~np.isin(image.object_index, [3, 4]))
    rng = np.random.default_rng(1)
    for pixels in (special, plain):
        over = 0
        for y, x in pixels[rng.choice(len(pixels), 15, replace=False)]:
            color = trace_pixel(scene, int(x), int(y), TraceSettings(accel="bvh")).color
            over += int(np.any(color > 1.0))
            np.testing.assert_allclose(image.color[y, x], np.minimum(np.maximum(color, 0.0), 1.0), rtol=0,
                                       atol=1e-12)
        assert over >= 3  # the light is bright enough that clamping is tested in both kinds of pixel
    assert image.color.max() == 1.0 and image.color.min() >= 0.0


def test_ray_trees_count_the_same_rays_as_the_render():
    scene = small(presets_trace.mirror_and_glass(), 16, 12)
    stats = render_trace(scene).stats["rays"]
    counts = dict.fromkeys(("primary", "shadow", "reflection", "refraction"), 0)
    for y in range(12):
        for x in range(16):
            for node in trace_pixel(scene, x, y).walk():
                counts[node.kind] += node.traced
    assert counts == {k: stats[k] for k in counts}
    assert counts["reflection"] > 0 and counts["refraction"] > 0


def test_colour_is_combined_from_the_last_hits_back_to_the_first():
    scene = small(presets_trace.mirror_and_glass())
    root = trace_pixel(scene, *pixel_of(scene, (-0.6, 0.9, 0.9 + 0.9)))  # the mirror ball, facing us
    assert root.hit_name == "mirror ball"
    for node in root.walk():
        if node.kind == "shadow" or not node.traced or node.hit is None:
            continue
        expected = node.local_color + sum(c.coefficient * c.color for c in node.children
                                          if c.kind != "shadow" and c.traced)
        np.testing.assert_allclose(node.color, expected, rtol=1e-15)
        shadows = [c.color for c in node.children if c.kind == "shadow"]
        np.testing.assert_allclose(node.local_color, node.ambient + sum(shadows), rtol=1e-14)
    reflection = [c for c in root.children if c.kind == "reflection"][0]
    assert reflection.coefficient == pytest.approx(MIRROR.reflectivity)
    assert reflection.weight == pytest.approx(MIRROR.reflectivity)
    assert any("reflection (gen 1)" in line for line in root.explain())


# --- glass: refraction, Fresnel, rays that start inside -----------------------------------------


def test_glass_ball_pixel_refracts_in_and_out():
    scene = small(presets_trace.mirror_and_glass())
    center, radius = np.array([1.3, 0.75, 1.4]), 0.75
    root = trace_pixel(scene, *pixel_of(scene, center))
    assert root.hit_name == "glass ball" and root.front_face
    r, t = root.fresnel
    assert r + t == pytest.approx(1.0) and 0 < r < 0.1
    inside = [c for c in root.children if c.kind == "refraction"][0]
    assert inside.traced and inside.coefficient == pytest.approx(GLASS.transparency * t)
    # The refracted ray starts just inside and leaves through the far side.
    assert np.linalg.norm(inside.origin - center) < radius
    assert inside.hit_name == "glass ball" and inside.front_face is False
    assert np.linalg.norm(inside.point - center) == pytest.approx(radius, rel=1e-12)
    assert np.dot(inside.normal, inside.direction) < 0  # the normal faces the ray
    assert inside.t > radius  # crossed the ball, not stuck at its entry point
    out = [c for c in inside.children if c.kind == "refraction"][0]
    assert out.traced and np.linalg.norm(out.origin - center) > radius


def test_a_shadow_ray_from_inside_a_glass_ball_tests_the_ball_alone_and_the_image_is_every_methods():
    """A ray from inside a ball to a light outside it must leave the ball: the BVH's shadow ray from
    the inside tests that ball first and, finding the crossing, searches nothing else.  The light's
    status is what a search of the whole scene finds: the image is bit for bit that of the methods
    that search (no acceleration, the grid)."""
    scene = small(presets_trace.mirror_and_glass())
    center, radius = np.array([1.3, 0.75, 1.4]), 0.75
    inside = [c for c in trace_pixel(scene, *pixel_of(scene, center), TraceSettings(accel="bvh")).children
              if c.kind == "refraction"][0]
    assert inside.front_face is False
    [shadow] = [c for c in inside.children if c.kind == "shadow"]
    assert np.linalg.norm(shadow.origin - center) < radius  # it starts inside
    assert shadow.hit_name == "glass ball" and shadow.tests == 1 and shadow.bounds_tests == 0
    # Where it leaves the ball: on the sphere, by hand.
    assert np.linalg.norm(shadow.origin + shadow.t * shadow.direction - center) == pytest.approx(radius)
    images = [render_trace(scene, TraceSettings(accel=accel)).color for accel in ("bvh", "none", "grid")]
    assert np.array_equal(images[0], images[1]) and np.array_equal(images[0], images[2])


def test_total_internal_reflection_inside_a_glass_block():
    glass = Material(transparency=1.0, ior=1.5)
    scene = Scene(camera=presets_trace.mirror_and_glass().camera.replace(eye=(0.0, 3.0, 4.0),
                                                                         target=(0.0, 0.0, 0.0)),
                  objects=(shapes.box((0.0, 0.0, 0.0), 2.0, glass, name="block"),),
                  lights=(PointLight((2.0, 6.0, 3.0)),))
    root = trace_pixel(scene, *pixel_of(scene, (0.0, 1.0, -0.9)))  # top face, near the far edge
    inside = [c for c in root.children if c.kind == "refraction"][0]
    assert inside.hit_name == "block" and not inside.front_face
    assert inside.total_internal_reflection and inside.fresnel == (1.0, 0.0)
    assert [c.kind for c in inside.children if c.kind != "shadow"] == ["reflection"]
    assert inside.k_reflect == 1.0


# --- what gets traced ---------------------------------------------------------------------


def test_adding_a_mirror_adds_reflection_rays_and_removing_it_removes_them():
    lecture = small(presets.lecture_scene())
    rays = render_trace(lecture).stats["rays"]
    assert rays["reflection"] == 0 and rays["refraction"] == 0 and rays["shadow"] > 0
    mirror = Sphere((2.0, 0.7, 2.0), 0.7, MIRROR, name="mirror")
    with_mirror = render_trace(replace(lecture, objects=(*lecture.objects, mirror))).stats["rays"]
    assert with_mirror["reflection"] > 0 and with_mirror["refraction"] == 0
    glass = Sphere((2.0, 0.7, 2.0), 0.7, GLASS, name="glass")
    with_glass = render_trace(replace(lecture, objects=(*lecture.objects, glass))).stats["rays"]
    assert with_glass["refraction"] > 0


def test_no_lights_means_no_shadow_rays():
    stats = render_trace(small(presets_trace.no_lights())).stats
    assert stats["rays"]["shadow"] == 0 and stats["rays"]["primary"] == 64 * 48


def test_a_light_nothing_can_block_gets_no_shadow_rays_and_still_lights():
    scene = small(presets_trace.lone_sphere())
    image = render_trace(scene)
    assert image.stats["rays"]["shadow"] == 0
    root = trace_pixel(scene, *pixel_of(scene, (0.0, 0.3, 1.5)))
    shadow = [c for c in root.children if c.kind == "shadow"][0]
    assert not shadow.traced and shadow.color.sum() > 0


def test_ray_casting_traces_first_hits_and_shadow_rays_only():
    stats = render_trace(small(presets_trace.mirror_and_glass()), TraceSettings(mode="raycast")).stats
    assert stats["rays"]["reflection"] == stats["rays"]["refraction"] == 0 and stats["rays"]["shadow"] > 0


def test_depth_limit_and_minimum_weight_cut_the_tree():
    scene = small(presets_trace.facing_mirrors())
    at = pixel_of(scene, (-1.95, 1.55, 4.9))  # the left mirror, seen almost square on
    deep = trace_pixel(scene, *at, TraceSettings(max_depth=8, min_weight=0.0))
    assert max(n.generation for n in deep.walk() if n.traced) == 8
    shallow = trace_pixel(scene, *at, TraceSettings(max_depth=2, min_weight=0.0))
    assert max(n.generation for n in shallow.walk() if n.traced) == 2
    assert any(n.status == "not traced: depth limit reached" for n in shallow.walk())
    weak = trace_pixel(scene, *at, TraceSettings(max_depth=8, min_weight=0.5))
    assert any(n.status == "not traced: weight below min_weight" for n in weak.walk())
    assert all(n.weight >= 0.5 for n in weak.walk() if n.traced)
    counts = [render_trace(scene, TraceSettings(max_depth=d)).stats["rays"]["reflection"] for d in (1, 3)]
    assert 0 < counts[0] < counts[1]


# --- shadows and the ray offset -----------------------------------------------------------


def shadow_scene(with_occluder: bool) -> Scene:
    ground = shapes.quad((0.0, 0.0, 0.0), 10.0, Material(color=(0.8, 0.8, 0.8)), name="ground")
    occluder = shapes.box((0.0, 2.0, 0.0), 1.0, Material(color=(0.2, 0.4, 0.9)), name="occluder")
    far_ball = Sphere((3.0, 0.5, -3.0), 0.5, name="ball")
    objects = (ground, far_ball, occluder) if with_occluder else (ground, far_ball)
    camera = presets_trace.mirror_and_glass().camera
    return Scene(camera=camera.replace(width=64, height=48, eye=(0.0, 6.0, 8.0), target=(0.0, 0.0, 0.0)),
                 objects=objects, lights=(PointLight((0.0, 6.0, 0.0)),))


def test_a_point_behind_an_occluder_is_dark_and_lit_without_it():
    point = (0.0, 0.0, 0.0)  # right below the occluder and the light
    blocked = trace_pixel(shadow_scene(True), *pixel_of(shadow_scene(True), point))
    free = trace_pixel(shadow_scene(False), *pixel_of(shadow_scene(False), point))
    assert blocked.hit_name == free.hit_name == "ground"
    shadow = [c for c in blocked.children if c.kind == "shadow"][0]
    assert shadow.traced and shadow.hit_name == "occluder" and 0 < shadow.t < shadow.t_max
    np.testing.assert_allclose(blocked.local_color, blocked.ambient)  # ambient light only
    lit = [c for c in free.children if c.kind == "shadow"][0]
    assert lit.traced and lit.hit is None and lit.status == "reached the light"
    assert free.color.sum() > 3 * blocked.color.sum()


def lit_plane_scene() -> Scene:
    """A ground plane lit from above, a ball casting a shadow on it: shadow rays everywhere."""
    camera = presets_trace.mirror_and_glass().camera
    return Scene(camera=camera.replace(width=80, height=60, eye=(0.0, 4.0, 7.0), target=(0.0, 0.0, 0.0)),
                 objects=(shapes.quad((0.0, 0.0, 0.0), 12.0, Material(color=(0.8, 0.8, 0.8)), name="ground"),
                          Sphere((1.0, 1.0, -1.0), 0.8, Material(color=(0.9, 0.3, 0.2)), name="ball")),
                 lights=(PointLight((-2.0, 8.0, 3.0)),))


def test_scaled_offset_gives_the_same_image_near_the_origin_and_ten_thousand_units_away():
    near = lit_plane_scene()
    far = translated(near, (1e4, 1e4, 1e4))
    a, b = render_trace(near), render_trace(far)
    assert np.array_equal(a.object_index, b.object_index)
    differs = np.abs(a.color - b.color).max(axis=2) > 1e-6
    assert differs.mean() < 0.002  # at most a pixel or two on the shadow's edge
    ground = a.object_index == 0
    lit = ground & (a.color.sum(axis=2) > 1.5 * a.color[ground].sum(axis=1).min())
    assert lit.sum() > 1000 and not differs[lit].any()  # no acne on the lit ground


@pytest.mark.parametrize("side", [1.0, -1.0])
def test_a_shadow_ray_starts_just_off_the_surface_on_the_side_of_its_light(side):
    """The scaled offset pushes a shadow ray's origin along the normal towards the light: above the
    ground when the eye and the light are above it (its front), below it when both are below (its
    back, whose normal faces the eye the other way).  The render decides that side from the normal
    facing the eye (kernels.shade); pbrt decides it from the direction to the light: past the test
    that the light is not behind the surface, the two are the same side."""
    scene = lit_plane_scene()
    below = replace(scene,
                    camera=scene.camera.replace(eye=(0.0, 4.0 * side, 7.0)),
                    objects=(scene.objects[0], replace(scene.objects[1], center=(1.0, 1.0 * side, -1.0))),
                    lights=(PointLight((-2.0, 8.0 * side, 3.0)),))
    root = trace_pixel(below, *pixel_of(below, (0.3, 0.0, 0.2)))
    assert root.hit_name == "ground" and root.front_face == (side > 0)
    shadow = [c for c in root.children if c.kind == "shadow"][0]
    assert shadow.traced and shadow.status == "reached the light"
    step = shadow.origin - root.point
    assert step[0] == 0.0 and step[2] == 0.0  # along the ground's normal only
    assert 0.0 < step[1] * side < 1e-12  # towards the light, by the error bound
    to_light = np.subtract(below.lights[0].position, root.point)
    assert np.dot(step, to_light) > 0.0


def test_fixed_epsilon_of_zero_shows_shadow_acne_far_from_the_origin():
    far = translated(lit_plane_scene(), (1e4, 1e4, 1e4))
    good = render_trace(far)
    acne = render_trace(far, TraceSettings(offset="fixed", epsilon=0.0))
    ground = good.object_index == 0
    darker = (acne.color.sum(axis=2) < good.color.sum(axis=2) - 0.05) & ground
    assert darker.sum() > 0.05 * ground.sum()
    fine = render_trace(far, TraceSettings(offset="fixed", epsilon=1e-4))
    assert np.abs(fine.color - good.color).max() < 1e-6 or (
        (np.abs(fine.color - good.color).max(axis=2) > 1e-6).mean() < 0.002)


# --- depth ----------------------------------------------------------------------------------


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_depth_of_a_plane_seen_straight_on_is_the_distance(projection):
    # Looking straight down from height 5: every ground point is 5 units along the viewing axis.
    scene = Scene(camera=presets_trace.mirror_and_glass().camera.replace(
                      eye=(0.0, 5.0, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), width=40, height=30,
                      projection=projection, ortho_height=4.0),
                  objects=(shapes.quad((0.0, 0.0, 0.0), 100.0),), lights=(PointLight((0.0, 9.0, 0.0)),))
    depth = render_trace(scene).depth
    np.testing.assert_allclose(depth, 5.0, rtol=1e-13)


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_depth_of_a_tilted_plane_matches_the_analytic_value(projection):
    cam = presets.lecture_scene().camera.replace(width=40, height=30, projection=projection, far=100.0)
    scene = Scene(camera=cam, objects=(shapes.quad((0.0, 0.0, 0.0), 1000.0),))
    depth = render_trace(scene).depth
    # The pixel's point at view depth s is eye + R (px s, py s, -s) (perspective) or
    # eye + R (px, py, -s) (orthographic); it is on the plane y = 0 where its y vanishes.
    rot = cam.world_from_view[:3, :3]
    hw, hh = cam.half_extent(1.0)
    px = ((np.arange(40) + 0.5) / 40 * 2 - 1) * hw
    py = (1 - (np.arange(30) + 0.5) / 30 * 2) * hh
    px, py = np.meshgrid(px, py)
    if projection == "perspective":
        expected = -cam.eye[1] / (rot[1, 0] * px + rot[1, 1] * py - rot[1, 2])
    else:
        expected = (cam.eye[1] + rot[1, 0] * px + rot[1, 1] * py) / rot[1, 2]
    seen = (expected > cam.near) & (expected < cam.far)  # the far plane ends the view
    np.testing.assert_allclose(depth[seen], expected[seen], rtol=1e-12)
    assert np.all(np.isinf(depth[~seen]))


# --- bands, coarse images, settings, statistics -----------------------------------------------


def test_a_band_of_rows_equals_those_rows_of_the_whole_image():
    scene = small(presets_trace.mirror_and_glass())
    whole = render_trace(scene)
    band = render_trace(scene, rows=(10, 27))
    assert band.color.shape == (17, 64, 3) and band.rows == (10, 27)
    assert np.array_equal(band.color, whole.color[10:27]) and np.array_equal(band.depth, whole.depth[10:27])
    assert band.stats["rays"]["primary"] == 17 * 64


def test_the_image_does_not_depend_on_how_many_threads_share_it():
    scene = small(presets_trace.mirror_and_glass(), width=50, height=37)  # 37 rows: the last band is short
    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        alone = render_trace(scene)
    finally:
        numba.set_num_threads(threads)
    shared = render_trace(scene)
    assert np.array_equal(shared.color, alone.color) and np.array_equal(shared.depth, alone.depth)
    assert shared.stats["rays"] == alone.stats["rays"] and shared.stats["rays"]["primary"] == 50 * 37


def test_frames_in_a_row_and_at_once_each_give_their_own_image_and_leave_the_last_as_it_was():
    # A thread reuses its working arrays from one frame to the next of the same size: nothing of a
    # frame may show in the next, the image a caller keeps must stay as it was, and two threads
    # rendering at once must not share them.
    import threading

    settings = TraceSettings(mode="raytrace", max_depth=5)
    scenes = {"lecture": small(presets.lecture_scene(), 80, 60),
              "mirror": small(presets_trace.mirror_and_glass(), 80, 60)}
    first = {name: render_trace(scene, settings) for name, scene in scenes.items()}
    kept = {name: result.color.copy() for name, result in first.items()}
    again = render_trace(scenes["lecture"], settings)
    assert np.array_equal(again.color, kept["lecture"])
    assert np.array_equal(again.depth, first["lecture"].depth)
    assert all(np.array_equal(first[name].color, kept[name]) for name in scenes)  # the kept images unchanged
    assert not np.array_equal(kept["lecture"], kept["mirror"])
    images, failures = {name: [] for name in scenes}, []

    def frames(name):
        try:
            for _ in range(4):
                images[name].append(render_trace(scenes[name], settings).color)
        except Exception as error:  # noqa: BLE001 - reported below, with the thread's scene
            failures.append((name, error))

    threads = [threading.Thread(target=frames, args=(name,)) for name in scenes]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join(timeout=300)
    assert not failures and not any(thread.is_alive() for thread in threads)
    for name in scenes:
        assert len(images[name]) == 4, name
        assert all(np.array_equal(image, kept[name]) for image in images[name]), name


def test_a_coarse_image_repeats_one_ray_per_block():
    scene = small(presets_trace.mirror_and_glass())
    whole = render_trace(scene)
    coarse = render_trace(scene, step=4)
    assert coarse.color.shape == whole.color.shape and coarse.stats["rays"]["primary"] == 16 * 12
    assert np.array_equal(coarse.color[::4, ::4], whole.color[::4, ::4])
    assert np.array_equal(coarse.color[1:4, 1:4], np.broadcast_to(whole.color[0, 0], (3, 3, 3)))


def test_statistics_are_complete_and_json_ready():
    stats = render_trace(small(presets_trace.mirror_and_glass()), TraceSettings(accel="grid")).stats
    json.dumps(stats)
    assert set(stats["rays"]) == {"primary", "shadow", "reflection", "refraction", "total"}
    assert stats["plan"]["reflection_rays"] is True
    assert {"method", "tests_per_ray", "cells_per_ray", "build_s"} <= set(stats["accel"])
    assert stats["accel"]["cells_per_ray"] > 0
    assert {"build", "primary", "shading", "secondary", "total"} <= set(stats["times"])
    assert stats["compile_s"] >= 0


@pytest.mark.parametrize("bad", [dict(mode="x"), dict(accel="kd"), dict(offset="x"), dict(max_depth=-1),
                                 dict(min_weight=-0.1), dict(epsilon=-1.0)])
def test_bad_settings_are_refused(bad):
    with pytest.raises(ValueError, match=next(iter(bad))):
        TraceSettings(**bad)


def test_bad_rows_step_and_pixels_are_refused():
    scene = small(presets.lecture_scene())
    with pytest.raises(ValueError, match="rows"):
        render_trace(scene, rows=(10, 5))
    with pytest.raises(ValueError, match="step"):
        render_trace(scene, step=0)
    with pytest.raises(ValueError, match="outside"):
        trace_pixel(scene, 64, 0)


@pytest.mark.parametrize("key", list(presets_trace.PRESETS_TRACE))
def test_every_preset_renders(key):
    title, build = presets_trace.PRESETS_TRACE[key]
    scene = small(build(), 24, 18)
    image = render_trace(scene)
    assert title and image.color.shape == (18, 24, 3)
    assert (image.object_index >= 0).mean() > 0.2


@pytest.mark.parametrize("accel", ["none", "spheres", "grid", "grid+spheres", "bvh"])
def test_an_empty_scene_is_all_background(accel):
    camera = presets.lecture_scene().camera.replace(width=8, height=6)
    scene = Scene(camera=camera, lights=(PointLight((1.0, 2.0, 3.0)),))
    image = render_trace(scene, TraceSettings(accel=accel))
    assert np.all(image.object_index == -1) and np.all(np.isinf(image.depth))
    np.testing.assert_array_equal(image.color, np.broadcast_to(scene.background, (6, 8, 3)))
    assert trace_pixel(scene, 3, 3, TraceSettings(accel=accel)).hit is None


def test_band_statistics_add_up_to_the_whole_image():
    scene = presets_trace.mirror_and_glass()
    scene = replace(scene, camera=scene.camera.replace(width=64, height=48))
    whole = render_trace(scene).stats
    bands = [render_trace(scene, rows=(a, min(a + 16, 48))).stats for a in range(0, 48, 16)]
    merged = merge_band_stats(bands)
    assert merged["rays"] == whole["rays"]
    for key in ("prim_tests", "bounds_tests", "cells_visited", "tests_per_ray"):
        assert merged["accel"][key] == pytest.approx(whole["accel"][key])
    assert merged["pixels_traced"] == whole["pixels_traced"] and merged["rows"] == [0, 48]


def _searching_every_shadow_ray(monkeypatch):
    """Render with plans that name no blockers: every shadow ray searches the whole scene."""
    import core.image_order.ray_tracing as ray_tracing

    plan_of = ray_tracing.effects_plan

    def no_blockers(scene, mode="raytrace"):
        plan = plan_of(scene, mode)
        return replace(plan, lights=tuple(replace(light, blockers=None) for light in plan.lights))

    monkeypatch.setattr(ray_tracing, "effects_plan", no_blockers)


@pytest.mark.parametrize("scene", [presets.lecture_scene, presets_trace.mirror_and_glass, lit_plane_scene,
                                   lambda: translated(lit_plane_scene(), (1e4, 1e4, 1e4))])
def test_shadow_rays_that_miss_every_possible_blocker_give_the_image_of_a_full_search(scene, monkeypatch):
    frame = scene()
    frame = replace(frame, camera=frame.camera.replace(width=96, height=72))
    settings = TraceSettings(accel="bvh")
    asking = render_trace(frame, settings)
    _searching_every_shadow_ray(monkeypatch)
    searching = render_trace(frame, settings)
    for a, b in ((asking.color, searching.color), (asking.depth, searching.depth),
                 (asking.object_index, searching.object_index)):
        assert np.array_equal(a, b)
    assert asking.stats["rays"] == searching.stats["rays"] and asking.stats["rays"]["shadow"] > 1000
    # Most shadow rays met no bounding sphere of a possible blocker and tested no triangle.
    assert asking.stats["accel"]["prim_tests"] < 0.8 * searching.stats["accel"]["prim_tests"]



def test_a_receiver_with_more_possible_blockers_than_its_columns_hold_searches_the_whole_scene():
    from core.image_order import flat_layout
    from core.image_order.effects_plan import effects_plan
    from core.image_order.flat_scene import kernel_inputs, trace_scene

    ground = shapes.quad((0.0, 0.0, 0.0), 60.0, name="ground")
    balls = tuple(Sphere((3.0 * k, 1.0, 0.0), 1.0, name=f"ball {k}")
                  for k in range(flat_layout.RECEIVER_SIZE))
    scene = Scene(objects=(ground, *balls), lights=(PointLight((0.0, 10.0, 0.0)),))
    plan = effects_plan(scene)
    assert len(plan.lights[0].blockers[0]) == flat_layout.RECEIVER_SIZE
    lights = kernel_inputs(scene, TraceSettings(), plan, trace_scene(scene), None).lights
    assert lights[0, flat_layout.LIGHT_SIZE] == flat_layout.BLOCKERS_UNKNOWN
    first_ball = flat_layout.LIGHT_SIZE + flat_layout.RECEIVER_SIZE
    assert lights[0, first_ball] == len(plan.lights[0].blockers[1])


def test_a_ray_tree_counts_the_one_sphere_test_of_a_shadow_ray_that_misses_the_only_possible_blocker():
    # Lit ground far from the ball's shadow: the ball is the only object that may shadow the
    # ground, so the shadow ray asks the ball's sphere once, misses it and tests no triangle.
    tree = trace_pixel(lit_plane_scene(), 5, 55, TraceSettings(accel="bvh"))
    assert tree.hit_name == "ground"
    shadow = [c for c in tree.children if c.kind == "shadow"][0]
    assert shadow.traced and shadow.status == "reached the light" and shadow.hit is None
    assert shadow.tests == 0 and shadow.bounds_tests == 1
