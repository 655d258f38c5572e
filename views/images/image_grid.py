"""Several images side by side, each with a title and a caption.

Used for the lecture's four-view figure (front, side and top orthographic
views next to the perspective view).
"""

from __future__ import annotations

import numpy as np
from PySide6.QtWidgets import QFrame, QGridLayout, QLabel, QVBoxLayout, QWidget

from views.images.image_view import DisplayImage, ImageView


class ImageGrid(QWidget):
    """A grid of titled :class:`ImageView` panes addressed by key."""

    def __init__(self, panes: list[tuple[str, str]], columns: int, parent: QWidget | None = None):
        """``panes`` are ``(key, title)`` pairs, laid out row by row."""
        super().__init__(parent)
        self.views: dict[str, ImageView] = {}
        self.titles: dict[str, str] = dict(panes)
        self.captions: dict[str, QLabel] = {}
        grid = QGridLayout(self)
        grid.setContentsMargins(6, 6, 6, 6)
        for i, (key, title) in enumerate(panes):
            box = QFrame()  # a word-wrapped title, not a group box's: narrow at large text
            box.setFrameShape(QFrame.Shape.StyledPanel)
            layout = QVBoxLayout(box)
            heading = QLabel(f"<b>{title}</b>")
            heading.setWordWrap(True)
            layout.addWidget(heading)
            self.views[key] = ImageView(placeholder="rendering…", pickable=False)  # no pixel readout
            self.captions[key] = QLabel()
            self.captions[key].setWordWrap(True)
            layout.addWidget(self.views[key], 1)
            layout.addWidget(self.captions[key])
            grid.addWidget(box, i // columns, i % columns)

    def set_image(self, key: str, image: np.ndarray | DisplayImage, caption: str = "") -> None:
        """Show ``image`` (see :meth:`ImageView.set_image`) in pane ``key``, with ``caption`` under it."""
        self.views[key].set_image(image)
        self.captions[key].setText(caption)
