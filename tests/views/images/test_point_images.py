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
