"""Where a lesson writes an object's name in the 3D pane: above it, or on it when it is flat."""

import numpy as np
import pytest

from app.lessons.runner import _label_point, _top, named_objects
from core import presets


def test_the_grounds_name_is_written_on_the_ground_away_from_the_cube_and_the_cone():
    # Above its middle, the ground's name stood beside the cube and the cone standing there.
    scene = presets.lecture_scene()
    cube, cone, ground = scene.objects
    at = _label_point(ground, [cube, cone])
    # By hand: the ground spans x, z in [-7, 7]; the spots 20 % in from its edges are x, z in
    # {-4.2, 0, 4.2}.  The cube's centre is (-1.7, -1.1) in x, z, the cone's (0.6, 1.0); the spot
    # (4.2, -4.2) is 6.67 from the cube and 6.29 from the cone, the farthest from both of any spot
    # (next: (-4.2, 4.2), 5.77 from the cone).  It is written just above the ground (0.08 = 8 % of
    # its height plus one).
    assert at == pytest.approx([4.2, 0.08, -4.2])
    for other in (cube, cone):
        low, high = np.asarray(other.vertices).min(axis=0), np.asarray(other.vertices).max(axis=0)
        outside = np.maximum(low[[0, 2]] - at[[0, 2]], at[[0, 2]] - high[[0, 2]]).max()
        assert outside > 2.0  # well clear of the object's footprint


def test_an_object_that_is_not_flat_keeps_its_name_above_it():
    scene = presets.lecture_scene()
    cube, cone, ground = scene.objects
    assert np.array_equal(_label_point(cube, [cone, ground]), _top(cube))
    top = _top(cube)
    assert top[1] > np.asarray(cube.vertices)[:, 1].max()  # above the cube's top


def test_a_lesson_names_an_object_by_its_whole_name_and_not_inside_another_word():
    # The frustum example's objects are "sphere" and "box": a sentence about a bounding box or a
    # bounding sphere does not speak of them, nor does "sandbox"; "the cones" speaks of the cone.
    scene = presets.frustum_cases()
    names = [obj.name for obj in scene.objects]
    assert "sphere" in names and "box" in names

    def named(text):
        return [obj.name for obj in named_objects(scene, text)]

    assert named("The bounding box of the sphere lies outside.") == ["sphere"]
    assert named("Its bounding sphere straddles the plane; the box is behind the observer.") == ["box"]
    assert named("A sandbox of spheres.") == ["sphere"]
    assert named("Nothing here.") == []
    lecture = presets.lecture_scene()
    assert [obj.name for obj in named_objects(lecture, "Both cones and the cube's bounding box.")] == [
        "cube", "cone"]
