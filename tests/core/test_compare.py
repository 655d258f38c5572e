"""Compare: the difference image of two outputs, the same pixel in each, and the explanation."""

from dataclasses import replace

import numpy as np
import pytest
from hand_rays import frame, image_hits, rays
from matplotlib import colormaps

from core.compare import OUTPUTS, compare, difference, explain, probe, render_output
from core.object_order.pipeline import render_raster
from core.presets import lecture_scene, zbuffer_three_polygons
from core.presets_trace import lone_sphere, mirror_and_glass, no_lights
from core.srgb import to_srgb8


def _small(scene, width=80, height=60):
    return replace(scene, camera=scene.camera.replace(width=width, height=height))


@pytest.mark.parametrize("name", list(OUTPUTS))
def test_the_difference_of_an_output_with_itself_is_zero_everywhere(name):
    scene = _small(mirror_and_glass())
    result = compare(scene, name, name)
    assert result.difference.delta.shape == (60, 80, 3)
    assert not result.difference.delta.any()
    assert result.difference.scale == 0.0
    assert result.difference.visible_fraction == 0.0
    assert "zero at every pixel" in " ".join(result.explanation)


def test_the_two_projections_differ_exactly_where_their_independent_renders_differ():
    scene = _small(lecture_scene())
    result = compare(scene, "orthographic", "perspective")
    # The two z-buffer images rendered here, without core.compare.
    ortho = render_raster(replace(scene, camera=scene.camera.replace(projection="orthographic"))).color
    persp = render_raster(replace(scene, camera=scene.camera.replace(projection="perspective"))).color
    differs = np.any(ortho != persp, axis=2)
    assert differs.any()  # parallel and converging rays put the objects on different pixels
    np.testing.assert_array_equal(result.difference.delta, np.abs(ortho - persp))
    np.testing.assert_array_equal(result.difference.magnitude > 0, differs)
    assert result.difference.scale == np.abs(ortho - persp).max() > 0


def test_the_colour_map_runs_from_zero_to_the_scale():
    a = np.zeros((2, 2, 3))
    b = a.copy()
    b[0, 0] = (0.5, 0.2, 0.0)  # largest channel difference 0.5 (linear RGB)
    b[1, 1] = (0.0, 0.25, 0.0)
    diff = difference(a, b, "viridis")
    assert diff.scale == 0.5
    cmap = colormaps["viridis"]
    expect = {(0, 0): 1.0, (1, 1): 0.5, (0, 1): 0.0}
    for (y, x), level in expect.items():
        want = np.round(np.array(cmap(level)[:3]) * 255)
        assert np.abs(to_srgb8(diff.colored[y, x]).astype(int) - want).max() <= 1
    bar = diff.colorbar(64, 4)
    assert bar.shape == (4, 64, 3)
    assert diff.ticks(3) == [(0.0, 0.0), (0.5, 0.25), (1.0, 0.5)]


def test_images_of_different_sizes_are_refused_with_both_sizes():
    with pytest.raises(ValueError, match="4 x 3 and 5 x 3"):
        difference(np.zeros((3, 4, 3)), np.zeros((3, 5, 3)))


def test_the_same_pixel_in_every_output_finds_the_nearest_polygon():
    # In the lecture's z-buffer figure blue is nearest wherever it overlaps the others.
    scene = zbuffer_three_polygons()
    blue = scene.objects[1]
    for name in OUTPUTS:
        output = render_output(scene, name)
        # The pixel under blue's centroid, in this output's own projection.
        x, y = (int(v) for v in np.floor(output.scene.camera.project(blue.vertices.mean(axis=0)).pixel))
        report = probe(output, x, y)
        assert "blue" in report.found
        np.testing.assert_array_equal(report.color, output.color[y, x])
        if output.raster is not None:
            assert report.events and report.events[-1].passed
            assert scene.objects[report.events[-1].object_index].name == "blue"
        else:
            assert report.ray_tree.hit_name == "blue"
    with pytest.raises(ValueError, match="outside"):
        probe(output, -1, 0)


def _text(scene, a, b):
    return " ".join(explain(render_output(scene, a), render_output(scene, b)))


def test_a_scene_with_a_mirror_and_glass_names_reflection_and_refraction():
    text = _text(_small(mirror_and_glass()), "perspective", "raytrace")
    assert "reflected rays" in text and "mirror ball" in text
    assert "Snell" in text and "glass ball" in text
    assert "true spheres" in text  # the two balls are analytic spheres
    assert "shadow" in text  # the light can be blocked: the tracer casts shadows, the z-buffer does not


