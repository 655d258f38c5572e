"""One line of text that shortens with "…" to fit, the whole text in its tooltip.

Status lines and hints change length with the text scale; wrapped, they would
take two or three lines at a lecture-hall size, which the images need more.
A progress bar's text does not wrap but is cut off at the top and the bottom
when it is too long, so :class:`ElidedProgressBar` shortens its text too.
"""

from __future__ import annotations

from PySide6.QtCore import QSize, Qt
from PySide6.QtWidgets import (
    QLabel,
    QProgressBar,
    QSizePolicy,
    QStyle,
    QStyleOptionProgressBar,
    QStylePainter,
)


class ElidedLabel(QLabel):
    """A QLabel for plain text kept to one line; ``text()`` is always the whole text."""

    def __init__(self, text: str = "", parent=None):
        super().__init__(parent)
        self._full = ""
        self.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Fixed)
        self.setTextFormat(Qt.TextFormat.PlainText)
        self.setText(text)

    def setText(self, text: str) -> None:
        self._full = text
        self.setToolTip(text)
        self._elide()

    def text(self) -> str:
        return self._full

    def minimumSizeHint(self) -> QSize:
        return QSize(0, self.fontMetrics().height())

    def sizeHint(self) -> QSize:
        return QSize(self.fontMetrics().horizontalAdvance(self._full), self.fontMetrics().height())

    def _elide(self) -> None:
        super().setText(self.fontMetrics().elidedText(self._full, Qt.TextElideMode.ElideRight,
                                                      max(self.width(), 1)))

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._elide()

    def changeEvent(self, event) -> None:
        super().changeEvent(event)
        if event.type() in (event.Type.FontChange, event.Type.StyleChange):
            self.updateGeometry()
            self._elide()


class ElidedProgressBar(QProgressBar):
    """A QProgressBar whose text is drawn shortened to fit; ``format()`` and ``text()`` stay whole."""

    def setFormat(self, text: str) -> None:
        super().setFormat(text)
        self.setToolTip(text.replace("%p%", "").replace("%p", "").rstrip(" …") or text)

    def shown_text(self) -> str:
        """The text as drawn: :meth:`text`, shortened with "…" to the bar's width."""
        room = self.width() - 2 * self.fontMetrics().averageCharWidth()
        return self.fontMetrics().elidedText(self.text(), Qt.TextElideMode.ElideRight, max(room, 1))

    def paintEvent(self, event) -> None:
        option = QStyleOptionProgressBar()
        self.initStyleOption(option)
        option.text = self.shown_text()
        QStylePainter(self).drawControl(QStyle.ControlElement.CE_ProgressBar, option)
