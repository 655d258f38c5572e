"""Placing a label beside the point it names, clear of the lines drawn around it.

A label in the 3D pane names a point of the drawing (a plane's edge, the
eye); centred just above that point it often sits on the very lines it
names, the more so when presentation mode thickens the lines and enlarges
the text.  :func:`place_label` tries spots around the point, nearest first
(above, beside, below, then ever farther), and takes the first where the
text's box stays inside the pane and clear of every line (each as thick as
it is drawn) and of the labels placed before it.  It is plain 2D geometry
in pixels, free of VTK.  A label with no room beside its point is tried
broken into lines too (:func:`broken`), and goes wherever is nearer
(:func:`place_nearest`); once all are placed, two whose leader lines cross
change places where each fits (:func:`uncross`).
"""

from __future__ import annotations

import itertools

import numpy as np

GAP_PX = 4.0
"""Room between a label's box and the lines around it, pixels at text scale 1."""
EDGE_PX = 2.0
"""Room between a label's box and the pane's edges, pixels: the glyphs' outline reaches a pixel or two
past the box measured (flush with the edge of a short pane at text x2, "A" lost its right leg)."""
_DIRECTIONS = ((0, 1), (1, 1), (-1, 1), (0, -1), (1, 0), (-1, 0), (1, -1), (-1, -1))
"""Where a label may go from the point it names, (right, up), above first."""
FIRST_SPOTS = 64
"""How many of the nearest spots :func:`place_label` checks against the lines first; then four times
as many of the next, and so on (checking every spot of the pane at once took 10-40 ms of the GUI
thread per labelled overlay, before each draw of the 3D pane)."""


def segments_meet_box(p, q, pad, box) -> np.ndarray:
    """For each segment ``p[i]``-``q[i]`` (as thick as ``2 pad[i]``), whether it meets ``box``
    ``(x0, y0, x1, y1)``: the segment clipped to the box grown by ``pad`` (Liang–Barsky).

    ``box`` may be many boxes, shape (M, 4): the answer is then (M, N), a row per box.
    """
    p, q = np.asarray(p, float).reshape(-1, 2), np.asarray(q, float).reshape(-1, 2)
    pad = np.asarray(pad, float)[:, None]
    box = np.asarray(box, float)
    low = box[..., None, :2] - pad  # (..., N, 2)
    high = box[..., None, 2:] + pad
    d = q - p
    flat = np.abs(d) < 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        a, b = (low - p) / d, (high - p) / d
    t0 = np.where(flat, 0.0, np.minimum(a, b))
    t1 = np.where(flat, 1.0, np.maximum(a, b))
    inside_flat = ~flat | ((low <= p) & (p <= high))
    return (np.maximum(t0.max(axis=-1), 0.0) <= np.minimum(t1.min(axis=-1), 1.0)) & inside_flat.all(axis=-1)


