"""A layout that puts its widgets side by side while the width holds them, and on more lines when not.

A row of fields (the eye's x, y and z) stays one line at the normal text size and takes two or three
at a large one in a narrow column, where a row of fixed order would widen the column past its dock
(and make it scroll sideways, cutting the last field).
"""

from __future__ import annotations

from PySide6.QtCore import QPoint, QRect, QSize, Qt
from PySide6.QtWidgets import QLayout, QWidget


class FlowLayout(QLayout):
    """Widgets left to right, as many to a line as fit; each as wide as its size hint, or as the line
    when narrower.  A line of several widgets shares the spare width among them, so a row that fits
    on one line looks as a box layout's would."""

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self._items = []
        self.setContentsMargins(0, 0, 0, 0)

    def addItem(self, item) -> None:  # noqa: N802 (Qt's name)
        self._items.append(item)

    def count(self) -> int:
        return len(self._items)

    def itemAt(self, index: int):  # noqa: N802
        return self._items[index] if 0 <= index < len(self._items) else None

    def takeAt(self, index: int):  # noqa: N802
        return self._items.pop(index) if 0 <= index < len(self._items) else None

    def expandingDirections(self) -> Qt.Orientation:  # noqa: N802
        return Qt.Orientation.Horizontal

    def hasHeightForWidth(self) -> bool:  # noqa: N802
        return True

    def heightForWidth(self, width: int) -> int:  # noqa: N802
        return self._place(QRect(0, 0, width, 0), move=False)

    def setGeometry(self, rect: QRect) -> None:  # noqa: N802
        super().setGeometry(rect)
        self._place(rect, move=True)

    def sizeHint(self) -> QSize:  # noqa: N802
        hints = [item.sizeHint() for item in self._items]
        width = sum(h.width() for h in hints) + self._gap() * max(0, len(hints) - 1)
        return QSize(width, max((h.height() for h in hints), default=0)) + self._margins()

    def minimumSize(self) -> QSize:  # noqa: N802
        least = [item.minimumSize() for item in self._items]
        return QSize(max((s.width() for s in least), default=0),
                     max((s.height() for s in least), default=0)) + self._margins()

    def _gap(self) -> int:
        return max(0, self.spacing())

    def _margins(self) -> QSize:
        m = self.contentsMargins()
        return QSize(m.left() + m.right(), m.top() + m.bottom())

    def _lines(self, width: int) -> list[list]:
        lines, line, used = [], [], 0
        for item in self._items:
            if item.isEmpty():
                continue
            wanted = item.sizeHint().width()
            if line and used + self._gap() + wanted > width:
                lines.append(line)
                line, used = [], 0
            used += (self._gap() if line else 0) + wanted
            line.append(item)
        return [*lines, line] if line else lines

    def _place(self, rect: QRect, move: bool) -> int:
        m = self.contentsMargins()
        area = rect.adjusted(m.left(), m.top(), -m.right(), -m.bottom())
        y = area.y()
        for line in self._lines(area.width()):
            height = max(item.sizeHint().height() for item in line)
            hinted = sum(item.sizeHint().width() for item in line)
            spare = area.width() - hinted - self._gap() * (len(line) - 1)
            x = area.x()
            for item in line:
                width = max(item.minimumSize().width(), item.sizeHint().width() + spare // len(line))
                width = min(width, area.right() + 1 - x)
                if move:
                    item.setGeometry(QRect(QPoint(x, y), QSize(width, height)))
                x += width + self._gap()
            y += height + self._gap()
        return y - self._gap() - area.y() + m.top() + m.bottom() if y > area.y() else m.top() + m.bottom()
