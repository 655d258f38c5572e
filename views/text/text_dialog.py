"""A dialog that shows a long text (the keys and mouse gestures) whole on a large screen and
scrolled on a small one, its OK button always on screen."""

from __future__ import annotations

from PySide6.QtGui import QFontDatabase
from PySide6.QtWidgets import QDialog, QDialogButtonBox, QPlainTextEdit, QVBoxLayout, QWidget

SCREEN_SHARE = 0.8
"""The most of its screen's available width and height the dialog takes (the frame and the
window behind it keep the rest)."""


def text_dialog(parent: QWidget, title: str, text: str) -> QDialog:
    """A modeless dialog titled ``title`` showing ``text`` in a fixed-pitch font (columns made
    with spaces line up), scrolled if it is longer than :data:`SCREEN_SHARE` of the screen."""
    dialog = QDialog(parent)
    dialog.setWindowTitle(title)
    view = QPlainTextEdit(text)
    view.setReadOnly(True)
    view.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
    font = QFontDatabase.systemFont(QFontDatabase.SystemFont.FixedFont)
    font.setPointSizeF(dialog.font().pointSizeF())  # the window's text size (large while presenting)
    view.setFont(font)
    buttons = QDialogButtonBox(QDialogButtonBox.StandardButton.Ok)
    buttons.accepted.connect(dialog.accept)
    layout = QVBoxLayout(dialog)
    layout.addWidget(view, 1)
    layout.addWidget(buttons)
    lines = text.splitlines() or [""]
    metrics = view.fontMetrics()
    frame = 2 * view.frameWidth() + 2 * round(view.document().documentMargin())
    scrollbar = view.verticalScrollBar().sizeHint().width()
    available = parent.screen().availableGeometry()
    width = max(metrics.horizontalAdvance(line) for line in lines) + frame + scrollbar
    height = len(lines) * metrics.lineSpacing() + frame
    view.setMinimumSize(min(width, round(available.width() * SCREEN_SHARE)),
                        min(height, round(available.height() * SCREEN_SHARE) - buttons.sizeHint().height()))
    return dialog
