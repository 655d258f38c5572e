"""Cancel on the Cost tab, or closing it, stops the sweep inside a render of many minutes (issue 35).

The sweep is of the acceleration knob on 90,000 triangles at 640 x 480; its first setting is
``none``, every ray against every triangle: about 2.8e10 ray-triangle tests for the camera rays
alone; each of its four renders (warm-up and three timed) takes about 7 minutes on the 2-core
test machine (4.5 s at 64 x 48, times 100 pixels as many).  The reference before it uses the
BVH and takes seconds.  Once the reference is done the sweep is inside that render; Cancel (or
closing the panel) must free the pool's thread within seconds, keep what was measured (nothing yet)
and show no failure.  The wait's timeout is only a guard against a hang.
"""

import pytest
from PySide6.QtCore import Qt, QThreadPool

from core.camera import Camera
from core.scene import PointLight, Scene
from core.shapes import uv_sphere
from views.panels.cost_panel import CostPanel

REFERENCE_TIMEOUT_MS = 240_000  # the reference (BVH), and the kernels if they still load or compile
STOP_TIMEOUT_MS = 5_000


def _minutes_per_render() -> Scene:
    cam = Camera(eye=(0, 0, 6), target=(0, 0, 0), width=640, height=480)
    sphere = uv_sphere((0, 0, 0), 1.5, rings=150, segments=300)  # 2 x 150 x 300 = 90,000 triangles
    return Scene(camera=cam, objects=(sphere,), lights=(PointLight((5, 5, 5)),))


@pytest.mark.parametrize("how", ["cancel button", "closing the panel"])
def test_cancel_stops_the_sweep_inside_its_render(qtbot, how):
    pool = QThreadPool()
    panel = CostPanel(pool=pool)
    qtbot.addWidget(panel)
    panel.show()
    panel.set_scene(_minutes_per_render())
    panel.knob.setCurrentIndex(panel.knob.findData("accel"))
    panel.mode.setCurrentIndex(panel.mode.findData("raytrace"))
    panel.width_px.setValue(640)
    panel.reference_spp.setValue(1)
    with qtbot.assertNotEmitted(panel.sweep_finished, wait=200):
        qtbot.mouseClick(panel.run_button, Qt.MouseButton.LeftButton)
        assert panel.running
        # The reference is stored when the sweep moves on to render 'none' (Sweep.events).
        qtbot.waitUntil(lambda: "raytrace" in panel.sweep.references, timeout=REFERENCE_TIMEOUT_MS)
        assert panel.sweep.settings[0].label == "none"
        if how == "cancel button":
            qtbot.mouseClick(panel.cancel_button, Qt.MouseButton.LeftButton)
        else:
            panel.close()
        qtbot.waitUntil(lambda: pool.activeThreadCount() == 0, timeout=STOP_TIMEOUT_MS)

    n = len(panel.sweep.settings)
    assert panel.status.text() == f"Stopped after 0 of {n} settings; Run resumes."
    assert "failed" not in panel.status.text()
    assert not panel.running and panel.rows() == []
    assert panel.run_button.isEnabled() and not panel.cancel_button.isEnabled()
