"""Framing a view camera on points: worked by hand for a square seen head on."""

import numpy as np
import pytest

from views.scene3d.framing import fit_view, label_bounds


def test_a_square_seen_head_on_through_a_right_angle_is_framed_from_its_half_width():
    # Corners (±1, ±1, 0), looking down -z through 90°: tan 45° = 1, so the eye stands at
    # distance 1 / edge share from the plane: 1 / 0.9 with a 10% margin.
    square = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]
    position, focal, up = fit_view(square, (0, 0, -1), (0, 1, 0), 90.0, 1.0, margin=0.1)
    assert position == pytest.approx((0, 0, 1 / 0.9), abs=1e-6)
    assert focal == pytest.approx((0, 0, 0), abs=1e-6)
    assert up == pytest.approx((0, 1, 0))


def test_a_wide_pane_frames_by_the_height_and_an_off_centre_square_is_centred():
    square = np.array([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]) + (5, 2, 0)
    position, _, _ = fit_view(square, (0, 0, -1), (0, 1, 0), 90.0, 2.0, margin=0.0)
    assert position == pytest.approx((5, 2, 1), abs=1e-6)  # across: 1 / (2 · 1) = 0.5 < 1


def test_a_label_needs_its_half_width_beside_its_anchor_and_its_height_above():
    # A 200 x 20 px text in a 400 x 200 px pane: its anchor at most 0.5 from the sides, 0.2 below the top.
    bounds = label_bounds(200, 20, (400, 200), margin=0.0)
    assert np.allclose(bounds, [[-0.5, 0.5], [-1.0, 0.8]])
    # One label at the square's top centre: the eye must step back until the label fits under the top.
    square = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0), (0, 1, 0)]
    whole = [[-1, 1], [-1, 1]]
    position, _, _ = fit_view(square, (0, 0, -1), (0, 1, 0), 90.0, 2.0,
                              [whole] * 4 + [bounds.tolist()], margin=0.0)
    # Eye at (0, y, z): bottom corner -1 - y = -z, label 1 - y = 0.8 z -> z = 2 / 1.8, y = z - 1.
    assert position == pytest.approx((0, 2 / 1.8 - 1, 2 / 1.8), abs=1e-6)