def test_a_scene_without_mirrors_or_spheres_does_not_claim_them():
    text = _text(_small(lecture_scene()), "perspective", "raytrace")
    assert "mirror" not in text and "Snell" not in text and "true sphere" not in text
    assert "No material reflects or transmits light" in text


@pytest.mark.parametrize("pair", [("perspective", "raytrace"), ("raycast", "raytrace"),
                                  ("orthographic", "raycast")])
def test_a_scene_without_lights_does_not_mention_shadows(pair):
    text = _text(_small(no_lights()), *pair)
    assert "shadow" not in text.lower()
    if "perspective" in pair or "orthographic" in pair:
        assert "no light" in text


def test_a_light_nothing_can_block_is_said_to_cast_no_shadows():
    text = _text(_small(lone_sphere()), "perspective", "raycast")
    assert "no shadow rays" in text
    assert "Only the tracer casts shadows" not in text


@pytest.mark.parametrize("make", [lecture_scene, lone_sphere])
def test_the_sentence_on_visible_surfaces_counts_the_pixels_where_they_part(make):
    # It said "both find the same visible surfaces and part only along edges" whatever the scene.  The
    # reference: each pixel's first hit by brute force (every triangle, the analytic sphere), its view
    # depth t (d . forward) for a unit d, against the z-buffer's depth; they part where one sees the
    # background and the other not, or the depths differ by more than 1e-9 of the larger.  The
    # lecture scene's faces are flat: the same plane, the same depth, at every pixel; the lone
    # sphere is drawn as facets inscribed in it: nearer than the true sphere wherever it shows.
    scene = _small(make())
    cam = scene.camera
    hits = np.stack(list(image_hits(scene).values())).min(axis=0)
    _, directions = rays(cam, *np.mgrid[0:cam.height, 0:cam.width][::-1].reshape(2, -1))
    depth = hits * (directions @ frame(cam)[2]).reshape(hits.shape)
    z_buffer = render_raster(scene).depth
    far_a, far_b = ~np.isfinite(depth), ~np.isfinite(z_buffer)
    with np.errstate(invalid="ignore"):
        apart = np.abs(depth - z_buffer) > 1e-9 * np.maximum(depth, z_buffer)
    parted = int(np.count_nonzero((far_a != far_b) | (~far_a & ~far_b & apart)))
    text = _text(scene, "perspective", "raycast")
    if make is lecture_scene:
        assert parted == 0 and "the same surface at every pixel, at the same depth" in text
    else:
        assert parted > 0.9 * np.count_nonzero(np.isfinite(depth))
        assert f"at every pixel but {parted:,} pixels" in text
    assert "along edges" not in text


def test_the_projection_sentence_appears_only_when_the_projections_differ():
    scene = _small(lecture_scene())
    assert "parallel rays" in _text(scene, "orthographic", "raytrace")
    assert "parallel rays" not in _text(scene, "perspective", "raytrace")


def test_a_picked_pixel_is_read_in_both_outputs_of_a_comparison():
    scene = zbuffer_three_polygons()
    result = compare(scene, "perspective", "raytrace")
    x, y = (int(v) for v in np.floor(scene.camera.project(scene.objects[1].vertices.mean(axis=0)).pixel))
    first, second = result.pixel(x, y)
    assert (first.output, second.output) == ("perspective", "raytrace")
    np.testing.assert_array_equal(first.color, result.a.color[y, x])
    np.testing.assert_array_equal(second.color, result.b.color[y, x])
    corner = result.pixel(0, 0)  # no polygon reaches the image corner: background in both
    assert all("background" in report.found for report in corner)
    assert corner[0].events == () and corner[1].ray_tree.hit is None



def test_the_polygon_count_reads_right_for_one_polygon_and_for_many():
    from core.scene import Mesh, PointLight, Scene

    # One triangle facing the observer, who looks at it from straight in front.
    triangle = Mesh(np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 0.0], [0.0, 1.0, 0.0]]), np.array([[0, 1, 2]]))
    camera = lecture_scene().camera.replace(width=80, height=60, eye=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0))
    one = Scene(camera=camera, objects=(triangle,), lights=(PointLight((0.0, 0.0, 4.0)),))
    assert render_raster(one).stats["polygons_drawn"] == 1
    text = _text(one, "perspective", "raytrace")
    assert "drawing its one polygon" in text and "1 polygons" not in text
    many = _small(lecture_scene())
    assert f"drawing all {render_raster(many).stats['polygons_drawn']:,} polygons" in _text(
        many, "perspective", "raytrace")
