"""Placing a label clear of the lines around the point it names: checked by sampling the lines."""

import numpy as np

from views.scene3d.label_placement import (
    EDGE_PX,
    box_distance,
    in_pane,
    place_label,
    place_nearest,
    segments_meet_box,
    uncross,
)


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


_AROUND = ((0, 1), (1, 1), (-1, 1), (0, -1), (1, 0), (-1, 0), (1, -1), (-1, -1))  # above first


def _nearest_clear_spot(anchor, size, segments, pane, taken, gap):
    """Brute force, spot by spot: the first spot (nearest first, above first at each distance) whose
    box is in the pane, ``gap`` clear of the labels ``taken`` and of every line; its index too."""
    (ax, ay), (w, h), (p, q, half) = anchor, size, segments
    k = 0
    for reach in np.arange(0.0, np.hypot(*pane), max(h / 4, 2.0)):
        for dx, dy in _AROUND:
            x = ax + dx * (w / 2 + gap + reach) if dx else ax  # the box's side nearest the point
            bottom = ay + gap + reach if dy > 0 else ay - gap - h - reach if dy < 0 else ay - h / 2
            box = (x - w / 2, bottom, x + w / 2, bottom + h)
            in_pane = min(box[0], box[1]) >= 0 and box[2] <= pane[0] and box[3] <= pane[1]
            clear = in_pane and not any(
                box[0] < o[2] + gap and o[0] - gap < box[2] and box[1] < o[3] + gap and o[1] - gap < box[3]
                for o in taken) and not segments_meet_box(p, q, half + gap, box).any()
            if clear:
                return (x, bottom), k
            k += 1
    return None, k


def test_the_label_goes_to_the_nearest_clear_spot_however_far_it_is():
    """Among thick lines crowding the point, nearest first: what checking every spot one by one finds."""
    rng = np.random.default_rng(7)
    pane, size, gap = (400.0, 300.0), (90.0, 16.0), 4.0
    far = []
    for _ in range(12):
        n = int(rng.integers(5, 40))
        anchor = rng.uniform((100, 80), (300, 220))
        rows = anchor[1] + 14.0 * np.arange(-int(rng.integers(0, 14)), int(rng.integers(1, 14)))
        p = np.vstack([anchor + rng.normal(0, 60, (n, 2)), np.c_[np.zeros_like(rows), rows]])
        q = np.vstack([anchor + rng.normal(0, 60, (n, 2)), np.c_[np.full_like(rows, pane[0]), rows]])
        half = np.r_[rng.uniform(1, 6, n), np.ones_like(rows)]  # lines, then rows too close for a label
        taken = [tuple(np.r_[c, c + (60, 14)]) for c in rng.uniform((0, 0), (340, 286), (3, 2))]
        expected, index = _nearest_clear_spot(anchor, size, (p, q, half), pane, taken, gap)
        spot = place_label(anchor, size, (p, q, half), pane, taken, gap)
        if expected is None:
            assert spot is None
        else:
            assert spot is not None and np.allclose(spot, expected, rtol=0, atol=1e-9)
        far.append(index if expected is not None else None)
    assert max(k for k in far if k is not None) > 64 + 64  # some found only past the nearest spots ...
    assert None in far  # ... and one nowhere, every spot checked


def test_a_label_keeps_clear_of_the_panes_edges_and_one_with_no_clear_spot_is_moved_into_the_pane():
    # In the perspective lesson's short 3D pane at text x2, "A" was placed flush with the right edge and
    # its glyphs' outline, a pixel or two past the box measured, was cut.
    no_lines = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    pane, size = (400, 300), (20, 20)
    x, bottom = place_label((390, 150), size, no_lines, pane)  # above it, the box would end at 400
    assert x + size[0] / 2 <= pane[0] - EDGE_PX and x - size[0] / 2 >= EDGE_PX
    x, bottom = in_pane(395, 295, size, pane)  # centred above a point at the corner: moved in
    assert (x + 10, bottom + 20) == (pane[0] - EDGE_PX, pane[1] - EDGE_PX)


