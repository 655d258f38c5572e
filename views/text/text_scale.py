"""The window's text scale (presentation mode's ×1.5, ×2), for text whose size is set apart.

Presentation mode scales the text by the application's font
(:mod:`views.presentation`), which every widget follows, also one made
later, unless it sets a ``font-size`` of its own; the normal size (scale 1,
the size Ctrl++ and Ctrl+- change) is kept beside it, as the application's
property :data:`NORMAL_TEXT_PT`.  :func:`text_scale` tells a widget how many
times the normal size its text is now; :func:`scaled_style` keeps a widget's
own style sheet, with its own size, that many times larger as the scale
changes (a heading stays 1.5 times the text around it).
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, QSize
from PySide6.QtWidgets import QApplication, QWidget

NORMAL_TEXT_PT = "normal_text_pt"
"""The application's property holding the normal text size in points; unset, the application's
font is the normal size."""


def normal_text_pt() -> float:
    """The normal text size (at scale 1), in points."""
    kept = QApplication.instance().property(NORMAL_TEXT_PT)
    return float(kept) if kept else (QApplication.font().pointSizeF() or 10.0)


def text_scale(widget: QWidget) -> float:
    """How many times the normal text size ``widget``'s text is now."""
    return widget.font().pointSizeF() / normal_text_pt()


class _ScaledStyle(QObject):
    """Watches the widget (a new style, parent, or its showing) and the widget around it (a new
    font: the text scale reaches it as one, while the widget's own size stays as its sheet says)."""

    def __init__(self, widget: QWidget, style: str, size_pt: float):
        super().__init__(widget)
        self.widget, self.style, self.size_pt = widget, style, size_pt
        self.scale = None
        self.around = None
        widget.installEventFilter(self)
        self.apply()

    def apply(self) -> None:
        around = self.widget.parentWidget()
        if around is not self.around:
            if self.around is not None:
                self.around.removeEventFilter(self)
            self.around = around
            if around is not None:
                around.installEventFilter(self)
        scale = text_scale(around) if around is not None else 1.0
        if scale != self.scale:
            self.scale = scale
            self.widget.setStyleSheet(f"{self.style} font-size: {self.size_pt * scale:g}pt;")

    def eventFilter(self, watched, event) -> bool:
        kind = event.type()
        if (watched is self.widget and kind in (QEvent.Type.StyleChange, QEvent.Type.ParentChange,
                                                QEvent.Type.Show)
                or watched is self.around and kind == QEvent.Type.FontChange):
            self.apply()
        return False


def scaled_style(widget: QWidget, style: str, size_pt: float) -> None:
    """Give ``widget`` the style sheet ``style`` with text ``size_pt`` points at scale 1,
    times the text scale of the widget around it from then on."""
    _ScaledStyle(widget, style, size_pt)


class _IconsFollowText(QObject):
    """Watches the owner's font and sizes the buttons' icons to its line height."""

    def __init__(self, owner: QWidget, buttons):
        super().__init__(owner)
        self.owner, self.buttons = owner, list(buttons)
        owner.installEventFilter(self)
        self.apply()

    def apply(self) -> None:
        side = self.owner.fontMetrics().height()
        for button in self.buttons:
            button.setIconSize(QSize(side, side))

    def eventFilter(self, watched, event) -> bool:
        if event.type() == QEvent.Type.FontChange:
            self.apply()
        return False


def icons_follow_text(owner: QWidget, buttons) -> None:
    """Keep the icons of ``buttons`` (tool buttons in ``owner``) as tall as a line of ``owner``'s
    text, at every text scale: a ×2 hall sees play and close buttons it can hit."""
    _IconsFollowText(owner, buttons)
