"""Widgets that ask, as their least size, for the room to show their first lines or rows whole.

A pane shared by a splitter or a box layout shrinks its parts down to their least sizes.  A plain
word-wrapped label or table asks for almost nothing, so at a large text size on a small screen a
caption kept two of its three lines and a table half of its first row.  These ask for what a reader
needs: all the label's lines at its width, and a table's header and its first few rows (or all of
them, when fewer), with the sideways scroll bar when the columns are wider than the view.
"""

from __future__ import annotations

from PySide6.QtCore import QSize
from PySide6.QtWidgets import QLabel, QTableWidget

#: How many of a table's rows its least height shows whole.
ROWS_SHOWN = 3


class WholeLinesLabel(QLabel):
    """A word-wrapped label whose least height shows every line at its width."""

    def __init__(self, text: str = "", parent=None):
        super().__init__(text, parent)
        self.setWordWrap(True)
        self._width = 0

    def minimumSizeHint(self) -> QSize:  # noqa: N802 (Qt's name)
        least = super().minimumSizeHint()
        if self.width() <= 0 or not self.text():
            return least
        return QSize(least.width(), max(least.height(), self.heightForWidth(self.width())))

    def setText(self, text: str) -> None:  # noqa: N802
        super().setText(text)
        self.updateGeometry()

    def resizeEvent(self, event) -> None:  # noqa: N802
        super().resizeEvent(event)
        if event.size().width() != self._width:  # other lines at another width
            self._width = event.size().width()
            self.updateGeometry()


class WholeRowsTable(QTableWidget):
    """A table whose least height shows its header and its first :data:`ROWS_SHOWN` rows whole."""

    def __init__(self, rows: int, columns: int, parent=None):
        super().__init__(rows, columns, parent)
        for header in (self.horizontalHeader(), self.verticalHeader()):  # rows and columns sized to text
            header.sectionResized.connect(lambda *_: self.updateGeometry())

    def minimumSizeHint(self) -> QSize:  # noqa: N802
        least = super().minimumSizeHint()
        rows = sum(self.rowHeight(r) for r in range(min(self.rowCount(), ROWS_SHOWN)))
        header = self.horizontalHeader().sizeHint().height() if self.horizontalHeader().isVisible() else 0
        sideways = self.horizontalScrollBar().sizeHint().height() if self._wider_than_view() else 0
        return QSize(least.width(), max(least.height(), 2 * self.frameWidth() + header + rows + sideways))

    def _wider_than_view(self) -> bool:
        header = self.horizontalHeader()
        return header.length() > self.width() - 2 * self.frameWidth()

    def resizeEvent(self, event) -> None:  # noqa: N802
        super().resizeEvent(event)
        if event.size().width() != event.oldSize().width():  # the columns may now fit, or not
            self.updateGeometry()
