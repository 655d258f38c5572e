"""A figure drawn off the GUI thread: a drawing that raises is told in words instead of a picture, and
the next drawing is shown."""

import numpy as np

from views.images.agg_figure import Drawn
from views.images.figure_image import FigureImage


def test_a_drawing_that_raises_is_told_and_the_next_one_shown(qtbot):
    image = FigureImage()
    qtbot.addWidget(image)

    def broken():
        raise ValueError("no rows to plot")

    with qtbot.waitSignal(image.failed, timeout=10_000) as told:
        image.request(broken)
    assert told.args == ["ValueError: no rows to plot"] and image.shown is None
    red = np.zeros((6, 8, 4), np.uint8)
    red[..., 0] = red[..., 3] = 255
    with qtbot.waitSignal(image.drawn, timeout=10_000):
        image.request(lambda: Drawn(None, red))
    assert image.shown.rgba is red
