"""The image pane marks a polygon's fragments with an outline that keeps their colours true."""

import numpy as np

from core.srgb import to_srgb8
from views.image_view import ImageView, mask_outline


def _perimeter_by_counting(mask):
    """Sides of masked pixels that face an unmasked pixel or the border, counted one by one."""
    h, w = mask.shape
    count = 0
    for y in range(h):
        for x in range(w):
            if mask[y, x]:
                for dx, dy in ((1, 0), (-1, 0), (0, 1), (0, -1)):
                    nx, ny = x + dx, y + dy
                    count += not (0 <= nx < w and 0 <= ny < h and mask[ny, nx])
    return count


def _unit_sides(segments):
    sides = []
    for x0, y0, x1, y1 in segments.astype(int).tolist():
        if y0 == y1:
            sides += [(x, y0, x + 1, y0) for x in range(x0, x1)]
        else:
            sides += [(x0, y, x0, y + 1) for y in range(y0, y1)]
    return sides


def test_the_outline_of_one_pixel_is_its_square_and_of_any_set_its_perimeter():
    single = np.zeros((3, 4), bool)
    single[1, 2] = True
    assert sorted(map(tuple, mask_outline(single).tolist())) == sorted(
        [(2, 1, 3, 1), (2, 2, 3, 2), (2, 1, 2, 2), (3, 1, 3, 2)])
    rng = np.random.default_rng(7)
    for _ in range(20):
        mask = rng.uniform(size=(9, 11)) < 0.4
        segments = mask_outline(mask)
        assert np.all((segments[:, 0] == segments[:, 2]) | (segments[:, 1] == segments[:, 3]))  # axis-aligned
        # Joined rows of sides: split back into unit sides, each side appears once, and all are there.
        sides = _unit_sides(segments)
        assert len(sides) == len(set(sides)) == _perimeter_by_counting(mask)


def test_a_straight_side_is_one_segment():
    mask = np.zeros((30, 40), bool)
    mask[5:25, 5:35] = True
    assert sorted(map(tuple, mask_outline(mask).tolist())) == sorted(
        [(5, 5, 35, 5), (5, 25, 35, 25), (5, 5, 5, 25), (35, 5, 35, 25)])


def test_pixels_inside_an_outlined_polygon_keep_their_true_colour(qtbot):
    view = ImageView()
    qtbot.addWidget(view)
    view.resize(400, 300)
    view.show()
    qtbot.waitExposed(view)
    blue = (0.1, 0.2, 0.9)
    image = np.zeros((30, 40, 3))
    image[5:25, 5:35] = blue
    mask = np.zeros((30, 40), bool)
    mask[5:25, 5:35] = True
    view.set_image(image)
    view.set_highlight(mask)
    shot = view.grab().toImage()
    rect = view.image_rect()
    centre = shot.pixelColor(int(rect.x() + rect.width() * 20 / 40), int(rect.y() + rect.height() * 15 / 30))
    assert (centre.red(), centre.green(), centre.blue()) == tuple(to_srgb8(np.array(blue)).tolist())
    edge = shot.pixelColor(int(rect.x() + rect.width() * 5 / 40), int(rect.y() + rect.height() * 15 / 30))
    assert (edge.red(), edge.green(), edge.blue()) != tuple(to_srgb8(np.array(blue)).tolist())
