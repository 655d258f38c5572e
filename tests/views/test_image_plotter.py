"""The 3D pane's plotter: VTK draws off screen, a plain widget paints the picture, the window stays raster."""

import numpy as np
import pytest
import pyvista as pv
from PySide6.QtGui import QSurface
from PySide6.QtWidgets import QApplication, QVBoxLayout, QWidget

from views.image_plotter import ImagePlotter


@pytest.fixture
def shown(qtbot):
    """A window with a plotter that sees one red, unlit square filling its view; and a draw counter."""
    window = QWidget()
    plotter = ImagePlotter(window)
    QVBoxLayout(window).addWidget(plotter)
    qtbot.addWidget(window)
    plotter.set_background("black")
    plotter.add_mesh(pv.Plane(i_size=10, j_size=10), color="red", lighting=False)
    plotter.view_xy()
    window.resize(300, 300)
    window.show()
    qtbot.waitExposed(window)
    draws = []
    plotter.ren_win.AddObserver("EndEvent", lambda *_: draws.append(1))
    yield window, plotter, draws
    plotter.close()


def _on_screen(widget):
    """What the screen shows where ``widget`` is, as (H, W, 3) uint8."""
    corner = widget.mapToGlobal(widget.rect().topLeft())
    image = QApplication.primaryScreen().grabWindow(0, corner.x(), corner.y(), widget.width(),
                                                     widget.height()).toImage()
    image = image.convertToFormat(image.Format.Format_RGB888)
    rows = np.frombuffer(image.constBits(), np.uint8).reshape(image.height(), image.bytesPerLine())
    return rows[:, :3 * image.width()].reshape(image.height(), image.width(), 3)


def test_the_drawn_picture_is_on_screen_and_the_window_stays_a_raster_surface(qtbot, shown):
    window, plotter, _ = shown
    plotter.render()
    qtbot.waitUntil(lambda: _on_screen(plotter)[150, 150, 0] > 200)
    middle = _on_screen(plotter)[140:160, 140:160]
    assert (middle[..., 0] > 200).all() and (middle[..., 1:] < 60).all()  # the red square
    assert window.windowHandle().surfaceType() == QSurface.SurfaceType.RasterSurface


def test_the_picture_is_upright(shown):
    _, plotter, _ = shown
    plotter.set_background("black", top="white")  # a gradient: white at the top of the view
    plotter.clear_actors()
    plotter.render()
    picture = plotter.picture.convertToFormat(plotter.picture.Format.Format_Grayscale8)
    assert picture.pixelColor(5, 2).value() > 200 and picture.pixelColor(5, picture.height() - 3).value() < 50


def test_a_paint_shows_the_last_picture_without_drawing_again(qtbot, shown):
    _, plotter, draws = shown
    plotter.render()
    assert draws == [1]
    plotter.repaint()
    assert draws == [1]


def test_a_new_size_is_drawn_at_once(qtbot, shown):
    window, plotter, draws = shown
    window.resize(360, 240)
    qtbot.waitUntil(lambda: plotter.picture is not None and plotter.picture.width() == plotter.width())
    assert draws and plotter.picture.height() == plotter.height()


def test_a_closed_plotter_no_longer_draws(shown):
    _, plotter, draws = shown
    plotter.close()
    plotter.render()
    assert not draws
