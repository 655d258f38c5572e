"""Our PNG writer, read back by Qt's own PNG decoder."""

import numpy as np
from PySide6.QtGui import QImage

from app.png import write_png


def test_png_reads_back_pixel_for_pixel(tmp_path):
    rng = np.random.default_rng(3)
    rgb = rng.integers(0, 256, size=(7, 11, 3)) / 255.0
    path = tmp_path / "img.png"
    write_png(path, rgb)
    image = QImage(str(path))
    assert (image.width(), image.height()) == (11, 7)
    for y, x in [(0, 0), (6, 10), (3, 5), (0, 10), (6, 0)]:
        c = image.pixelColor(x, y)
        assert (c.red(), c.green(), c.blue()) == tuple(np.round(rgb[y, x] * 255).astype(int))
