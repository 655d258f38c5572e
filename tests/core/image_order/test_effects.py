"""The effects plan: only what the scene calls for is simulated."""

import json
from dataclasses import replace

import pytest

from core import presets, presets_trace, shapes
from core.image_order.effects_plan import PAIRS_LIMIT, effects_plan
from core.scene import Material, PointLight, Scene, Sphere


def test_lecture_scene_needs_shadow_rays_and_nothing_else():
    plan = effects_plan(presets.lecture_scene())
    assert not plan.reflection_rays and not plan.refraction_rays and not plan.fresnel
    assert plan.shadow_rays and plan.lights[0].blockable
    assert not plan.transparency_pass
    json.dumps(plan.to_dict())


def test_mirror_and_glass_needs_everything():
    plan = effects_plan(presets_trace.mirror_and_glass())
    assert plan.reflection_rays and plan.refraction_rays and plan.fresnel and plan.shadow_rays
    assert plan.transparency_pass
    # Its reasons name the mirror and the glass ball as a sentence lists them (they read "mirror
    # ball, glass ball reflect").
    assert "reflection rays: mirror ball and glass ball reflect" in plan.reasons[0]
    assert "refraction rays and Fresnel terms: glass ball transparent" in plan.reasons[1]


def test_a_mirror_alone_needs_reflection_but_no_refraction_or_fresnel():
    scene = replace(presets.lecture_scene(), objects=(
        *presets.lecture_scene().objects, Sphere((2.0, 1.0, 2.0), 0.5, Material(reflectivity=0.8))))
    plan = effects_plan(scene)
    assert plan.reflection_rays and not plan.refraction_rays and not plan.fresnel


def test_ray_casting_mode_never_reflects_or_refracts():
    plan = effects_plan(presets_trace.mirror_and_glass(), mode="raycast")
    assert not plan.reflection_rays and not plan.refraction_rays
    assert plan.shadow_rays


def test_no_lights_no_shadow_rays():
    plan = effects_plan(presets_trace.no_lights())
    assert plan.lights == () and not plan.shadow_rays


def test_a_lone_sphere_cannot_shadow_anything():
    plan = effects_plan(presets_trace.lone_sphere())
    assert not plan.lights[0].blockable and not plan.shadow_rays


def test_a_convex_mesh_alone_cannot_shadow_itself_but_a_non_convex_one_can():
    light = (PointLight((3.0, 5.0, 4.0)),)
    box = Scene(objects=(shapes.box((0.0, 0.0, 0.0), 1.0),), lights=light)
    prism = Scene(objects=(shapes.notched_prism((0.0, 0.0, 0.0), 2.0, 1.0),), lights=light)
    assert not effects_plan(box).lights[0].blockable
    assert effects_plan(prism).lights[0].blockable


def test_a_sphere_above_the_ground_shadows_the_ground_but_not_the_other_way_round():
    ground = shapes.quad((0.0, 0.0, 0.0), 10.0, name="ground")
    ball = Sphere((0.0, 1.5, 0.0), 1.0, name="ball")
    above = Scene(objects=(ground, ball), lights=(PointLight((0.0, 6.0, 0.0)),))
    plan = effects_plan(above)
    assert plan.lights[0].blockable and plan.lights[0].reason.startswith("ball may shadow ground")
    # Light off to the side, the ball far from the line to it: nothing can block.
    apart = Scene(objects=(Sphere((-5.0, 1.0, 0.0), 1.0, name="a"), Sphere((5.0, 1.0, 0.0), 1.0, name="b")),
                  lights=(PointLight((0.0, 1.0, 20.0)),))
    assert not effects_plan(apart).lights[0].blockable


