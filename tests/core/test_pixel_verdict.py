"""Why this pixel: the verdict and every fragment's fate on scenes whose answers are worked by hand.

The scenes and their answers are in ``tests/verdict_scenes.py``; nothing here is copied from a run.
"""

import json

import numpy as np
import pytest
import verdict_scenes as vs

from core.compare import probe, render_output, why_here
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tree import trace_pixel
from core.object_order.pipeline import RasterSettings, render_raster
from core.pixel_verdict import FATES, raster_verdict, trace_verdict

RECORD = RasterSettings(record_steps=True)


def _raster(scene, settings=RECORD, pixel=vs.PIXEL):
    result = render_raster(scene, settings)
    return result, raster_verdict(result, *pixel)


def _fates(verdict):
    return [(f.object, f.fate) for f in verdict.fragments]


def test_a_pixel_covered_only_by_a_back_face_is_culled_and_keeps_the_background():
    scene = vs.back_face_only()
    result, v = _raster(scene)
    assert (v.verdict, v.object) == ("culled", None)
    assert _fates(v) == [("ground", "culled")]
    assert v.fragments[0].depth == pytest.approx(10.0)  # the quad at y = 0, the eye at y = -10
    assert "back face" in v.sentence and "ground" in v.sentence
    x, y = vs.PIXEL
    assert np.allclose(result.color[y, x], scene.background)


def test_without_back_face_culling_the_same_back_face_is_drawn_and_kept():
    _, v = _raster(vs.back_face_only(), RasterSettings(record_steps=True, back_face_culling=False))
    assert (v.verdict, v.object) == ("visible", "ground")
    assert _fates(v) == [("ground", "kept")]


@pytest.mark.parametrize("near_first, far_fate", [(True, "failed z-test"), (False, "overwritten")])
def test_the_nearer_of_two_quads_wins(near_first, far_fate):
    _, v = _raster(vs.two_quads(near_first))
    assert (v.verdict, v.object) == ("visible", "near")
    assert sorted(_fates(v)) == sorted([("near", "kept"), ("far", far_fate)])
    depths = {f.object: f.depth for f in v.fragments}
    assert depths == pytest.approx({"near": 8.0, "far": 10.0})  # eye at y = 10, quads at y = 2 and y = 0
    assert "near" in v.sentence and "2 fragments" in v.sentence
    if near_first:
        assert "far failed the z-test" in v.sentence


def test_step_limits_the_verdict_to_the_polygons_drawn_so_far():
    result = render_raster(vs.two_quads(near_first=False), RECORD)
    # The far quad's two triangles are polygons 1 and 2: after them, far is what the pixel shows.
    v = raster_verdict(result, *vs.PIXEL, step=2)
    assert (v.verdict, v.object) == ("visible", "far")
    assert v.sentence.startswith("After 2 polygons")
    one = raster_verdict(result, *vs.PIXEL, step=1)  # not "After 1 polygons"
    assert one.sentence.startswith("After 1 polygon: "), one.sentence


def test_a_quad_nearer_than_the_near_plane_is_clipped_there():
    scene = vs.before_near_plane()
    result, v = _raster(scene)
    assert (v.verdict, v.object) == ("clipped", None)
    [f] = v.fragments
    assert (f.object, f.fate, f.plane) == ("pane", "clipped", "near")
    assert f.depth == pytest.approx(0.5)  # the quad at y = 9.5, the eye at y = 10
    assert "near plane" in v.sentence
    x, y = vs.PIXEL
    assert np.allclose(result.color[y, x], scene.background)


def test_a_quad_beyond_the_far_plane_is_clipped_at_the_far_plane():
    # The same quad 0.5 below the eye, with the frustum from 0.1 to 0.4: beyond its end plane.
    scene = vs.before_near_plane()
    scene = type(scene)(camera=scene.camera.replace(near=0.1, far=0.4), objects=scene.objects)
    _, v = _raster(scene)
    assert v.verdict == "clipped"
    assert [(f.fate, f.plane) for f in v.fragments] == [("clipped", "far")]


