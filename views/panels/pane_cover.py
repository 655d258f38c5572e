"""Covers over panes that must not be read now, each saying why.

Two kinds (:data:`KINDS`):

- ``"stale"``: a tab whose pictures are out of date.  When a render is refused
  (over the memory budget) or fails, the tab would otherwise go on showing the
  previous scene's image as if it were this one's; a translucent sheet with the
  reason lies over the whole tab, and the tab's settings stay usable under it
  (one of them may be what brings it back).
- ``"answer"``: a readout that would give away the answer to the exercise being
  asked (:func:`core.lessons.exercises.withheld`); an opaque sheet hides it until
  the exercise is answered or revealed, and the readout is disabled meanwhile, so
  that Tab does not walk into it unseen (nor a screen reader read it).

:func:`cover` lays a sheet over a pane, :func:`uncover` takes it away, :func:`covered_with`
says why a pane is covered.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, Qt
from PySide6.QtWidgets import QLabel, QWidget

from views.text.text_scale import scaled_style

STALE, ANSWER = "stale", "answer"
KINDS = (STALE, ANSWER)
_LOOK = {STALE: ("background: rgba(40, 40, 40, 200); color: white;", 14),
         ANSWER: ("background: rgb(58, 62, 70); color: white;", 10)}


class PaneCover(QLabel):
    """The sheet itself: a child of the pane that follows its size and says why it is covered."""

    def __init__(self, pane: QWidget, kind: str):
        super().__init__(pane)
        self.setObjectName(f"{kind} cover")
        self.setWordWrap(True)
        self.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.setMargin(24 if kind == STALE else 0)  # an answer's may cover one line of text
        # Under a stale cover the tab's own settings stay usable; an answer's is not to be read or used.
        self.setAttribute(Qt.WidgetAttribute.WA_TransparentForMouseEvents, kind == STALE)
        scaled_style(self, *_LOOK[kind])
        self.setGeometry(pane.rect())
        pane.installEventFilter(self)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if event.type() == QEvent.Type.Resize:
            self.setGeometry(watched.rect())
        return False


def _found(pane: QWidget, kind: str) -> PaneCover | None:
    return pane.findChild(PaneCover, f"{kind} cover", Qt.FindChildOption.FindDirectChildrenOnly)


def cover(pane: QWidget, why: str, kind: str = STALE) -> None:
    """Cover ``pane`` with ``why`` (for ``"stale"``: its pictures are not of the current scene)."""
    sheet = _found(pane, kind) or PaneCover(pane, kind)
    sheet.setText(why)
    sheet.show()
    sheet.raise_()
    if kind == ANSWER:
        pane.setEnabled(False)


def uncover(pane: QWidget, kind: str = STALE) -> None:
    """Take ``pane``'s cover of ``kind`` off, if it has one."""
    sheet = _found(pane, kind)
    if sheet is not None and not sheet.isHidden():
        sheet.hide()
        if kind == ANSWER:
            pane.setEnabled(True)


def covered_with(pane: QWidget, kind: str = STALE) -> str | None:
    """The reason ``pane`` is covered with (a cover of ``kind``), or None when it is not."""
    sheet = _found(pane, kind)
    return sheet.text() if sheet is not None and not sheet.isHidden() else None