def test_objects_resting_on_the_ground_shadow_it_but_the_ground_shadows_none_of_them():
    # The lecture scene: cube and cone stand on the ground (their lowest vertices at y = 0, in the
    # ground's plane), the light above.  A segment from any of their points to the light rises from
    # y >= 0, so it never meets the ground again; what the light's shadow rays are for is the cube's
    # and the cone's shadows on the ground, and that is the reason given: both of them (the reason
    # named only the first pair it found, "cube may shadow ground", beside a picture of two shadows).
    scene = presets.lecture_scene()
    ground = next(o for o in scene.objects if o.name == "ground")
    assert all(o.vertices[:, 1].min() == 0.0 for o in scene.objects)  # all resting in the plane y = 0
    assert scene.lights[0].position[1] > 0 and set(ground.vertices[:, 1]) == {0.0}
    reason = effects_plan(scene).lights[0].reason
    assert reason == "cube and cone may shadow ground: shadow rays"
    # A box alone on the ground: the box shadows the ground, the ground nothing.
    box = shapes.box((0.0, 0.5, 0.0), 1.0, name="box")
    ground = shapes.quad((0.0, 0.0, 0.0), 10.0, name="ground")
    assert box.vertices[:, 1].min() == 0.0
    alone = Scene(objects=(box, ground), lights=(PointLight((0.0, 6.0, 0.0)),))
    assert effects_plan(alone).lights[0].reason == "box may shadow ground: shadow rays"
    # Only the ground and a decal lying in it: neither can shadow the other.
    decal = shapes.quad((0.0, 0.0, 0.0), 1.0, name="decal")
    flat = Scene(objects=(ground, decal), lights=(PointLight((0.0, 6.0, 0.0)),))
    assert not effects_plan(flat).lights[0].blockable


def test_the_plan_names_which_objects_may_shadow_each_object():
    # Two balls high above the ground, far apart, the light straight above the first: both may
    # shadow the ground (it lies below them, towards the light's other side); the second lies
    # far from the line from the first to the light, and the ground is flat under both, so
    # nothing can shadow either ball.  A notched prism is not convex: it may shadow itself.
    ground = shapes.quad((0.0, 0.0, 0.0), 40.0, name="ground")
    a, b = Sphere((0.0, 3.0, 0.0), 1.0, name="a"), Sphere((12.0, 3.0, 0.0), 1.0, name="b")
    plan = effects_plan(Scene(objects=(ground, a, b), lights=(PointLight((0.0, 10.0, 0.0)),)))
    assert plan.lights[0].blockers == ((1, 2), (), ())
    # A third ball on the line from the first to the light: it may shadow the first.
    c = Sphere((0.0, 6.0, 0.0), 1.0, name="c")
    plan = effects_plan(Scene(objects=(ground, a, c), lights=(PointLight((0.0, 10.0, 0.0)),)))
    assert plan.lights[0].blockers == ((1, 2), (2,), ())
    assert plan.lights[0].reason == "a and c may shadow ground; c may shadow a: shadow rays"
    prism = shapes.notched_prism((0.0, 1.0, 0.0), 2.0, 1.0, name="prism")
    plan = effects_plan(Scene(objects=(prism,), lights=(PointLight((3.0, 5.0, 4.0)),)))
    assert plan.lights[0].blockers == ((0,),)
    assert plan.lights[0].reason == "prism may shadow itself (not convex): shadow rays"


def test_past_the_pairs_limit_the_first_shadowing_pair_decides_and_no_blockers_are_named():
    balls = tuple(Sphere((3.0 * k, 1.0, 0.0), 1.0, name=f"ball {k}") for k in range(PAIRS_LIMIT + 1))
    ground = shapes.quad((0.0, 0.0, 0.0), 200.0, name="ground")
    light = (PointLight((0.0, 10.0, 0.0)),)
    many = effects_plan(Scene(objects=(ground, *balls), lights=light)).lights[0]
    assert many.blockable and many.reason == "ball 0 may shadow ground: shadow rays" and many.blockers is None
    few = effects_plan(Scene(objects=(ground, *balls[:2]), lights=light)).lights[0]
    assert few.blockers == ((1, 2), (), ())
    assert few.reason == "ball 0 and ball 1 may shadow ground: shadow rays"  # every pair, once worked out


@pytest.mark.parametrize("opacity, expected", [(1.0, False), (0.5, True)])
def test_transparency_pass_follows_opacity(opacity, expected):
    scene = Scene(objects=(Sphere((0.0, 0.0, 0.0), 1.0, Material(opacity=opacity)),))
    assert effects_plan(scene).transparency_pass is expected


def test_bad_mode_is_refused():
    with pytest.raises(ValueError, match="mode"):
        effects_plan(Scene(), mode="pathtrace")
