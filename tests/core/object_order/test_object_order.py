"""The whole object-order pipeline: stages, switches, records and the ray caster as a reference."""

from __future__ import annotations

import json

import brute_force
import numpy as np
import pytest

from core import presets
from core.object_order import pipeline
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Scene, Sphere


def _small(scene: Scene, width=160, height=120) -> Scene:
    return Scene(camera=scene.camera.replace(width=width, height=height), objects=scene.objects,
                 lights=scene.lights, background=scene.background)


def test_stats_are_json_and_count_every_stage():
    result = render_raster(_small(presets.frustum_cases()), RasterSettings(record_steps=True))
    stats = json.loads(json.dumps(result.stats))
    for key in ("faces_culled", "objects_outside", "objects_inside", "objects_crossing",
                "polygons_clipped", "fragments_generated", "fragments_passed", "fragments_failed",
                "blends"):
        assert isinstance(stats[key], int), key
    assert stats["fragments_generated"] == stats["fragments_passed"] + stats["fragments_failed"]
    assert stats["fragments_generated"] == int(result.draw.generated.sum())
    assert set(stats["times"]) >= {"transform", "back_face_culling", "frustum_culling", "clipping",
                                   "projection", "rasterization"}
    assert all(t >= 0 for t in stats["times"].values())
    assert stats["faces"] == len(result.faces.visible) == result.face_offsets[-1]


def test_frustum_cases_are_classified_and_culling_them_changes_no_pixel():
    scene = _small(presets.frustum_cases())
    result = render_raster(scene)
    names = [o.name for o in scene.objects]
    state = dict(zip(names, result.objects.state, strict=True))
    assert state == {"cube": "inside", "cone": "inside", "ground": "crossing",
                     "sphere": "crossing", "box": "outside"}
    assert result.stats["objects_outside"] == 1 and result.stats["objects_crossing"] == 2
    assert result.stats["faces_in_objects_outside"] == 12
    assert result.stats["polygons_clipped"] > 0
    assert not np.any(result.draw.object_index == names.index("box"))
    # Frustum culling is an optimisation: switched off, clipping throws the same polygons away.
    unculled = render_raster(scene, RasterSettings(frustum_culling=False))
    assert unculled.objects is None and unculled.stats["objects_not_tested"] == 5
    assert np.array_equal(unculled.color, result.color)
    assert unculled.stats["triangles_rejected_by_clipping"] > result.stats["triangles_rejected_by_clipping"]


def test_clipping_switched_off_breaks_the_image_of_a_plane_reaching_behind_the_eye():
    scene = _small(presets.frustum_cases())
    right = render_raster(scene)
    wrong = render_raster(scene, RasterSettings(clipping=False))
    assert np.mean(np.any(wrong.color != right.color, axis=-1)) > 0.02


def test_back_face_culling_is_an_optimisation_for_closed_solids():
    scene = _small(presets.lecture_scene())
    culled = render_raster(scene)
    everything = render_raster(scene, RasterSettings(back_face_culling=False))
    assert culled.stats["faces_culled"] > 0 and everything.stats["faces_culled"] == 0
    assert len(everything.draw) > len(culled.draw)
    assert np.mean(np.all(everything.color == culled.color, axis=-1)) > 0.999


