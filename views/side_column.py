"""A column of settings beside an image: as wide as its contents, scrolling when too tall.

A panel whose image sits beside its settings (rather than under them) keeps
the image as tall as the pane allows; the settings take only the width they
need at the current text size, and scroll up and down when the pane is
shorter than they are, so they never make the window taller than its screen.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, Qt
from PySide6.QtWidgets import QFrame, QScrollArea, QSizePolicy, QVBoxLayout, QWidget


class SideColumn(QScrollArea):
    """Widgets stacked top to bottom in a scroll area exactly as wide as the widest of them."""

    def __init__(self, widgets=(), parent: QWidget | None = None):
        super().__init__(parent)
        self.inner = QWidget()
        self.column = QVBoxLayout(self.inner)
        self.column.setContentsMargins(0, 0, 4, 0)
        for w in widgets:
            self.column.addWidget(w)
        self.column.addStretch(1)
        self.setWidget(self.inner)
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.Shape.NoFrame)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self.setSizePolicy(QSizePolicy.Policy.Fixed, QSizePolicy.Policy.Expanding)
        self.inner.installEventFilter(self)
        self._fit()

    def _fit(self) -> None:
        scrollbar = self.verticalScrollBar().sizeHint().width()
        self.setFixedWidth(self.inner.sizeHint().width() + scrollbar)

    def eventFilter(self, watched, event) -> bool:
        # A new font (text scale) or new contents change the width the column needs.
        if watched is self.inner and event.type() in (QEvent.Type.LayoutRequest, QEvent.Type.FontChange,
                                                      QEvent.Type.StyleChange):
            self._fit()
        return False
