"""One line of text that shortens with "…" to fit, the whole text in its tooltip.

Status lines and hints change length with the text scale; wrapped, they would
take two or three lines at a lecture-hall size, which the images need more.
A label may be given more lines where there is room (:meth:`ElidedLabel.set_max_lines`).
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
    """A QLabel for plain text kept to :attr:`max_lines` lines (one by default), broken between words;
    ``text()`` is always the whole text."""

    def __init__(self, text: str = "", parent=None):
        super().__init__(parent)
        self._full = ""
        self.max_lines = 1
        self.setSizePolicy(QSizePolicy.Policy.Ignored, QSizePolicy.Policy.Fixed)
        self.setTextFormat(Qt.TextFormat.PlainText)
        self.setText(text)

    def setText(self, text: str) -> None:
        self._full = text
        self.setToolTip(text)
        self._elide()

    def text(self) -> str:
        return self._full

    def set_max_lines(self, lines: int) -> None:
        """Let the text take up to ``lines`` lines (at least one) before it ends in "…"."""
        lines = max(1, int(lines))
        if lines != self.max_lines:
            self.max_lines = lines
            self._elide()

    def minimumSizeHint(self) -> QSize:
        return QSize(0, self.fontMetrics().height())

    def sizeHint(self) -> QSize:
        return QSize(self.fontMetrics().horizontalAdvance(self._full), self.fontMetrics().height())

    def shown_lines(self) -> list[str]:
        """The text as drawn: broken between words into lines as wide as the label, at most
        :attr:`max_lines` of them, the last shortened with "…" if the text goes on."""
        metrics, room = self.fontMetrics(), max(self.width(), 1)
        lines, words = [], self._full.split(" ")
        while (len(lines) < self.max_lines - 1 and len(words) > 1
               and metrics.horizontalAdvance(" ".join(words)) > room):  # the rest needs another line
            take = 1
            while take < len(words) and metrics.horizontalAdvance(" ".join(words[:take + 1])) <= room:
                take += 1
            lines.append(" ".join(words[:take]))
            words = words[take:]
        return [*lines, metrics.elidedText(" ".join(words), Qt.TextElideMode.ElideRight, room)]

    def _elide(self) -> None:
        lines = self.shown_lines()
        super().setText("\n".join(lines))
        if self.max_lines > 1 or self.minimumHeight():  # lines added or taken away: as tall as they are
            height = (len(lines) - 1) * self.fontMetrics().lineSpacing() + self.fontMetrics().height()
            if (self.minimumHeight(), self.maximumHeight()) != (height, height):
                self.setFixedHeight(height)

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
