"""A pyvista plotter that VTK draws off screen and a plain Qt widget paints as an image.

Why not :class:`pyvistaqt.QtInteractor`: that one is a ``QOpenGLWidget``, and
a single OpenGL widget turns the whole Qt window into an OpenGL surface that
Qt composes again on *every* repaint — a progress bar step, a new image in a
tab — by drawing the full window as textures.  Under a software OpenGL
(llvmpipe, as under Xvfb) that costs 15–40 ms a repaint at 1600 × 900, and
the window repaints many times a second while the observer moves.  Letting
VTK draw into a native child window avoids that, but then every draw copies
the picture to the window through OpenGL (8 ms of a 20 ms draw in llvmpipe).

Here VTK draws into its own off-screen framebuffer; :meth:`render` reads the
picture back (about a millisecond) and the widget paints it like any other
image.  The Qt window stays a plain raster surface (a repaint costs about a
millisecond) and one window of the window system (:meth:`ImagePlotter._stay_plain`),
and a paint makes VTK draw only after a change of size, once
however often the size changed since (a new text size or full screen resizes
the pane four or five times in one turn of the event loop, each draw 8-30 ms),
and in the turn after that paint.

The plotter is both the Qt widget (mouse and keys go to VTK's trackball
interactor, through VTK's own ``QVTKRenderWindowInteractor``) and a pyvista
plotter (``add_mesh``, ``renderer``, ``camera``, ``render()``, ``screenshot()``).
"""

from __future__ import annotations

import contextlib

import numpy as np
import vtkmodules.vtkInteractionStyle  # noqa: F401  (VTK's interactor styles)
import vtkmodules.vtkInteractionWidgets  # noqa: F401  (these three: see below)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL render window of this platform)
import vtkmodules.vtkViewsContext2D  # noqa: F401
import vtkmodules.vtkViewsCore  # noqa: F401
from PySide6.QtCore import Qt, QTimer
from PySide6.QtGui import QColor, QImage, QLinearGradient, QPainter
from PySide6.QtWidgets import QWidget
from pyvista.plotting.plotter import BasePlotter
from pyvista.plotting.render_window_interactor import RenderWindowInteractor
from vtkmodules.qt.QVTKRenderWindowInteractor import QVTKRenderWindowInteractor
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray
from vtkmodules.vtkRenderingCore import vtkRenderWindow

# pyvista's interactor loads vtkInteractionWidgets, vtkViewsContext2D and vtkViewsCore on first use, in
# the plotter's constructor on the GUI thread (about 90 ms); imported above, they load with this module,
# on the thread that imports it (views.scene3d.deferred_scene_view).


@contextlib.contextmanager
def _without_base_plotter_init():
    """Qt's constructor calls the next ``__init__`` of the class's bases (BasePlotter's)
    without arguments; it is called once, explicitly, after the widget exists."""
    init = BasePlotter.__init__
    BasePlotter.__init__ = lambda *args, **kwargs: None
    try:
        yield
    finally:
        BasePlotter.__init__ = init


@contextlib.contextmanager
def _without_native_window(cls):
    """VTK's widget asks Qt for its native window (``winId``) to hand VTK, which draws off screen
    here and needs none: meanwhile the widget is told it has none (0), and no window of the window
    system is made for it (see :meth:`ImagePlotter._stay_plain`)."""
    cls.winId = lambda self: 0
    try:
        yield
    finally:
        del cls.winId


