"""Editing a scene through its file form (core.checked_edits): checked like a file, camera kept."""

from __future__ import annotations

import numpy as np
import pytest

from core import checked_edits, presets, shapes
from core.files import scene_file
from core.files.scene_file import SceneFileError
from core.scene import Material, Mesh, PointLight, Scene, Sphere

TETRA_V = np.array([[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
TETRA_T = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])


def _scene() -> Scene:
    return Scene(objects=(Sphere((0.0, 1.0, 0.0), 1.0, name="ball"),
                          shapes.box((3.0, 0.5, 0.0), 1.0, name="cube")),
                 lights=(PointLight((4.0, 8.0, 6.0)),))


def _problems(call) -> list[str]:
    with pytest.raises(SceneFileError) as info:
        call()
    return info.value.problems


def test_a_field_change_keeps_the_camera_and_the_untouched_objects():
    scene = presets.lecture_scene()
    scene = scene.__class__(**{**scene.__dict__, "camera": scene.camera.orbit(30.0, 20.0)})
    edited = checked_edits.with_field(scene, ("object", 0), "material.color", [1.0, 0.0, 0.0])
    assert edited.objects[0].material.color == (1.0, 0.0, 0.0)
    assert edited.objects[0].name == scene.objects[0].name
    assert edited.camera is scene.camera
    assert all(a is b for a, b in zip(edited.objects[1:], scene.objects[1:], strict=True))
    assert edited.lights == scene.lights and edited.background == scene.background


@pytest.mark.parametrize(("item", "key", "value", "message"), [
    # The messages the README gives for scene files.
    (("object", 0), "radius", -1, "objects[0].radius: must be > 0, got -1"),
    (("object", 1), "material.opacity", 1.5, "objects[1].material.opacity: must be in [0, 1], got 1.5"),
    (("object", 0), "center", [0, "a", 0], 'objects[0].center: expected 3 numbers, got [0, "a", 0]'),
    (("light", 0), "intensity", -1, "lights[0].intensity: must be >= 0, got -1"),
    (("background", 0), "color", [2, 0, 0],
     "background: colour components must be in [0, 1], got [2, 0, 0]"),
])
def test_a_value_the_loader_refuses_is_refused_with_its_message(item, key, value, message):
    scene = _scene()
    assert _problems(lambda: checked_edits.with_field(scene, item, key, value)) == [message]


def test_the_scene_wide_triangle_limit_holds_for_added_objects():
    big = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=1000, segments=1000)  # 1,998,000 triangles
    scene = Scene(objects=(big, shapes.box((3.0, 0.0, 0.0), 1.0)))  # the loader counts 24 for a box
    cone = checked_edits.new_object(scene, "cone", (0.0, 0.0, 0.0))
    cone["segments"] = 1000  # 2,000 more: past 2,000,000
    (problem,) = _problems(lambda: checked_edits.added(scene, "object", cone))
    assert problem.startswith("objects[2]: this cone has 2,000 triangles, which takes the scene past")


def test_every_primitive_can_be_added_where_asked_with_a_free_name():
    scene = _scene()
    for type_name in checked_edits.NEW_OBJECTS:
        value = checked_edits.new_object(scene, type_name, (1.0, 2.0, 3.0))
        scene, item = checked_edits.added(scene, "object", value)
        assert item == ("object", len(scene.objects) - 1)
        assert np.allclose(checked_edits.position_of(scene, item), (1.0, 2.0, 3.0))
    names = [o.name for o in scene.objects]
    assert names[2:] == list(checked_edits.NEW_OBJECTS)
    assert len(set(names)) == len(names)
    again, _ = checked_edits.added(scene, "object", checked_edits.new_object(scene, "box", (0, 0, 0)))
    assert again.objects[-1].name == "box 2"


def test_duplicate_goes_after_the_original_with_a_number():
    scene, item = checked_edits.duplicated(_scene(), ("object", 1))
    assert item == ("object", 2)
    assert [o.name for o in scene.objects] == ["ball", "cube", "cube 2"]
    copy_ = scene.objects[2]
    assert np.array_equal(copy_.vertices, scene.objects[1].vertices)
    scene, item = checked_edits.duplicated(scene, ("object", 2))
    assert scene.objects[3].name == "cube 3"
    scene, item = checked_edits.duplicated(scene, ("light", 0))
    assert [light.name for light in scene.lights] == ["light", "light 2"]
    assert scene.lights[1].position == scene.lights[0].position


