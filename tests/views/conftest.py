"""What the views' tests share."""

from dataclasses import replace

import pytest
from PySide6.QtWidgets import QMainWindow
from qt_fixtures import (  # noqa: F401
    application_font_restored,
    closed_widgets_deleted,
    private_settings,
    require_display,
    shown_widget,
)

from core.presets_trace import mirror_and_glass
from views.panels.cost_panel import CostPanel
from views.presentation import Presentation

COST_TIMEOUT_MS = 240_000


@pytest.fixture
def cost_panel(qtbot):
    """A Cost panel at 1280 x 720 on a small mirror-and-glass scene, set for quick sweeps (32 pixels
    wide, 2 samples in the reference); cancelled and its sweep finished after the test."""
    widget = shown_widget(qtbot, CostPanel(), 1280, 720)
    scene = mirror_and_glass()
    widget.set_scene(replace(scene, camera=scene.camera.replace(width=320, height=240)))
    widget.width_px.setValue(32)
    widget.reference_spp.setValue(2)
    yield widget
    widget.cancel()
    qtbot.waitUntil(lambda: widget._sweep_lock.acquire(blocking=False), timeout=COST_TIMEOUT_MS)
    widget._sweep_lock.release()


@pytest.fixture
def present(qtbot):
    """``present(panel)`` shows ``panel`` alone in a 1280 x 720 main window, as a lecturer's window
    would hold it, and returns ``(window, presentation)``: the window's presentation mode."""

    def show(panel):
        window = QMainWindow()
        window.setCentralWidget(panel)
        shown_widget(qtbot, window, 1280, 720)
        return window, Presentation(window)

    return show
