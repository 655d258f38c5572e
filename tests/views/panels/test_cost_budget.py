"""The Cost panel estimates a sweep before it starts: over the memory budget it does not start."""

from dataclasses import replace

from PySide6.QtCore import Qt

from core import presets
from views.panels.cost_panel import CostPanel


def test_a_sweep_over_the_budget_does_not_start_and_says_what_to_reduce(qtbot):
    panel = CostPanel()
    qtbot.addWidget(panel)
    panel.show()
    scene = presets.lecture_scene()
    panel.set_scene(replace(scene, camera=scene.camera.replace(width=640, height=480)))
    panel.width_px.setValue(640)
    panel.memory_limit = 50_000_000
    qtbot.mouseClick(panel.run_button, Qt.MouseButton.LeftButton)
    text = panel.status.text()
    assert not panel.running and panel.run_button.isEnabled()
    assert text.startswith("This sweep of 50 settings at 640 × 480 needs about")
    for fragment in ("kept images", "the budget is 50 MB", "Not started", "smaller width"):
        assert fragment in text