def test_moving_a_box_moves_its_corners_by_the_same_offset():
    scene = checked_edits.moved(_scene(), ("object", 1), (3.0, 2.5, -1.0))
    assert np.allclose(scene.objects[1].vertices, shapes.box((3.0, 0.5, 0.0), 1.0).vertices + [0, 2, -1])
    assert scene.objects[1].source["center"] == [3.0, 2.5, -1.0]


def test_moving_a_mesh_from_a_file_writes_it_inline(tmp_path):
    path = str(tmp_path / "tetra.obj")
    scene = scene_file.from_dict({"objects": [{"type": "mesh_file", "path": path}]},
                                 read_mesh=lambda p: (TETRA_V, TETRA_T))
    assert np.allclose(checked_edits.position_of(scene, ("object", 0)), (0.5, 0.5, 0.5))
    moved = checked_edits.moved(scene, ("object", 0), (1.5, 0.5, 0.5))  # the file is never read again
    mesh = moved.objects[0]
    assert isinstance(mesh, Mesh) and mesh.source is None and mesh.name == "tetra"
    assert np.allclose(mesh.vertices, TETRA_V + [1.0, 0.0, 0.0])
    assert scene_file.to_dict(moved)["objects"][0]["type"] == "mesh"


def test_a_renamed_mesh_file_is_not_read_again_and_keeps_its_file(tmp_path):
    path = str(tmp_path / "tetra.obj")
    scene = scene_file.from_dict({"objects": [{"type": "mesh_file", "path": path}]},
                                 read_mesh=lambda p: (TETRA_V, TETRA_T))
    renamed = checked_edits.with_field(scene, ("object", 0), "name", "pyramid of four")
    assert renamed.objects[0].name == "pyramid of four"
    assert renamed.objects[0].source["resolved_path"] == path


def test_removed_and_unique_names():
    scene = checked_edits.removed(_scene(), ("object", 0))
    assert [o.name for o in scene.objects] == ["cube"]
    assert checked_edits.removed(scene, ("light", 0)).lights == ()
    assert checked_edits.unique_name("cube", ["cube", "cube 2"]) == "cube 3"
    assert checked_edits.unique_name("cube 2", ["cube", "cube 2"]) == "cube 3"
    assert checked_edits.unique_name("cone", ["cube"]) == "cone"


def test_a_name_another_object_or_light_has_is_refused_saying_whose_it_is():
    """Lessons and their facts pick objects out by name: a second "ball" could not be reached."""
    scene = _scene()
    assert _problems(lambda: checked_edits.with_field(scene, ("object", 1), "name", "ball")) == [
        "objects[1].name: 'ball' is already the name of objects[0]; each object needs a name of its own"]
    assert checked_edits.with_field(scene, ("object", 1), "name", "cube") == scene  # its own, typed again
    assert checked_edits.with_field(scene, ("object", 1), "name", "crate").objects[1].name == "crate"
    lit = Scene(lights=(PointLight((0.0, 5.0, 0.0), name="key"), PointLight((1.0, 5.0, 0.0), name="fill")))
    assert _problems(lambda: checked_edits.with_field(lit, ("light", 1), "name", "key")) == [
        "lights[1].name: 'key' is already the name of lights[0]; each light needs a name of its own"]
    assert checked_edits.with_field(lit, ("light", 1), "name", "ball").lights[1].name == "ball"  # an object's


def test_light_names_are_saved_and_loaded():
    scene = Scene(lights=(PointLight((0.0, 5.0, 0.0), name="key light"),))
    d = scene_file.to_dict(scene)
    assert d["lights"][0]["name"] == "key light"
    assert scene_file.from_dict(d).lights == scene.lights
    assert scene_file.from_dict({"lights": [{"position": [0, 1, 0]}]}).lights[0].name == "light"


def test_a_material_left_at_its_defaults_is_edited_field_by_field():
    scene = _scene()
    edited = checked_edits.with_field(scene, ("object", 0), "material.shininess", 8)
    assert edited.objects[0].material == Material(shininess=8.0)


