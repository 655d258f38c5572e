"""A swept setting's images beside the reference and the FLIP map: every title reads whole, at 1280 x 720
and presenting at x2 at 1920 x 1080."""

import itertools

import numpy as np
import pytest

from core.accuracy.sweep import Point, Row
from views.images.point_images import point_images_drawing


def _point(samples: bool) -> tuple[Point, object]:
    rng = np.random.default_rng(0)
    row = Row("adaptive" if samples else "spp", "0.4" if samples else "1x1", "raytrace", 0.0421, 0.0, 0.0082,
              0.0, 0.0, 0.0082, 3.25 if samples else 1.0, None, "reference")
    color = rng.random((48, 64, 3))
    point = Point(0, row, color, rng.random((48, 64)).astype(np.float32),
                  rng.integers(1, 16, (48, 64)) if samples else None)

    class Reference:
        spp = 16

    Reference.color = color
    return point, Reference


@pytest.mark.parametrize("samples", [False, True])
@pytest.mark.parametrize("size", [(350, 290, 100.0), (506, 435, 200.0)])  # 1280 x 720; x2 at 1920 x 1080
def test_every_title_shows_whole_and_apart(size, samples):
    point, reference = _point(samples)
    drawn = point_images_drawing(point, reference, *size, dark=True)()
    figure = drawn.figure
    renderer = figure.canvas.get_renderer()
    edge = figure.bbox
    titles = [ax.title for ax in figure.axes if ax.get_title()]
    assert len(titles) == (4 if samples else 3)
    assert any("FLIP against reference" in t.get_text().replace("\n", " ") for t in titles)  # says the same
    boxes = [t.get_window_extent(renderer) for t in titles]
    for box in boxes:
        assert edge.x0 - 1 <= box.x0 and box.x1 <= edge.x1 + 1
        assert edge.y0 - 1 <= box.y0 and box.y1 <= edge.y1 + 1
    for a, b in itertools.combinations(boxes, 2):
        assert not (a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1)
    words = " ".join(t.get_text() for t in titles).split()
    assert ("adaptive" if samples else "reference") in words  # broken between words, never inside one
    bars = [ax for ax in figure.axes if not ax.get_title()]
    assert len(bars) == (2 if samples else 1)
    for bar in bars:  # each scale's two ends, whose labels cannot overlap ("5", "10", "15" did)
        assert len(bar.get_yticks()) == 2


@pytest.mark.parametrize("size", [(350, 290, 100.0), (506, 435, 200.0)])  # 1280 x 720; x2 at 1920 x 1080
def test_the_error_map_alone_on_its_row_is_drawn_as_large_as_the_images_above_under_a_short_title(size):
    point, reference = _point(samples=False)
    figure = point_images_drawing(point, reference, *size, dark=True)().figure
    renderer = figure.canvas.get_renderer()
    images = [ax for ax in figure.axes if ax.get_title()]
    error = images[2]
    assert error.get_title().startswith("FLIP")
    shown = [ax.get_window_extent(renderer) for ax in images]  # each image's drawn box (aspect kept)
    assert shown[2].width >= 0.9 * min(box.width for box in shown[:2])  # a third as large before
    assert shown[2].height >= 0.9 * min(box.height for box in shown[:2])
    assert len(error.get_title().splitlines()) <= 2  # "FLIP against reference" / "mean 0.0082"
    title = error.title.get_window_extent(renderer)
    assert not any(title.overlaps(box) for box in shown[:2])  # clear of the images above


@pytest.mark.parametrize("samples", [False, True])
def test_a_wide_figure_draws_the_images_in_one_row_larger_than_two_rows_would(samples):
    # The chosen point's own page presenting at x2 on 1920 x 1080: about 1250 x 560 pixels at 200 dpi.
    point, reference = _point(samples)
    figure = point_images_drawing(point, reference, 1250, 560, 200.0, dark=True)().figure
    renderer = figure.canvas.get_renderer()
    shown = [ax.get_window_extent(renderer) for ax in figure.axes if ax.get_title()]
    assert len({round(box.y0) for box in shown}) == 1  # one row
    # Two rows of 560 pixels leave an image less than 280 - 2 title lines (~100 px) tall, whatever its width.
    assert min(box.height for box in shown) > 180
    titles = [ax.title.get_window_extent(renderer) for ax in figure.axes if ax.get_title()]
    for a, b in itertools.combinations(titles, 2):
        assert not a.overlaps(b)
