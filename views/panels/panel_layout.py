"""How an image tab is laid out: its pictures (with their settings beside them) on top, the
picked pixel's details below, in a splitter the user can drag.

The pictures get three fifths of the height to begin with, so they stay the largest thing in
the tab, and the details' tables still show several rows.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QSplitter, QVBoxLayout, QWidget


def pictures_over_details(panel: QWidget, top: QWidget, details: QWidget) -> QSplitter:
    """Lay ``panel`` out as ``top`` above ``details``; returns the splitter between them."""
    split = QSplitter(Qt.Orientation.Vertical)
    split.addWidget(top)
    split.addWidget(details)
    split.setStretchFactor(0, 3)
    split.setStretchFactor(1, 2)
    split.setSizes([600, 400])
    layout = QVBoxLayout(panel)
    layout.setContentsMargins(6, 6, 6, 6)
    layout.addWidget(split, 1)
    return split