class ImagePlotter(QVTKRenderWindowInteractor, BasePlotter):
    """A pyvista plotter and the Qt widget that shows what it drew.

    Attributes
    ----------
    picture : the last picture drawn (a QImage in device pixels), or ``None`` before the first.
    """

    def __init__(self, parent: QWidget | None = None, render_window: vtkRenderWindow | None = None):
        """``render_window``: a new VTK render window to draw in (one is made if not given; the first
        one a process makes loads the OpenGL libraries, some 45 ms)."""
        window = render_window if render_window is not None else vtkRenderWindow()
        window.SetOffScreenRendering(True)
        window.SetMultiSamples(0)  # anti-aliasing is FXAA, and only when the pane rests
        with _without_base_plotter_init(), _without_native_window(ImagePlotter):
            QVTKRenderWindowInteractor.__init__(self, None, rw=window)  # (no parent: see _stay_plain)
        self._stay_plain(parent)
        BasePlotter.__init__(self)
        self.picture: QImage | None = None
        self._resized = False  # drawn the turn after the next paint, at the size the pane has then
        # The draw after a new size waits for the turn after the paint that asked for it: a new text
        # size or full screen relays and repaints the whole window in one turn, and VTK's draw (6-12
        # ms) made that turn longer still.  Meanwhile the last picture is painted, stretched.
        self._draw_resized = QTimer(self, singleShot=True, interval=0)
        self._draw_resized.timeout.connect(lambda: self._resized and self.render())
        self._pixels = vtkUnsignedCharArray()
        self._gradient = None  # (top, bottom) RGB in 0..1, painted under the picture
        self.ren_win = window
        window.SetAlphaBitPlanes(True)  # the picture keeps its coverage, to go over a painted gradient
        for renderer in self.renderers:
            renderer.view_isometric()
            window.AddRenderer(renderer)
        # Every draw is shown, also those VTK's trackball makes while the mouse turns, pans or
        # zooms the view (they were drawn off screen and never painted until the next change).
        self._grabbing = True
        window.AddObserver("EndEvent", lambda *_: self._grab())
        self.iren = RenderWindowInteractor(self, interactor=window.GetInteractor())
        self.iren.interactor.RemoveObservers("MouseMoveEvent")  # pyvista's own: a draw per mouse move
        self.iren.initialize()
        self.enable_trackball_style()
        self._first_time = False  # BasePlotter draws only after its first show(); this one is shown

    def _stay_plain(self, parent: QWidget | None) -> None:
        """Undo what VTK's widget asked of Qt for drawing on screen, then take ``parent``: to be
        painted on screen, and a window of the window system of its own (``MSWindowsOwnDC``, which
        on X11 asks for one, and made in a parent on screen, makes one at once for every widget
        around it).  Such a window it was, and so were its parents, their siblings and the window's
        docks, menu and status bars (19 in all), whose sizes and places then went through the X
        server and came back later.  This widget paints the picture itself, a plain widget inside
        the window's own (``setParent`` resets the window flags)."""
        self.setAttribute(Qt.WidgetAttribute.WA_PaintOnScreen, False)
        self.setAttribute(Qt.WidgetAttribute.WA_NativeWindow, False)
        if parent is not None:
            self.setParent(parent)

    def set_background(self, color, top=None, **kwargs) -> None:
        """As pyvista's; a vertical gradient (``top`` given) is painted by the widget, under the
        picture VTK draws over a transparent background.  (VTK's own gradient costs a software
        OpenGL a pass over every pixel of every draw, a third or more of the draw; Qt paints it
        in about a millisecond.)  :meth:`screenshot` has VTK draw the gradient itself."""
        BasePlotter.set_background(self, color, top=top, **kwargs)
        self._gradient = None
        if top is not None:
            self._gradient = (self.renderer.GetBackground2(), self.renderer.GetBackground())
        self._vtk_draws_background(self._gradient is None)

    def _vtk_draws_background(self, yes: bool) -> None:
        """VTK draws the background, or a transparent black one (the picture is then premultiplied)."""
        if self._gradient is None:
            return
        top, bottom = self._gradient
        self.renderer.SetBackground(*(bottom if yes else (0.0, 0.0, 0.0)))
        self.renderer.SetBackground2(*top)
        self.renderer.SetGradientBackground(yes)
        self.renderer.SetBackgroundAlpha(1.0 if yes else 0.0)

    @contextlib.contextmanager
    def _drawn_for_a_file(self):
        """Meanwhile VTK draws the background itself (gradient and all), and its draws (at another size,
        background drawn) are not taken as the pane's picture."""
        self._vtk_draws_background(True)
        self._grabbing = False
        try:
            yield
        finally:
            self._grabbing = True
            self._vtk_draws_background(False)

    def screenshot(self, *args, **kwargs):
        """pyvista's screenshot, with the background drawn by VTK (gradient and all)."""
        with self._drawn_for_a_file():
            BasePlotter.render(self)
            return BasePlotter.screenshot(self, *args, **kwargs)

    def picture_at(self, scale: int) -> np.ndarray:
        """The scene drawn at ``scale`` × the pane's size, background and all: (H, W, 3) uint8.

        VTK draws it once, its off-screen window made ``scale`` times as large for that draw: what
        pyvista's ``screenshot(window_size=...)`` gives, pixel for pixel, without the draws it makes
        around it.  (Drawn in tiles of the pane's size, as ``screenshot(scale=...)`` does, it took
        nine draws at × 2, two and a half times as long, and held the window 100-160 ms.)
        """
        w, h = self.ren_win.GetSize()
        pixels = vtkUnsignedCharArray()
        with self._drawn_for_a_file():
            self.ren_win.SetSize(scale * w, scale * h)
            try:
                self.ren_win.Render()
                rgba = self._read_back(pixels)
            finally:
                self.ren_win.SetSize(w, h)
        return np.ascontiguousarray(rgba[..., :3])

    def _read_back(self, pixels: vtkUnsignedCharArray) -> np.ndarray:
        """What VTK last drew, read into ``pixels``: an (H, W, 4) view of it, row 0 on top."""
        w, h = self.ren_win.GetSize()
        self.ren_win.GetRGBACharPixelData(0, 0, w - 1, h - 1, False, pixels)
        return vtk_to_numpy(pixels).reshape(h, w, 4)[::-1]

    def paintEngine(self):
        return QWidget.paintEngine(self)

    def paintEvent(self, event) -> None:
        if self._resized:
            self._draw_resized.start()
        if self.picture is None:
            return
        painter = QPainter(self)
        if self._gradient is not None:
            top, bottom = self._gradient
            fill = QLinearGradient(0, 0, 0, self.height())
            fill.setColorAt(0.0, QColor.fromRgbF(*top))
            fill.setColorAt(1.0, QColor.fromRgbF(*bottom))
            painter.fillRect(self.rect(), fill)
        painter.drawImage(self.rect(), self.picture)
        painter.end()

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)  # VTK's: the render window takes the new size, and a paint is asked
        self._resized = True

    def render(self) -> None:
        """Draw the scene now and show it (nothing once closed or while hidden)."""
        if getattr(self, "_closed", False) or not self.isVisible():
            return
        BasePlotter.render(self)  # VTK's EndEvent: _grab shows the picture

    def _grab(self) -> None:
        """Read back the picture VTK just drew and paint it with the next frame."""
        if not self._grabbing or getattr(self, "_closed", False) or not self.isVisible():
            return
        self._resized = False
        rgba = np.ascontiguousarray(self._read_back(self._pixels))
        h, w, _ = rgba.shape
        over = self._gradient is not None  # VTK drew over a transparent background
        kind = QImage.Format.Format_RGBA8888_Premultiplied if over else QImage.Format.Format_RGBX8888
        self.picture = QImage(rgba.data, w, h, 4 * w, kind).copy()
        self.picture.setDevicePixelRatio(self.devicePixelRatioF())
        self.update()

    def close(self) -> None:
        """Release VTK's render window and OpenGL context (the Qt widget goes with its parent)."""
        if getattr(self, "_closed", True):
            return
        BasePlotter.close(self)  # finalizes the render window
