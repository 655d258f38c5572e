"""The 3D pane, built once the window is on screen.

pyvista and VTK take about a second to import and the first VTK
frame more; none of it is needed to show the window, its tabs and the first
image.  :class:`DeferredSceneView` stands in the window's layout for the
:class:`views.scene3d.scene_view.SceneView`: it shows a short note, and builds the
real view in its place when told to (:meth:`build_soon`: the window does so
once its first image is shown) or at the latest :data:`BUILD_AFTER_MS` after
it was first painted.  Not earlier: the imports hold the GIL, so they would
slow the first render by as much as they take.  pyvista, VTK's Qt widget and
every VTK module the view loads are imported on a thread, and VTK's render window made there, so
the window keeps answering meanwhile; the view is then built around it, in two turns of the event
loop, and VTK draws its first frame, on the GUI thread.

Until then it keeps what the window asks of the 3D pane (overlays, which of
them are shown, the overview camera) and hands it to the view when it is
built, so the pane shows the same as if it had been there from the start.
Any other attribute of the view (``plotter``, ``frustum``, ...) builds it at
once when asked for, and has the changes that wait a turn
(:meth:`~views.scene3d.scene_view.SceneView.held`) made first.
"""

from __future__ import annotations

import contextlib
import threading
import weakref

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtWidgets import QLabel, QVBoxLayout, QWidget

from views.gui_thread import messenger, tell

PLACEHOLDER = "Loading the 3D view…"
IMPORT_WAIT_S = 10.0
"""How long closing the pane waits for pyvista's import to end (it takes a second or two)."""
BUILD_AFTER_MS = 5000
"""The view is built this long after the pane was first painted if no one asked before: a first
render that compiles the kernels takes minutes, one from numba's cache well under a second (a few
seconds on a busy machine, where loading pyvista beside it would only slow it down)."""


def _import_pyvista(pane: weakref.ref) -> None:
    """Import what the view needs and make VTK's render window for it.  Making one asks which of
    OpenGL's ways to a picture works here: the first time in a process, VTK tries a window of the X
    server with the OpenGL libraries loaded for it (some 50-75 ms), and it did that on the GUI
    thread; the window it returns holds no OpenGL context, which the GUI thread makes later."""
    render_window = None
    try:
        import pyvista  # noqa: F401
        from vtkmodules.vtkRenderingCore import vtkRenderWindow

        import views.scene3d.scene_picking  # noqa: F401  (the pane, VTK's Qt widget and OpenGL; clicks in the pane)

        render_window = vtkRenderWindow()
    finally:
        tell(pane, lambda view: view._build_in_turns(render_window))  # built on the GUI thread