def test_notched_prism_front_face_survives_culling_and_the_zbuffer_hides_part_of_it():
    scene = _small(presets.culling_notched(), 240, 180)
    result = render_raster(scene)
    prism = result.meshes[0]
    # The notch's inner wall: the faces facing +z that are not on the prism's front side.
    inner = np.flatnonzero(np.isclose(prism.normals[:, 2], 1.0)
                           & (prism.corners[:, :, 2].max(axis=1) < prism.vertices[:, 2].max() - 1e-9))
    assert len(inner) == 2
    assert result.faces.visible[inner].all()  # front-facing: culling keeps it
    drawn = np.isin(result.draw.triangle_index, inner)
    assert result.draw.passed[drawn].sum() > 0  # partly seen
    assert result.draw.failed[drawn].sum() > 0  # partly hidden by the L's other arm
    # What is seen agrees with the ray caster (which knows nothing of culling).
    cast = brute_force.cast(scene)
    hit = cast.object_index >= 0
    _, directions = scene.camera.primary_rays()
    cast_depth = cast.t * (directions @ scene.camera.forward)
    both = hit & np.isfinite(result.depth)
    assert np.mean(hit == np.isfinite(result.depth)) > 0.998
    assert np.median(np.abs(result.depth[both] - cast_depth[both])) < 1e-9


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_raster_and_ray_caster_agree_on_the_lecture_scene(projection):
    scene = _small(presets.lecture_scene())
    scene = Scene(camera=scene.camera.replace(projection=projection), objects=scene.objects,
                  lights=scene.lights)
    result = render_raster(scene)
    assert np.array_equal(result.clip_from_view, scene.camera.clip_from_view)
    cast = brute_force.cast(scene)
    assert np.mean((cast.object_index >= 0) == np.isfinite(result.depth)) > 0.995
    # Flat shading per face is close to per-pixel Lambert: the same colours on the whole.
    assert np.median(np.abs(cast.color - result.color)) < 0.02


def test_analytic_spheres_are_tessellated_and_faces_are_addressed_per_object():
    scene = _small(presets.frustum_cases())
    result = render_raster(scene)
    sphere_index = next(i for i, o in enumerate(scene.objects) if isinstance(o, Sphere))
    mesh = result.meshes[sphere_index]
    assert len(mesh.triangles) == 2 * pipeline.SPHERE_SEGMENTS * (pipeline.SPHERE_RINGS - 1)
    assert np.allclose(np.linalg.norm(mesh.vertices - scene.objects[sphere_index].center, axis=1), 1.0)
    face = result.face_index(sphere_index, 7)
    assert face == sum(len(m.triangles) for m in result.meshes[:sphere_index]) + 7
    normal = result.faces.normal[face]
    world_normal = mesh.normals[7] @ result.view_from_world[:3, :3].T
    assert np.allclose(normal, world_normal) and result.faces.nz[face] == normal[2]
    # Every drawn polygon's world vertices lie on the plane of the face it came from.
    for p in range(0, len(result.draw), 97):
        obj, tri = result.draw.object_index[p], result.draw.triangle_index[p]
        corners = result.meshes[obj].corners[tri]
        n = np.cross(corners[1] - corners[0], corners[2] - corners[0])
        assert np.allclose((result.draw.polygons.world_vertices(p) - corners[0]) @ n, 0, atol=1e-9)


def test_clipped_polygons_are_kept_in_world_space_inside_the_frustum():
    scene = _small(presets.frustum_cases())
    result = render_raster(scene)
    pieces = result.clipping.clipped_polygons()
    assert len(pieces) == result.stats["polygons_clipped"] > 0
    planes = scene.camera.frustum_planes()
    for piece in pieces:
        assert np.all(piece @ planes[:, :3].T + planes[:, 3] >= -1e-9)


def test_empty_scene_is_background_at_infinite_depth():
    scene = Scene(camera=presets.lecture_scene().camera.replace(width=20, height=10))
    result = render_raster(scene, RasterSettings(record_steps=True))
    assert np.all(result.color == scene.background) and np.all(np.isinf(result.depth))
    assert result.stats["fragments_generated"] == 0 and result.history.n_steps == 0
    json.dumps(result.stats)


def test_presets_menu_lists_every_scene():
    assert presets.PRESETS["lecture"] == (presets.PRESETS["lecture"][0], presets.lecture_scene)
    for key, (title, build) in presets.PRESETS.items():
        scene = build()
        assert isinstance(scene, Scene) and scene.objects and title, key
    three = presets.zbuffer_three_polygons()
    assert [o.name for o in three.objects] == ["green", "blue", "yellow"]
