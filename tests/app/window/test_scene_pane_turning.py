"""The 3D pane turns under the mouse while it is dragged, not only at the next change."""

import numpy as np
from PySide6.QtCore import QPoint, QPointF, Qt


def _pixels(view) -> np.ndarray:
    picture = view.plotter.picture
    return np.array(picture.constBits(), np.uint8).reshape(picture.height(), picture.bytesPerLine())


def test_dragging_away_from_the_camera_and_target_turns_the_view_live(qtbot, window):
    view = window.scene_view
    qtbot.waitUntil(lambda: view.plotter is not None and view.plotter.picture is not None)  # drawn once
    plotter = view.plotter
    start = QPointF(plotter.width() * 0.8, plotter.height() * 0.8)
    assert view.grabbable_at(start) is None  # away from the camera glyph and the target
    before, position = _pixels(view), plotter.camera.position
    qtbot.mousePress(plotter, Qt.MouseButton.LeftButton, pos=start.toPoint())
    for k in range(1, 6):
        qtbot.mouseMove(plotter, pos=(start - QPointF(12 * k, 0)).toPoint())
    # Still dragging: the overview camera turned and the pane shows it.
    assert plotter.camera.position != position
    assert not np.array_equal(_pixels(view), before)
    qtbot.mouseRelease(plotter, Qt.MouseButton.LeftButton, pos=(start - QPointF(60, 0)).toPoint())
    assert plotter.rect().contains(QPoint(0, 0))


def test_the_camera_glyph_stays_in_the_pane_while_the_observer_orbits(qtbot, window):
    # Orbiting with the arrow keys walked the observer's camera glyph out of the pane.
    from views.scene3d.observer_keys import ORBIT_STEP_DEG, orbit

    view, model = window.scene_view, window.model
    plotter = view.plotter
    for _ in range(round(360 / ORBIT_STEP_DEG)):  # once around the target, as the Right key does
        model.set_camera(orbit(model.camera, ORBIT_STEP_DEG, 0))
        eye = view.widget_pos(model.camera.eye)
        assert 0 <= eye.x() <= plotter.width() and 0 <= eye.y() <= plotter.height(), model.camera.eye
        target = view.widget_pos(model.camera.target)
        assert 0 <= target.x() <= plotter.width() and 0 <= target.y() <= plotter.height()