def test_a_quad_wholly_beyond_the_far_plane_is_culled_by_the_frustum_not_clipped():
    scene = vs.beyond_far_plane()
    result, v = _raster(scene)
    assert result.objects.state == ("outside",)  # worked in the scene's docstring
    assert (v.verdict, v.object) == ("frustum-culled", None)
    [f] = v.fragments
    assert (f.object, f.fate, f.plane) == ("distant", "frustum-culled", "far")
    assert f.depth == pytest.approx(40.0)  # the quad at y = -30, the eye at y = 10
    assert v.sentence.startswith("Culled by the frustum at the far plane: distant reaches this pixel only "
                                 "beyond the far plane (40 > 30)")
    assert "frustum culling dropped the whole object before clipping" in v.sentence
    assert "clipped" not in v.sentence.lower()
    x, y = vs.PIXEL
    assert np.allclose(result.color[y, x], scene.background)


def test_without_frustum_culling_the_same_quad_is_clipped_at_the_far_plane():
    _, v = _raster(vs.beyond_far_plane(), RasterSettings(record_steps=True, frustum_culling=False))
    assert v.verdict == "clipped"
    assert [(f.fate, f.plane) for f in v.fragments] == [("clipped", "far")]
    assert "frustum culling" not in v.sentence and "clipped away" in v.sentence


def test_compare_names_frustum_culling_as_what_dropped_the_object():
    # Perspective against ray casting: the tracer's primary rays end at the far plane too, so both
    # show the background; against a far plane moved past the quad only the tracer sees it.
    scene = vs.beyond_far_plane()
    a = render_output(scene, "perspective")
    tracer_scene = type(scene)(camera=scene.camera.replace(far=50.0), objects=scene.objects)
    b = render_output(tracer_scene, "raycast")
    ra, rb = probe(a, *vs.PIXEL), probe(b, *vs.PIXEL)
    assert (ra.verdict.verdict, rb.verdict.object) == ("frustum-culled", "distant")
    assert "before the z-buffer, frustum culling dropped what reaches this pixel" in why_here(a, b, ra, rb)


def test_a_transparent_pane_over_a_box_is_blended_over_the_box_top():
    _, v = _raster(vs.pane_over_box())
    assert (v.verdict, v.object) == ("blended", "pane")
    assert sorted(_fates(v)) == sorted([("box", "kept"), ("pane", "blended"), ("box", "culled")])
    by_fate = {f.fate: f for f in v.fragments}
    assert by_fate["kept"].depth == pytest.approx(9.0)     # the box's top face, y = 1
    assert by_fate["blended"].depth == pytest.approx(8.0)  # the pane, y = 2
    assert by_fate["culled"].depth == pytest.approx(11.0)  # the box's bottom face, y = -1
    assert by_fate["blended"].alpha == 0.4
    assert "0.4" in v.sentence and "box" in v.sentence


def test_an_empty_pixel_is_background():
    scene = vs.two_quads()
    _, v = _raster(scene, pixel=(0, 0))  # the corner ray misses both quads (6 units wide at distance 10)
    assert (v.verdict, v.object, v.fragments) == ("background", None, ())


def test_the_raster_json_has_the_fields_and_vocabulary_of_the_command():
    _, v = _raster(vs.pane_over_box())
    data = json.loads(json.dumps(v.to_dict(), allow_nan=False))
    assert {"verdict", "object", "sentence", "fragments"} <= data.keys()
    for f in data["fragments"]:
        assert {"object", "polygon", "depth", "fate"} <= f.keys()
        assert f["fate"] in FATES


def _traced(scene, pixel=(20, 15), mode="raytrace"):
    settings = TraceSettings(mode=mode)
    return trace_verdict(trace_pixel(scene, *pixel, settings), scene, mode, *pixel)


def test_a_floor_point_in_the_balls_shadow_for_one_light_and_lit_by_the_other():
    v = _traced(vs.ball_shadow(), mode="raycast")
    assert (v.verdict, v.object) == ("hit", "floor")
    lights = {light.name: (light.lit, light.blocked_by) for light in v.lights}
    assert lights == {"sun": (False, "ball"), "fill": (True, None)}
    assert "in the shadow of ball for sun" in v.sentence and "lit by fill" in v.sentence
    assert f"t = {np.sqrt(45.0):.6g}" in v.sentence  # six digits, as the worked math writes t
    assert v.rays == {"primary": 1, "shadow": 2, "reflection": 0, "refraction": 0}


