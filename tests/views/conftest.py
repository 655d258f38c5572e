"""What the views' tests share."""

import pytest
from PySide6.QtWidgets import QMainWindow

from views.presentation import Presentation


@pytest.fixture
def present(qtbot):
    """``present(panel)`` shows ``panel`` alone in a 1280 x 720 main window, as a lecturer's window
    would hold it, and returns ``(window, presentation)``: the window's presentation mode."""

    def show(panel):
        window = QMainWindow()
        window.setCentralWidget(panel)
        qtbot.addWidget(window)
        window.resize(1280, 720)
        window.show()
        return window, Presentation(window)

    return show