def test_a_long_label_with_no_room_beside_its_point_is_broken_into_lines_nearer_it_rather_than_carried_afar():
    # The apex of a V of thick lines (closed at its top) 20 px above the bottom of a 300 x 240 pane, as
    # the viewing pyramid seen from above: a 240 x 14 label finds no room beside the apex, only above
    # the V's top, carried across all of it; broken into three lines (100 x 42) it fits inside the V
    # where it is wide enough, 60 px nearer.
    lines = [((150, 20), (60, 190), 2.0), ((150, 20), (240, 190), 2.0), ((60, 190), (240, 190), 2.0)]
    segments = tuple(np.array([seg[k] for seg in lines], float) for k in range(3))
    one_line, broken = (240.0, 14.0), (100.0, 42.0)
    far = place_label((150, 20), one_line, segments, (300, 240))
    assert far is not None and far[1] > 190  # alone, it goes past the V's top
    k, (x, bottom) = place_nearest((150, 20), [one_line, broken], segments, (300, 240))
    assert k == 1
    assert box_distance((150, 20), x, bottom, broken) < box_distance((150, 20), *far, one_line) - 50
    box = (x - 50, bottom, x + 50, bottom + 42)
    assert not any(_touches(box, a, b, h + 4.0) for a, b, h in lines)


def test_a_label_that_fits_beside_its_point_on_one_line_keeps_one_line():
    no_lines = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    k, (x, bottom) = place_nearest((200, 100), [(120.0, 14.0), (60.0, 42.0)], no_lines, (400, 300))
    assert (k, x, bottom) == (0, 200, 104)  # centred just above the point, one line
    # With neither way beside the point, the nearer spot wins whichever way it is written.
    wall = (np.array([[0.0, 95.0], [0.0, 150.0]]), np.array([[400.0, 95.0], [400.0, 150.0]]),
            np.array([40.0, 2.0]))
    sizes = [(120.0, 14.0), (60.0, 42.0)]
    k, spot = place_nearest((200, 100), sizes, wall, (400, 300))
    other = place_label((200, 100), sizes[1 - k], wall, (400, 300))
    assert box_distance((200, 100), *spot, sizes[k]) <= box_distance((200, 100), *other, sizes[1 - k])


def _crossing(anchors, boxes) -> bool:
    """Brute force: whether the lines from two points to their boxes' centres meet, sampled."""
    (a, b), (c, d) = ((np.asarray(p, float), np.array([(x0 + x1) / 2, (y0 + y1) / 2]))
                      for p, (x0, y0, x1, y1) in zip(anchors, boxes, strict=True))
    t = np.linspace(0, 1, 401)[:, None]
    one, other = a * (1 - t) + b * t, c * (1 - t) + d * t
    return bool((np.hypot(*(one[:, None] - other[None]).T) < 0.5).any())


def test_two_labels_each_beside_the_others_point_are_swapped_so_their_leaders_no_longer_cross():
    # Points at (100, 100) and (300, 100) in a 400 x 300 pane; each one's 60 x 16 label was put by the
    # other's point, so the leaders cross.  Swapped, each label stands over its own point.
    no_lines = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    anchors = [(100.0, 100.0), (300.0, 100.0)]
    boxes = [(270.0, 130.0, 330.0, 146.0), (70.0, 120.0, 130.0, 136.0)]
    assert _crossing(anchors, boxes)
    swapped = uncross(anchors, boxes, [no_lines, no_lines], (400, 300))
    assert not _crossing(anchors, swapped)
    assert swapped == [(70.0, 120.0, 130.0, 136.0), (270.0, 130.0, 330.0, 146.0)]


def test_labels_are_not_swapped_where_one_would_not_fit_or_must_stay():
    no_lines = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
    anchors = [(100.0, 100.0), (300.0, 100.0)]
    boxes = [(270.0, 130.0, 330.0, 146.0), (70.0, 120.0, 130.0, 136.0)]
    # A line through the first label's place in the swap (y = 128, 4 px thick): it stays where it is.
    line = (np.array([[0.0, 128.0]]), np.array([[400.0, 128.0]]), np.array([2.0]))
    assert uncross(anchors, boxes, [no_lines, line], (400, 300)) == boxes
    assert uncross(anchors, boxes, [no_lines, None], (400, 300)) == boxes  # one placed nowhere clear
    assert uncross(anchors, boxes, [no_lines, no_lines], (400, 300), fixed=[(60, 110, 140, 150)]) == boxes
