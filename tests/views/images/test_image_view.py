"""The image pane marks a polygon's fragments with an outline that keeps their colours true."""

import numpy as np
from qt_fixtures import shown_widget

from core.srgb import to_srgb8
from views.images.image_view import ImageView, mask_outline


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
    view = shown_widget(qtbot, ImageView(), 400, 300)
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


def _shown(view, qtbot, rgb, size):
    view.resize(*size)
    view.set_image(rgb)
    view.show()
    qtbot.waitExposed(view)
    return view.grab().toImage()


def test_a_small_image_shows_its_pixel_grid_centres_and_a_polygons_edges(qtbot):
    """16 x 12 pixels at 640 x 480: each pixel is 40 px, its centre dotted white on a black image."""
    view = ImageView()
    qtbot.addWidget(view)
    black = np.zeros((12, 16, 3))
    picture = _shown(view, qtbot, black, (640, 480))
    assert view.grid_shown()
    centre, between = view.widget_pos(3, 7), view.widget_pos(3, 7) + type(view.widget_pos(0, 0))(10, 10)
    assert picture.pixelColor(centre.toPoint()).lightness() > 200  # the centre's dot
    assert picture.pixelColor(between.toPoint()).lightness() < 60  # the pixel's own colour around it
    # An edge from pixel (1, 1)'s centre to (14, 1)'s: drawn cyan halfway between two centres.
    view.set_edges(np.array([[1.5, 1.5], [14.5, 1.5], [8.0, 10.0]]))
    picture = view.grab().toImage()
    half = (view.widget_pos(7, 1) + view.widget_pos(8, 1)) / 2
    colour = picture.pixelColor(half.toPoint())
    assert colour.blue() > 200 and colour.green() > 200 and colour.red() < 80
    # A polygon still to come: the same edges dashed, gaps along the top edge where solid had none.
    a, b = view.widget_pos(2, 1), view.widget_pos(13, 1)

    def cyan_along(image):
        return [image.pixelColor(round(a.x() + (b.x() - a.x()) * s / 200), round(a.y())).blue() > 200
                for s in range(201)]

    assert all(cyan_along(picture))
    view.set_edges(np.array([[1.5, 1.5], [14.5, 1.5], [8.0, 10.0]]), coming=True)
    dashed = cyan_along(view.grab().toImage())
    assert any(dashed) and not all(dashed)


def test_a_large_image_shows_no_grid(qtbot):
    view = ImageView()
    qtbot.addWidget(view)
    picture = _shown(view, qtbot, np.zeros((240, 320, 3)), (640, 480))  # 2 px a pixel
    assert not view.grid_shown()
    row = [picture.pixelColor(view.widget_pos(x, 100).toPoint()).lightness() for x in range(100, 140)]
    assert max(row) < 30  # no centre dots


def test_the_picked_pixel_is_outlined_not_covered_by_the_highlights_colour(qtbot):
    # With a polygon's fragments outlined and the pixels too small for the grid, the picked pixel's
    # box took the outline's magenta as its fill and hid the pixel and its neighbours (presenting the
    # rasterization lesson on a 1280 x 720 projector).
    blue = (0.1, 0.2, 0.9)
    image = np.zeros((60, 80, 3))
    image[10:50, 10:70] = blue
    mask = np.zeros((60, 80), bool)
    mask[10:50, 10:70] = True
    view = ImageView()
    qtbot.addWidget(view)
    _shown(view, qtbot, image, (240, 180))  # 3 px a pixel: no grid
    assert not view.grid_shown()
    view.set_highlight(mask)
    view.set_picked((30, 30))
    shot = view.grab().toImage()
    centre = shot.pixelColor(view.widget_pos(30, 30).toPoint())
    assert (centre.red(), centre.green(), centre.blue()) == tuple(to_srgb8(np.array(blue)).tolist())


def test_the_rasterization_lessons_pixels_show_their_grid_at_11_px_each(qtbot):
    view = ImageView()
    qtbot.addWidget(view)
    _shown(view, qtbot, np.zeros((12, 16, 3)), (16 * 11 + 8, 12 * 11 + 8))
    assert view.grid_shown()
