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
    """Widgets stacked top to bottom in a scroll area as wide as they ask to be.

    The column takes at most ``share`` of its parent's width, unless its
    widgets cannot be narrower (a form then puts its labels above the fields).
    """

    def __init__(self, widgets=(), share: float = 0.3, parent: QWidget | None = None):
        super().__init__(parent)
        self.share = share
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
        wanted, least = self.inner.sizeHint().width(), self.inner.minimumSizeHint().width()
        if self.parentWidget() is not None:
            wanted = min(wanted, max(least, round(self.share * self.parentWidget().width())))
        width = wanted + self.verticalScrollBar().sizeHint().width()
        if width != self.width() or self.minimumWidth() != width:
            self.setFixedWidth(width)

    def eventFilter(self, watched, event) -> bool:
        # A new font (text scale), new contents or a new pane width change the width to take.
        if (watched is self.inner and event.type() in (QEvent.Type.LayoutRequest, QEvent.Type.FontChange,
                                                       QEvent.Type.StyleChange)
                or watched is self.parentWidget() and event.type() == QEvent.Type.Resize):
            self._fit()
        return False

    def event(self, event) -> bool:
        if event.type() == QEvent.Type.ParentChange and self.parentWidget() is not None:
            self.parentWidget().installEventFilter(self)  # its width sets the column's share
        return super().event(event)