def test_a_mirror_takes_part_of_its_colour_from_the_reflected_ray_which_hits_the_wall():
    v = _traced(vs.mirror_ball())
    assert (v.verdict, v.object) == ("hit", "mirror")
    assert "t = 4" in v.sentence
    assert "80%" in v.sentence and "reflected ray, which hits wall" in v.sentence
    assert v.rays["reflection"] == 1


def test_a_glass_ball_is_split_by_fresnel():
    v = _traced(vs.glass_ball())
    assert (v.verdict, v.object) == ("hit", "glass")
    assert "R = 0.04" in v.sentence and "T = 0.96" in v.sentence
    assert "refracted ray hits glass" in v.sentence  # straight through, to the far side from inside
    assert v.rays["refraction"] >= 1


def test_a_ray_inside_glass_beyond_the_critical_angle_is_totally_reflected():
    v = _traced(vs.glass_block())
    assert (v.verdict, v.object) == ("hit", "glass")
    assert "R = 0.0892" in v.sentence  # Fresnel at 60 degrees, worked in the scene's docstring
    assert "total internal reflection inside glass" in v.sentence
    assert "critical angle 41.8°" in v.sentence and "at (1, 0.293, 0) (2 times in all)" in v.sentence
    # Where (tan(theta2) = 1/sqrt(2) inside): the side x = 1 at y = 1 - 1/sqrt(2); the bottom at
    # x = 1 - (2 - 1/sqrt(2)) / sqrt(2) = 1.5 - sqrt(2); the side x = -1 at y = -1 + sqrt(2) (2.5 - sqrt(2)).
    first, second = v.total_internal_reflection
    assert first.object == second.object == "glass"
    assert np.allclose(first.point, (1, 1 - 1 / np.sqrt(2), 0), atol=1e-9)
    assert np.allclose(second.point, (-1, 2.5 * np.sqrt(2) - 3, 0), atol=1e-9)
    assert first.critical_deg == pytest.approx(np.degrees(np.arcsin(1 / 1.5)), abs=1e-12)  # 41.81
    data = json.loads(json.dumps(v.to_dict(), allow_nan=False))
    assert [r["object"] for r in data["total_internal_reflection"]] == ["glass", "glass"]


def test_a_glass_ball_never_reflects_totally():
    # Inside a sphere a refracted ray meets the surface at the angle it entered at, always below
    # the critical angle: the glass ball's pixel has no total internal reflection.
    v = _traced(vs.glass_ball())
    assert v.total_internal_reflection == () and "total internal" not in v.sentence


def test_a_ray_past_everything_is_a_miss():
    v = _traced(vs.mirror_ball(), pixel=(0, 0))
    assert (v.verdict, v.object, v.lights) == ("miss", None, ())
    data = json.loads(json.dumps(v.to_dict(), allow_nan=False))
    assert data["rays"]["primary"] == 1 and data["lights"] == []


def test_compare_says_why_two_outputs_differ_at_a_shadowed_pixel():
    scene = vs.ball_shadow()
    a, b = render_output(scene, "perspective"), render_output(scene, "raycast")
    ra, rb = probe(a, 20, 15), probe(b, 20, 15)
    assert (ra.verdict.object, rb.verdict.object) == ("floor", "floor")
    assert ra.found == ra.verdict.sentence and "kept by the z-buffer" in ra.found
    why = why_here(a, b, ra, rb)
    assert why.startswith("Both show floor here")
    assert "a shadow only the tracer computes (ball blocks sun)" in why


def test_compare_says_only_ray_tracing_follows_the_mirror_and_the_sphere_is_faceted():
    scene = vs.mirror_ball()
    a, b = render_output(scene, "perspective"), render_output(scene, "raytrace")
    why = why_here(a, b, probe(a, 20, 15), probe(b, 20, 15))
    assert "faceted sphere" in why
    assert "only ray tracing follows the reflected and refracted rays of mirror" in why
    c = render_output(scene, "raycast")
    assert "only ray tracing follows" in why_here(c, b, probe(c, 20, 15), probe(b, 20, 15))
