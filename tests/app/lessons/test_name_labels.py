"""Where a lesson writes an object's name in the 3D pane: above it, or on it when it is flat (which names
its words name: tests/core/lessons/test_naming.py)."""

import numpy as np
import pytest

from app.lessons.runner import _label_point, _top
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
