"""The viewing lessons' exercises: where a corner lands, and which picture is which view.

The references: the observer's frame and the projections written out by hand (:mod:`hand_rays`,
nothing of :mod:`core.projection`), and the pictures read for where the blue cone and the orange
cube lie in them.
"""

import math

import numpy as np
import pytest
from hand_rays import frame, half_size, image_hits, nearest, pixel_of
from shipped_exercises import exercise

from core.lessons.exercises import PICTURE_SIZE, judge, pictures


def _corner_6(p):
    scene = p.step.scene
    return scene, next(o for o in scene.objects if o.name == "cube").vertices[6]


def test_perspective_a_prime_lands_where_the_line_to_the_eye_crosses_the_screen():
    # A = (-0.9, 1.6, -1.9); in the observer's frame its offsets (x, y, depth) divided by the depth are
    # A′ on the image plane at distance 1 (x′ = x d / z with d = 1), then scaled to the 320 x 240 pixels.
    ex, p = exercise("perspective", 0)
    scene, corner = _corner_6(p)
    assert corner == pytest.approx([-0.9, 1.6, -1.9])
    right, up, forward = frame(scene.camera)
    offset = corner - np.asarray(scene.camera.eye)
    hw, hh = half_size(scene.camera)
    u, v = (offset @ right) / (offset @ forward), (offset @ up) / (offset @ forward)
    pixel = (math.floor((u / hw + 1) * 160), math.floor((1 - v / hh) * 120))
    assert pixel == pixel_of(scene.camera, corner)
    assert judge(ex, p, pixel).right
    assert not judge(ex, p, (pixel[0] + 1, pixel[1])).right
    assert not judge(ex, p, (pixel[0], pixel[1] - 1)).right


def test_orthographic_the_corner_keeps_its_x_and_y():
    # Parallel projection: no division by depth; the view volume is 6 high and 8 wide, so a unit is
    # 40 pixels: A′ = (160 + 40 x, 120 - 40 y) with x, y A's offsets along right and up.
    ex, p = exercise("orthographic", 0)
    scene, corner = _corner_6(p)
    right, up, _ = frame(scene.camera)
    offset = corner - np.asarray(scene.camera.eye)
    assert scene.camera.ortho_height == 6 and (scene.camera.width, scene.camera.height) == (320, 240)
    pixel = (math.floor(160 + 40 * (offset @ right)), math.floor(120 - 40 * (offset @ up)))
    assert pixel == pixel_of(scene.camera, corner)
    assert judge(ex, p, pixel).right
    perspective = pixel_of(exercise("perspective", 0)[1].step.scene.camera, corner)
    assert perspective != pixel and not judge(ex, p, perspective).right


def _cone_and_cube(rgb):
    """Masks of the blue cone ((0.15, 0.55, 0.75) lit: blue 5 times red, even in its shade) and the
    orange cube ((0.95, 0.55, 0.2) lit); the grey ground and the background (blue 2.4 times red) are
    neither."""
    cone = (rgb[..., 2] > 3 * rgb[..., 0]) & (rgb[..., 2] > rgb[..., 0] + 0.05)
    cube = (rgb[..., 0] > rgb[..., 2] + 0.3) & (rgb[..., 0] > 0.4)
    return cone, cube


def test_three_views_the_perspective_sketch_is_the_picture_the_observers_rays_see():
    # Every pixel's ray from the observer's eye, brute force, at the pictures' size: where the cone is
    # nearest.  Only one picture puts the cone there.
    ex, p = exercise("three_views", 2)
    camera = p.step.scene.camera.replace(width=PICTURE_SIZE[0], height=PICTURE_SIZE[1])
    cast = nearest(image_hits(p.step.scene, camera)) == "cone"
    overlap = {}
    for key, rgb in pictures(ex, p).items():
        cone, _ = _cone_and_cube(rgb)
        overlap[key] = np.count_nonzero(cone & cast) / np.count_nonzero(cone | cast)
    assert overlap["observer"] > 0.85 and max(v for k, v in overlap.items() if k != "observer") < 0.5
    assert judge(ex, p, "observer").right
    assert not judge(ex, p, "front").right


def test_three_views_the_side_view_shows_the_cone_beside_the_cube_along_z():
    # Seen from +x looking down -x with y up, right is forward × up = (-1, 0, 0) × (0, 1, 0) = (0, 0, -1):
    # the cone (z = 1.0) is left of the cube (z = -1.1).  From the front (looking down -z) right is +x,
    # and the cone (x = 0.6) is right of the cube (x = -1.7).  From the side the cone is a triangle
    # 2r = 2 wide and h = 2.2 high, the cube a square 1.6 wide.
    ex, p = exercise("three_views", 4)
    drawn = pictures(ex, p)
    cone_left_of_cube = {}
    for key in ("front", "side"):
        cone, cube = _cone_and_cube(drawn[key])
        cone_xs, cube_xs = np.nonzero(cone)[1], np.nonzero(cube)[1]
        cone_left_of_cube[key] = cone_xs.max() < cube_xs.min()
        assert (np.ptp(cube_xs) + 1) / (np.ptp(cone_xs) + 1) == pytest.approx(1.6 / 2, rel=0.1)
    assert cone_left_of_cube == {"front": False, "side": True}
    ys, xs = np.nonzero(_cone_and_cube(drawn["side"])[0])
    assert (np.ptp(xs) + 1) / (np.ptp(ys) + 1) == pytest.approx(2 / 2.2, rel=0.1)
    assert judge(ex, p, "side").right
    assert not judge(ex, p, "front").right
