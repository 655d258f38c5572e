"""The image pane: what the observer sees, pixel by pixel.

Pixels are drawn as crisp squares (nearest neighbour) so a student can see
that the image is a grid of samples, scaled to fit the pane with its aspect
ratio kept.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QRectF, Qt
from PySide6.QtGui import QColor, QImage, QPainter
from PySide6.QtWidgets import QSizePolicy, QWidget


def to_qimage(rgb: np.ndarray) -> QImage:
    """An (H, W, 3) float image in [0, 1] as a QImage that owns its pixels."""
    data = np.ascontiguousarray(np.clip(rgb * 255.0 + 0.5, 0, 255).astype(np.uint8))
    h, w, _ = data.shape
    return QImage(data.data, w, h, 3 * w, QImage.Format.Format_RGB888).copy()


class ImageView(QWidget):
    """Shows an RGB image scaled to fit, with its pixels kept square and sharp."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self._image: QImage | None = None
        self.rgb: np.ndarray | None = None
        self.setMinimumSize(160, 120)
        self.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Expanding)

    def set_image(self, rgb: np.ndarray) -> None:
        """Show ``rgb``, an (H, W, 3) float array in [0, 1] (row 0 at the top)."""
        self.rgb = rgb
        self._image = to_qimage(rgb)
        self.update()

    def image_rect(self) -> QRectF:
        """Where the image is drawn inside the widget (aspect kept, centred)."""
        if self._image is None:
            return QRectF()
        scale = min(self.width() / self._image.width(), self.height() / self._image.height())
        w, h = self._image.width() * scale, self._image.height() * scale
        return QRectF((self.width() - w) / 2, (self.height() - h) / 2, w, h)

    def paintEvent(self, event):
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor("#15181f"))
        if self._image is not None:
            painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform, False)
            painter.drawImage(self.image_rect(), self._image)
        else:
            painter.setPen(QColor("#8a93a6"))
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, "rendering…")
        painter.end()
