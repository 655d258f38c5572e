"""A dialog that shows a long table (the keys and mouse gestures) whole on a large screen and
scrolled on a small one, its OK button always on screen.

The table has two columns: what to press and what it does.  The first never wraps; the second
wraps to the dialog's width, so a long line never needs a horizontal scroll (presenting at x2
on a 1280 x 720 screen, the keys' plain text in a fixed-pitch font was twice as wide as the
dialog could be).
"""

from __future__ import annotations

import html

from PySide6.QtGui import QFont, QFontMetrics
from PySide6.QtWidgets import QDialog, QDialogButtonBox, QTextBrowser, QVBoxLayout, QWidget

SCREEN_SHARE = 0.8
"""The most of its screen's available width and height the dialog takes (the frame and the
window behind it keep the rest)."""

Section = tuple[str, list[tuple[str, str]]]
"""A heading and its rows, each ``(what to press, what it does)``."""

_PADDING = 3
"""Pixels of space around a cell's text (the tables' ``cellpadding``)."""


def _html(sections: list[Section]) -> str:
    parts = []
    for heading, rows in sections:
        parts.append(f"<p><b>{html.escape(heading)}</b></p><table cellspacing='0' cellpadding='{_PADDING}'>")
        parts += [f"<tr><td nowrap>{html.escape(keys)}</td><td>{html.escape(what)}</td></tr>"
                  for keys, what in rows]
        parts.append("</table>")
    return "".join(parts)


def _unwrapped_width(view: QWidget, sections: list[Section]) -> int:
    """The width ``sections`` take with nothing wrapped, in ``view``'s font: the widest heading (bold) or
    table (each section's widest first column, then its widest second one, each cell padded on both
    sides, and a pixel a column for the rounding of its text's width to whole pixels; the tables
    have no border, spacing or margin)."""
    metrics = view.fontMetrics()
    bold = QFont(view.font())
    bold.setBold(True)
    widths = [QFontMetrics(bold).horizontalAdvance(heading) for heading, _ in sections]
    for _, rows in sections:
        if rows:
            widths.append(max(metrics.horizontalAdvance(keys) for keys, _ in rows)
                          + max(metrics.horizontalAdvance(what) for _, what in rows) + 2 * (2 * _PADDING + 1))
    return max(widths, default=0)


def table_dialog(parent: QWidget, title: str, sections: list[Section]) -> QDialog:
    """A modeless dialog titled ``title`` showing ``sections`` in the window's text size (large
    while presenting): as wide as its longest row where the screen allows, else its second column
    wrapped; scrolled if it is taller than :data:`SCREEN_SHARE` of the screen."""
    dialog = QDialog(parent)
    dialog.setWindowTitle(title)
    view = QTextBrowser()
    view.setFont(dialog.font())
    view.setHtml(_html(sections))
    buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok)
    buttons.accepted.connect(dialog.accept)
    layout = QVBoxLayout(dialog)
    layout.addWidget(view, 1)
    layout.addWidget(buttons)
    available = parent.screen().availableGeometry()
    frame = 2 * view.frameWidth()
    scrollbar = view.verticalScrollBar().sizeHint().width()
    document = view.document()
    width = min(_unwrapped_width(view, sections) + round(2 * document.documentMargin()) + frame + scrollbar,
                round(available.width() * SCREEN_SHARE))
    document.setTextWidth(width - frame - scrollbar)
    height = min(round(document.size().height()) + frame,
                 round(available.height() * SCREEN_SHARE) - buttons.sizeHint().height())
    view.setMinimumSize(width, height)
    return dialog
