"""Placing a label clear of the lines around the point it names: checked by sampling the lines."""

import numpy as np

from views.scene3d.label_placement import place_label, segments_meet_box


def _touches(box, p, q, half) -> bool:
    """Brute force: does any of 2001 points along p-q come within ``half`` of ``box``?"""
    t = np.linspace(0, 1, 2001)[:, None]
    pts = np.asarray(p) * (1 - t) + np.asarray(q) * t
    dx = np.maximum(0, np.maximum(box[0] - pts[:, 0], pts[:, 0] - box[2]))
    dy = np.maximum(0, np.maximum(box[1] - pts[:, 1], pts[:, 1] - box[3]))
    return bool((np.hypot(dx, dy) <= half).any())


def test_a_segment_meets_a_box_when_it_crosses_it_or_passes_within_its_half_width():
    box = (10, 10, 20, 20)
    p = np.array([[0, 0], [0, 15], [0, 23], [0, 23], [15, 0]], float)
    q = np.array([[30, 30], [30, 15], [30, 23], [30, 23], [15, 5]], float)
    pad = np.array([0, 0, 2, 4, 0], float)
    assert segments_meet_box(p, q, pad, box).tolist() == [True, True, False, True, False]


def test_a_label_named_on_a_line_is_moved_off_every_line_and_stays_in_the_pane():
    # A 120 x 20 px label naming the middle of a horizontal line, with a slanted line above it.
    lines = [((50, 100), (350, 100), 4.0), ((50, 110), (350, 160), 4.0), ((200, 0), (200, 300), 2.0)]
    p, q, half = (np.array([seg[k] for seg in lines], float) for k in range(3))
    x, bottom = place_label((200, 100), (120, 20), (p, q, half), (400, 300), gap=4.0)
    box = (x - 60, bottom, x + 60, bottom + 20)
    assert box[0] >= 0 and box[2] <= 400 and box[1] >= 0 and box[3] <= 300
    assert not any(_touches(box, a, b, h + 4.0) for a, b, h in lines)
    assert np.hypot(x - 200, bottom - 100) < 150  # still near the point it names


def test_labels_placed_one_after_the_other_do_not_cover_each_other():
    no_lines = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    first = place_label((100, 100), (80, 20), no_lines, (400, 300))
    taken = [(first[0] - 40, first[1], first[0] + 40, first[1] + 20)]
    second = place_label((110, 100), (80, 20), no_lines, (400, 300), taken)
    a, b = taken[0], (second[0] - 40, second[1], second[0] + 40, second[1] + 20)
    assert a[2] <= b[0] or b[2] <= a[0] or a[3] <= b[1] or b[3] <= a[1]