def test_a_picking_ray_selects_the_nearest_object_it_meets():
    from core.image_order.picking import first_object_hit

    box = shapes.box((0.0, 0.0, 0.0), 1.0)  # its front face is the plane z = 0.5
    ball = Sphere((0.0, 0.0, -5.0), 1.0)
    assert first_object_hit([ball, box], (0, 0, 10), (0, 0, -1)) == (1, 9.5)
    assert first_object_hit([ball, box], (0, 0, 10), (0, 0, -2)) == (1, 4.75)  # t in units of |d|
    assert first_object_hit([ball, box], (3, 0, 10), (0, 0, -1)) is None
    assert first_object_hit([ball, box], (0, 0, -2), (0, 0, -1)) == (0, 2.0)  # past the box: the ball


def test_a_mesh_edit_keeps_its_arrays_and_the_limits_count_it():
    mesh = Mesh(TETRA_V, TETRA_T, name="tetra")
    scene = Scene(objects=(mesh,))
    renamed = checked_edits.with_field(scene, ("object", 0), "material.opacity", 0.5)
    assert np.shares_memory(renamed.objects[0].vertices, mesh.vertices)
    assert renamed.objects[0].material.opacity == 0.5
    assert _problems(lambda: checked_edits.with_field(scene, ("object", 0), "material.ior", 0.5)) == [
        "objects[0].material.ior: must be >= 1, got 0.5"]
    copied, item = checked_edits.duplicated(scene, ("object", 0))
    assert copied.objects[1].name == "tetra 2"
    assert np.shares_memory(copied.objects[1].triangles, mesh.triangles)


def test_the_object_limit_holds_for_added_objects():
    scene = Scene(objects=(Sphere((0.0, 0.0, 0.0), 1.0),) * scene_file.MAX_OBJECTS)
    value = checked_edits.new_object(scene, "sphere", (0.0, 0.0, 0.0))
    assert _problems(lambda: checked_edits.added(scene, "object", value)) == [
        f"objects: at most {scene_file.MAX_OBJECTS:,} are allowed, got {scene_file.MAX_OBJECTS + 1:,}"]


def test_a_mesh_moved_beyond_the_coordinate_limit_is_refused():
    scene = Scene(objects=(Mesh(TETRA_V, TETRA_T, name="tetra"),))
    (problem,) = _problems(lambda: checked_edits.moved(scene, ("object", 0), (2e6, 0.0, 0.0)))
    assert problem == "objects[0].position: numbers must be within ±1,000,000, got [2000000.0, 0.0, 0.0]"
    # A centre within the limit whose vertices are not: the tetrahedron's reach 0.5 beyond its centre.
    (problem,) = _problems(lambda: checked_edits.moved(scene, ("object", 0), (999_999.9, 0.0, 0.0)))
    assert "coordinates must be within ±1,000,000" in problem and problem.startswith("objects[0]")


def test_a_new_objects_place_reads_as_typed_without_a_minus_zero_and_a_point_object_goes_to_the_target():
    """plain_view_spot rounds to a hundredth of the object's size: a target 0.001 left of the
    origin gives 0, not -0 (which the editor shows as "-0.0"); an object with no extent (nothing
    to step by) goes to the observer's target."""
    camera = presets.lecture_scene().camera.replace(target=(-0.001, 0.8, 0.002))
    empty = Scene(camera=camera, objects=())
    spot = checked_edits.plain_view_spot(empty, np.full(3, -0.5), np.full(3, 0.5))  # at the target
    assert [np.copysign(1.0, c) for c in spot] == [1.0, 1.0, 1.0] and list(spot) == [0.0, 0.8, 0.0]
    point = checked_edits.plain_view_spot(empty, np.zeros(3), np.zeros(3))
    assert list(point) == [-0.001, 0.8, 0.002]


def test_a_tiny_new_object_hidden_at_the_target_is_still_placed_in_plain_view():
    """Stepping towards the eye by the object's own size, a speck of 1e-9 behind the lecture
    scene's cone needed about 1e10 steps (their list alone, 77 GB, failed with MemoryError); the
    steps are now at most a hundredth of the way."""
    scene = presets.lecture_scene()
    low, high = np.full(3, -0.5e-9), np.full(3, 0.5e-9)
    spot = checked_edits.plain_view_spot(scene, low, high)
    eye = np.asarray(scene.camera.eye, float)
    assert scene.camera.project(spot).inside
    assert all(checked_edits._misses(eye, spot, checked_edits.object_bounds(obj)) for obj in scene.objects)
