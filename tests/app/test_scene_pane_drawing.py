"""How the 3D pane is drawn: cheaply, and the same picture as VTK's most careful way."""

from PySide6.QtGui import QSurface


def test_repaints_of_the_window_never_go_through_opengl(window):
    # One OpenGL widget anywhere would make Qt compose the whole window through OpenGL at every repaint.
    assert window.windowHandle().surfaceType() == QSurface.SurfaceType.RasterSurface
