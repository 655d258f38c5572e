"""A cover over a tab whose pictures are out of date: the scene was not rendered there, and it says why.

When a render is refused (over the memory budget) or fails, the tab would
otherwise go on showing the previous scene's image as if it were this one's.
:func:`cover` lays a translucent sheet with the reason over the whole tab;
:func:`uncover` takes it away when a new image is shown.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, Qt
from PySide6.QtWidgets import QLabel, QWidget

from views.text.text_scale import scaled_style


class StaleCover(QLabel):
    """The sheet itself: a child of the tab that follows its size and says why nothing is current."""

    def __init__(self, pane: QWidget):
        super().__init__(pane)
        self.setObjectName("stale cover")
        self.setWordWrap(True)
        self.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.setMargin(24)
        # The tab's own settings stay usable under the sheet: one of them may be what brings it back.
        self.setAttribute(Qt.WidgetAttribute.WA_TransparentForMouseEvents)
        scaled_style(self, "background: rgba(40, 40, 40, 200); color: white;", 14)
        self.setGeometry(pane.rect())
        pane.installEventFilter(self)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if event.type() == QEvent.Type.Resize:
            self.setGeometry(watched.rect())
        return False


def _found(pane: QWidget) -> StaleCover | None:
    return pane.findChild(StaleCover, options=Qt.FindChildOption.FindDirectChildrenOnly)


def cover(pane: QWidget, why: str) -> None:
    """Cover ``pane`` with ``why`` (its pictures are not of the current scene)."""
    sheet = _found(pane) or StaleCover(pane)
    sheet.setText(why)
    sheet.show()
    sheet.raise_()


def uncover(pane: QWidget) -> None:
    """Take the cover off ``pane``, if it has one."""
    sheet = _found(pane)
    if sheet is not None:
        sheet.hide()


def covered_with(pane: QWidget) -> str | None:
    """The reason ``pane`` is covered with, or None when its pictures are current."""
    sheet = _found(pane)
    return sheet.text() if sheet is not None and not sheet.isHidden() else None