class DeferredSceneView(QWidget):
    """Holds the place of a :class:`views.scene3d.scene_view.SceneView` until it is built.

    Attributes
    ----------
    view : the SceneView, or ``None`` before it is built.

    Signals
    -------
    ready() : the SceneView has been built and shows the pane's state.
    """

    ready = Signal()

    def __init__(self, model, parent: QWidget | None = None):
        super().__init__(parent)
        self.model = model
        self.view = None
        self._overlays: dict[str, list] = {}  # set_overlay calls before the view exists, by name
        self._visible: tuple[bool, object] = (False, None)  # (asked, names) of show_overlays_only
        self._look: tuple[bool, object] = (False, None)  # (asked, view) of look_from
        self._line_scale = 1.0  # set_line_scale before the view exists
        self._painted = False
        self._importer: threading.Thread | None = None  # importing pyvista, once started
        self._closed = False  # closed with its window: nothing more is built
        self._plotter = None  # VTK's widget, made a turn before the view around it
        self._placeholder = QLabel(PLACEHOLDER)
        self._placeholder.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self._placeholder.setStyleSheet("background: #1d2230; color: #c8cfdc;")
        self._layout = QVBoxLayout(self)
        self._layout.setContentsMargins(0, 0, 0, 0)
        self._layout.addWidget(self._placeholder)

    def paintEvent(self, event) -> None:
        super().paintEvent(event)
        if not self._painted:
            self._painted = True
            QTimer.singleShot(BUILD_AFTER_MS, self.build_soon)

    def build_soon(self, *_) -> None:
        """Import pyvista on a thread, then build the view on the GUI thread (once)."""
        if self.view is None and self._importer is None and not self._closed:
            messenger()  # here, on the GUI thread
            self._importer = threading.Thread(target=_import_pyvista, args=(weakref.ref(self),),
                                              name="import pyvista", daemon=True)
            self._importer.start()

    def _build_in_turns(self, render_window) -> None:
        """VTK's widget around ``render_window`` (made on the import thread; ``None`` if that failed,
        and one is made here) in this turn of the event loop (OpenGL and an empty first frame, some 35
        ms), the view around that (the scene's actors, the observer, the axes) in the next: built in
        one go with the render window, it held the window 110-120 ms."""
        if self.view is not None or self._plotter is not None or self._closed:
            return
        from views.scene3d.image_plotter import ImagePlotter

        self._plotter = ImagePlotter(self, render_window)  # hidden until the view shows it
        QTimer.singleShot(0, self, self.build)

    def build(self):
        """Import VTK and build the SceneView now (once); returns it."""
        if self.view is not None:
            return self.view
        from views.scene3d.scene_view import SceneView

        view = SceneView(self.model, self, plotter=self._plotter)
        if self._visible[0]:
            view.show_overlays_only(self._visible[1])
        for name, parts in self._overlays.items():
            view.set_overlay(name, parts)
        if self._look[0]:
            view.look_from(self._look[1])
        if self._line_scale != 1.0:
            view.set_line_scale(self._line_scale)
        self._overlays.clear()
        self._layout.replaceWidget(self._placeholder, view)
        self._placeholder.deleteLater()
        self._layout.activate()  # the view has its place and size at once (mouse positions map)
        self.view = view
        self.ready.emit()
        return view

    # What the window asks of the pane before it exists is kept for it.
    def set_overlay(self, name: str, parts: list) -> None:
        if self.view is not None:
            self.view.set_overlay(name, parts)
        else:
            self._overlays[name] = [(poly, style) for poly, style in parts if poly.n_points]

    def show_overlays_only(self, names) -> None:
        if self.view is not None:
            self.view.show_overlays_only(names)
        else:
            self._visible = (True, None if names is None else set(names))

    def look_from(self, view) -> None:
        if self.view is not None:
            self.view.look_from(view)
        else:
            self._look = (True, view)

    def set_line_scale(self, scale: float) -> None:
        if self.view is not None:
            self.view.set_line_scale(scale)
        else:
            self._line_scale = float(scale)

    def held(self):
        """The view's :meth:`~views.scene3d.scene_view.SceneView.held`; before the view is built its
        changes are kept until it is, in any case."""
        return self.view.held() if self.view is not None else contextlib.nullcontext()

    def overlay_names(self) -> list[str]:
        if self.view is not None:
            return self.view.overlay_names()
        shown = self._visible[1]
        return [name for name, parts in self._overlays.items() if parts and (shown is None or name in shown)]

    def overlay_parts(self, name: str) -> list:
        if self.view is not None:
            return self.view.overlay_parts(name)
        return [poly for poly, _ in self._overlays.get(name, [])]

    def close(self) -> bool:
        """Close the view, or VTK's widget made for it, and build nothing after: a window closed while
        its pane was being built went on to build it, and pyvista's list of plotters kept its VTK
        render window, its OpenGL context open, until the process ended.  An import under way is
        waited for (it takes a second or two): the process may end next, and an import on a thread while it
        ends may crash it."""
        self._closed = True
        if self._importer is not None:
            self._importer.join(IMPORT_WAIT_S)
        if self.view is not None:
            self.view.close()
        elif self._plotter is not None:
            self._plotter.close()
            self._plotter = None
        return super().close()

    def __getattr__(self, name: str):
        # Only called for what this widget lacks: the SceneView's own attributes.  Names no
        # attribute could have (PySide's connect looks a lambda slot up as "<lambda>") build nothing.
        if name.startswith("_") or not name.isidentifier() or name in ("view", "model"):
            raise AttributeError(name)
        view = self.build()
        view.catch_up()  # answered for every change asked before (SceneView.held)
        return getattr(view, name)
