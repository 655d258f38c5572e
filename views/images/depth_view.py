"""The z-buffer shown as an image: nearer is darker, the far plane is white.

The z-buffer starts cleared to the far plane (white here); every fragment
that passes the depth test writes its distance, so surfaces appear as shades
of grey.  A scale under the image says which distance each grey stands for.
The greys are display levels already (an even ramp on screen), not light,
so they are not sRGB-encoded.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtGui import QColor, QLinearGradient, QPainter
from PySide6.QtWidgets import QHBoxLayout, QLabel, QVBoxLayout, QWidget

from views.images.image_view import DisplayImage, ImageView, display_image


def depth_to_grey(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """(H, W) camera distances to an (H, W, 3) grey image: near -> black, far or +inf -> white."""
    level = np.clip((np.asarray(depth) - near) / (far - near), 0.0, 1.0)
    return np.repeat(level[..., None], 3, axis=2)


class _GreyScale(QWidget):
    def paintEvent(self, event):
        painter = QPainter(self)
        gradient = QLinearGradient(0, 0, self.width(), 0)
        gradient.setColorAt(0.0, QColor("black"))
        gradient.setColorAt(1.0, QColor("white"))
        painter.fillRect(self.rect(), gradient)
        painter.end()


class DepthView(QWidget):
    """A z-buffer image with its grey scale in scene units."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.image = ImageView(placeholder="z-buffer")
        self.near_label, self.far_label = QLabel(), QLabel()
        scale = _GreyScale()
        scale.setFixedHeight(12)
        scale.setToolTip("Distance along the viewing axis: dark is near, white is the far plane")
        row = QHBoxLayout()
        row.addWidget(self.near_label)
        row.addWidget(scale, 1)
        row.addWidget(self.far_label)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.image, 1)
        layout.addLayout(row)

    def set_depth(self, depth: np.ndarray, near: float, far: float, grey: DisplayImage | None = None) -> None:
        """Show ``depth`` (H, W), distances along the viewing axis, +inf where nothing was drawn.

        ``grey``: its grey scale when already made (``display_image(depth_to_grey(...), linear=False)``).
        """
        self.depth, self.near, self.far = depth, near, far
        if grey is None:
            grey = display_image(depth_to_grey(depth, near, far), linear=False)
        self.image.set_image(grey)
        self.near_label.setText(f"near {near:g}")
        self.far_label.setText(f"far {far:g}")
