"""A′, where a point's projector meets the screen, worked by hand for a camera on the z axis."""

import numpy as np

from core.camera import Camera
from core.projection_ray import screen_image

EYE_ON_Z = dict(eye=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), near=2.0, far=20.0)


def test_perspective_image_is_where_the_line_to_the_eye_crosses_the_near_plane():
    # A = (1, 2, -3) is 8 in front of the eye; the near plane is 2 in front: A′ = eye + (A - eye) * 2/8.
    image = screen_image(Camera(**EYE_ON_Z), (1.0, 2.0, -3.0))
    assert np.allclose(image, (0.25, 0.5, 3.0))


def test_orthographic_image_keeps_x_and_y_and_lands_on_the_near_plane():
    image = screen_image(Camera(**EYE_ON_Z, projection="orthographic"), (1.0, 2.0, -3.0))
    assert np.allclose(image, (1.0, 2.0, 3.0))


def test_a_point_behind_the_eye_has_no_image():
    assert screen_image(Camera(**EYE_ON_Z), (1.0, 2.0, 9.0)) is None
