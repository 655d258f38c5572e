"""Tab titles that fit: a tab bar too narrow for its titles shows their short forms, whole, before it
elides any.

At twice the text size on a 1280 x 720 projector the window's six tabs read "Image …", "Object …",
"Four v…", "Com…", "Hard c…", "Cost"; with short forms for three of them they read "Image", "Object",
"Views", "Compare", "Hard cases", "Cost", and each tab's tooltip gives its whole title.  When the
titles fit again (a larger window, a smaller text, a lesson that shows fewer tabs), they are whole
again.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, QTimer
from PySide6.QtWidgets import QTabWidget


class TitlesThatFit(QObject):
    """Keeps ``tabs``' titles whole when they fit and short (``short[title]``) when they do not."""

    def __init__(self, tabs: QTabWidget, short: dict[str, str]):
        super().__init__(tabs)
        self.tabs, self.short = tabs, dict(short)
        self._fit_soon = QTimer(self, singleShot=True, interval=0, timeout=self.fit)
        tabs.installEventFilter(self)

    def title(self, index: int) -> str:
        """Tab ``index``'s whole title (kept as its tooltip)."""
        return self.tabs.tabToolTip(index) or self.tabs.tabText(index)

    def eventFilter(self, watched: QObject, event: QEvent) -> bool:
        if event.type() in (QEvent.Type.Resize, QEvent.Type.FontChange, QEvent.Type.StyleChange,
                            QEvent.Type.LayoutRequest):  # a tab shown or hidden asks for a new layout
            self._fit_soon.start()
        return False

    def fit(self) -> None:
        tabs, bar = self.tabs, self.tabs.tabBar()
        shown = [i for i in range(tabs.count()) if tabs.isTabVisible(i)]
        for i in range(tabs.count()):
            tabs.setTabToolTip(i, self.title(i))
        self._set({i: self.title(i) for i in shown})
        if sum(bar.tabSizeHint(i).width() for i in shown) > tabs.width():
            self._set({i: self.short.get(self.title(i), self.title(i)) for i in shown})

    def _set(self, texts: dict[int, str]) -> None:
        for i, text in texts.items():
            if self.tabs.tabText(i) != text:  # a new text asks for a layout, which fits again
                self.tabs.setTabText(i, text)