def place_label(anchor, size, segments, pane, taken=(), gap: float = GAP_PX,
                within: float = np.inf) -> tuple[float, float] | None:
    """Where to put the bottom centre of a ``size`` (w, h) label naming the point ``anchor``.

    ``segments`` is ``(p, q, half_width)``: arrays (n, 2), (n, 2), (n,) of the lines
    drawn, ``pane`` the pane's (width, height) and ``taken`` the boxes
    ``(x0, y0, x1, y1)`` of labels already placed, all in pixels with y up.  The
    nearest clear spot wins: first beside the point, then ever farther (a leader line
    then joins them), :data:`EDGE_PX` inside the pane; None if no spot is clear, or none whose box
    is less than ``within`` from the point.
    """
    w, h = size
    ax, ay = anchor
    step = max(h / 4, 2.0)
    farthest = min(np.hypot(*pane), within - gap)
    reach = np.repeat(np.arange(0.0, farthest, step), len(_DIRECTIONS))  # nearest first
    dx, dy = np.tile(np.array(_DIRECTIONS, float), (len(reach) // len(_DIRECTIONS), 1)).T
    # The box's side nearest the point is ``gap`` + ``reach`` away from it.
    cx = np.where(dx != 0, ax + dx * (w / 2 + gap + reach), ax)
    bottom = np.where(dy > 0, ay + gap + reach, np.where(dy < 0, ay - gap - h - reach, ay - h / 2))
    boxes = np.stack([cx - w / 2, bottom, cx + w / 2, bottom + h], axis=1)
    ok = _in_pane_and_apart(boxes, pane, taken, gap)
    p, q, half = segments
    start, size = 0, FIRST_SPOTS
    while start < len(boxes):  # the nearest spots first: most labels find one among them
        spots = start + np.flatnonzero(ok[start:start + size])
        if len(p) and len(spots):
            spots = spots[~segments_meet_box(p, q, np.asarray(half) + gap, boxes[spots]).any(axis=1)]
        if len(spots):
            return float(cx[spots[0]]), float(bottom[spots[0]])
        start, size = start + size, 4 * size
    return None


def _in_pane_and_apart(boxes, pane, taken, gap) -> np.ndarray:
    """Which of the boxes (n, 4) lie :data:`EDGE_PX` inside the pane, ``gap`` clear of the boxes ``taken``."""
    ok = ((boxes[:, 0] >= EDGE_PX) & (boxes[:, 1] >= EDGE_PX) & (boxes[:, 2] <= pane[0] - EDGE_PX)
          & (boxes[:, 3] <= pane[1] - EDGE_PX))
    for other in taken:
        ok &= ~((boxes[:, 0] < other[2] + gap) & (other[0] - gap < boxes[:, 2])
                & (boxes[:, 1] < other[3] + gap) & (other[1] - gap < boxes[:, 3]))
    return ok


def box_clear(box, segments, pane, taken=(), gap: float = GAP_PX) -> bool:
    """Whether a label's ``box`` (x0, y0, x1, y1) is where :func:`place_label` could put it: in the
    pane, clear of the lines ``segments`` and of the boxes ``taken``."""
    boxes = np.asarray(box, float).reshape(1, 4)
    p, q, half = segments
    return bool(_in_pane_and_apart(boxes, pane, taken, gap)[0]
                and not (len(p) and segments_meet_box(p, q, np.asarray(half) + gap, boxes).any()))


def _cross(a, b, c, d) -> bool:
    """Whether the segments ``a``-``b`` and ``c``-``d`` cross (the ends of each either side of the other)."""
    def side(p, q, r):
        return np.sign((q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]))
    return side(a, b, c) * side(a, b, d) < 0 and side(c, d, a) * side(c, d, b) < 0


def _centre(box) -> tuple[float, float]:
    return (box[0] + box[2]) / 2, (box[1] + box[3]) / 2


def _centred(box, centre) -> tuple:
    """``box`` moved so that its centre is ``centre``."""
    w, h = box[2] - box[0], box[3] - box[1]
    return centre[0] - w / 2, centre[1] - h / 2, centre[0] + w / 2, centre[1] + h / 2


def uncross(anchors, boxes, segments, pane, fixed=(), gap: float = GAP_PX) -> list:
    """The labels' ``boxes`` (x0, y0, x1, y1), two swapped wherever the lines from their points
    ``anchors`` to their centres cross and each fits in the other's place (:func:`box_clear` of its
    own lines ``segments``, None for a label that must stay; clear of the other labels and of the
    boxes ``fixed``).

    Placed one after the other, nearest first, labels in a crowded pane can end up each nearer the
    other's point, their leader lines crossing (presenting at x2 on 1280x720, the observer lesson's
    five objects).  Swapping two such labels uncrosses their leaders and shortens them both together
    (two crossing segments are longer than the two that join their ends the other way).
    """
    boxes = [tuple(box) for box in boxes]
    for _ in range(len(boxes)):  # a swap may make another crossing; each pass leaves the leaders shorter
        swapped = False
        for i, j in itertools.combinations(range(len(boxes)), 2):
            if segments[i] is None or segments[j] is None:
                continue
            if not _cross(anchors[i], _centre(boxes[i]), anchors[j], _centre(boxes[j])):
                continue
            box_i, box_j = _centred(boxes[i], _centre(boxes[j])), _centred(boxes[j], _centre(boxes[i]))
            others = [box for k, box in enumerate(boxes) if k not in (i, j)] + list(fixed)
            if (box_clear(box_i, segments[i], pane, others + [box_j], gap)
                    and box_clear(box_j, segments[j], pane, others, gap)):
                boxes[i], boxes[j], swapped = box_i, box_j, True
        if not swapped:
            break
    return boxes


def box_distance(point, cx: float, bottom: float, size) -> float:
    """How far ``point`` lies from the box of a ``size`` (w, h) label whose bottom centre is
    ``(cx, bottom)`` (0 inside it), pixels."""
    (w, h), (x, y) = size, point
    return float(np.hypot(max(cx - w / 2 - x, 0.0, x - cx - w / 2), max(bottom - y, 0.0, y - bottom - h)))


def place_nearest(anchor, sizes, segments, pane, taken=(), gap: float = GAP_PX) -> tuple[int, tuple] | None:
    """:func:`place_label` for a label that can be written in several ways, ``sizes`` (w, h) in order of
    preference (one line, then :func:`broken`): ``(k, spot)``, way ``k`` and where it goes.

    The first way that finds a spot beside the point (no farther from it than a leader line's
    shortest, ``3 gap``) is taken; failing that, the way whose spot lies nearest the point.  A long
    label on one line, with no room beside its point, was otherwise carried across the whole drawing
    to the first room there was: in the observer lesson's overview the near plane's label went from
    the apex of the viewing pyramid to beyond the far plane, and the far plane's down to the apex,
    each on a long leader line beside the other's point.  None if no way finds a spot.

    Each way after the first is looked for only as far as the nearest spot found yet: placing the
    observer lesson's labels, the view turning 3 degrees a frame at 1280x720, took a median 10-13 ms
    a frame, as with one way (11-14); searching every way in full, 14-15.
    """
    nearest = None
    for k, size in enumerate(sizes):
        # (a box ``reach`` away on the search's rays is at least ``gap + reach`` from the point)
        within = np.inf if nearest is None else nearest[0]
        spot = place_label(anchor, size, segments, pane, taken, gap, within)
        if spot is None:
            continue
        away = box_distance(anchor, *spot, size)
        if away <= 3 * gap:
            return k, spot
        if nearest is None or away < nearest[0]:
            nearest = (away, k, spot)
    return None if nearest is None else nearest[1:]


def in_pane(cx: float, bottom: float, size, pane) -> tuple[float, float]:
    """The bottom centre ``(cx, bottom)`` of a ``size`` (w, h) label moved the least to put it whole in
    ``pane`` (w, h), :data:`EDGE_PX` inside, pixels with y up: where a label of a point in view that
    found no clear spot goes (centred above its point, in a short pane at text x2 it was cut)."""
    (w, h), (width, height), e = size, pane, EDGE_PX
    return (min(max(cx, w / 2 + e), max(width - w / 2 - e, w / 2)),
            min(max(bottom, e), max(height - h - e, 0.0)))


def broken(text: str) -> str:
    """``text`` on several lines, broken after its commas and before its brackets: a narrower label."""
    return text.replace(", ", ",\n").replace(" (", "\n(")
