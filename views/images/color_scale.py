"""A colour scale: which value each colour of a colour-mapped image stands for.

A difference image shows numbers as colours; without its scale the colours
say nothing.  The bar is drawn from the colour map itself (left: the lowest
value, right: the highest), with the values at its ends and their units.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from PySide6.QtCore import QRectF
from PySide6.QtGui import QPainter
from PySide6.QtWidgets import QHBoxLayout, QLabel, QVBoxLayout, QWidget

from core.heat_map import HeatMap, heat_map
from views.images.image_view import DisplayImage, display_image
from views.text.elided_label import ElidedLabel


@dataclass(frozen=True)
class HeatOver:
    """A heat map laid over an image, ready to paint, with its colour scale's strip and its numbers."""

    image: DisplayImage
    colorbar: DisplayImage
    heat: HeatMap


def heat_over(counts: np.ndarray, what: str, rgb: np.ndarray, note: str) -> HeatOver:
    """The heat map of ``counts`` (``what`` a pixel counts) laid over the linear ``rgb`` image, titled
    ``note`` (made on a worker: the window only paints it)."""
    heat = heat_map(counts, what)
    return HeatOver(display_image(heat.over(rgb), note), display_image(heat.colorbar()), heat)


class _Bar(QWidget):
    """The colour map's strip, stretched to the widget."""

    def __init__(self):
        super().__init__()
        self.strip: DisplayImage | None = None
        self.setFixedHeight(12)

    def paintEvent(self, event):
        if self.strip is None:
            return
        painter = QPainter(self)
        painter.drawImage(QRectF(self.rect()), self.strip.qimage)
        painter.end()


class ColorScale(QWidget):
    """A colour bar with the values at its two ends and a line naming the units.

    ``units_lines``: the units take at most that many lines, the last shortened with "…" if they
    go on (the whole in their tooltip), where an image above them needs the height; by default
    they take every line they need.
    """

    def __init__(self, tip: str, parent: QWidget | None = None, units_lines: int | None = None):
        super().__init__(parent)
        self.bar = _Bar()
        self.low, self.high = QLabel(), QLabel()
        for widget in (self.bar, self.low, self.high):
            widget.setToolTip(tip)
        if units_lines is None:
            self.units = QLabel()
            self.units.setWordWrap(True)
            self.units.setToolTip(tip)
        else:  # its tooltip is its whole text
            self.units = ElidedLabel()
            self.units.set_max_lines(units_lines)
        row = QHBoxLayout()
        row.setContentsMargins(0, 0, 0, 0)
        row.addWidget(self.low)
        row.addWidget(self.bar, 1)
        row.addWidget(self.high)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(2)
        layout.addLayout(row)
        layout.addWidget(self.units)

    def set_scale(self, strip: DisplayImage, low: str, high: str, units: str) -> None:
        """Show ``strip`` (the colour map, lowest value left) from ``low`` to ``high``, in ``units``."""
        self.bar.strip = strip
        self.low.setText(low)
        self.high.setText(high)
        self.units.setText(units)
        self.bar.update()
