"""A dock's title bar that follows the text size.

Qt draws a dock's own title in the platform's title font, taken once when the
dock is made, whenever the dock's font is the application's: presenting at ×2
(:mod:`views.presentation`, which scales the application's font) would leave
every dock title at the normal size.  :class:`DockTitle` is a label (and a
close button for a dock that may be closed) that takes the dock's font like any
widget.  Dragging it moves the dock, as Qt's own title does: neither the bar
nor its label takes the mouse, so the press reaches the dock.
"""

from __future__ import annotations

from PySide6.QtWidgets import QDockWidget, QHBoxLayout, QLabel, QStyle, QToolButton, QWidget

from views.text.text_scale import icons_follow_text


class DockTitle(QWidget):
    """The title bar of ``dock``: its title, and a close button if it may be closed."""

    def __init__(self, dock: QDockWidget):
        super().__init__(dock)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(4, 1, 1, 1)
        self.label = QLabel(dock.windowTitle())
        dock.windowTitleChanged.connect(self.label.setText)
        layout.addWidget(self.label, 1)
        self.close_button = None
        if dock.features() & QDockWidget.DockWidgetFeature.DockWidgetClosable:
            self.close_button = QToolButton()
            self.close_button.setIcon(self.style().standardIcon(QStyle.StandardPixmap.SP_TitleBarCloseButton))
            self.close_button.setAutoRaise(True)
            self.close_button.setToolTip(f"Close {dock.windowTitle()} (the View menu shows it again)")
            self.close_button.clicked.connect(dock.close)
            layout.addWidget(self.close_button)
            icons_follow_text(self, [self.close_button])
        dock.setTitleBarWidget(self)
