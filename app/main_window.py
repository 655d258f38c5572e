"""The main window: wires the scene model to the 3D pane, the image pane and the controls.

No algorithms live here.  The model (:class:`app.state.SceneModel`) holds the
scene; the camera panel asks it for changes; its signals redraw the frustum
and start a background render of the observer's image.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pyvista as pv
from PySide6.QtCore import Qt, QThreadPool, QTimer
from PySide6.QtGui import QAction, QFont, QKeySequence
from PySide6.QtWidgets import (
    QApplication,
    QDockWidget,
    QFileDialog,
    QHBoxLayout,
    QLabel,
    QMainWindow,
    QMessageBox,
    QProgressBar,
    QPushButton,
    QScrollArea,
    QSplitter,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from app.mesh_files import read_mesh
from app.state import SceneModel
from app.tabs import CompareTab, FourViewsTab, ImageOrderTab, ObjectOrderTab
from app.workers import Renderer
from core import presets, scene_file
from core.camera import camera_problems
from core.image_order.bounding_spheres import bounding_spheres
from core.image_order.flat_scene import trace_scene
from core.image_order.grid_of_cuboids import cells_on_ray
from core.image_order.ray_tree import trace_pixel
from core.object_order import three_views
from core.presets_trace import PRESETS_TRACE
from core.scene import Scene
from views import raytree_view, vtk_convert
from views.camera_panel import CameraPanel
from views.raytree_view import KIND_COLORS
from views.scene_view import SceneView

ORBIT_STEP_DEG = 5.0
ZOOM_FACTOR = 1.15


class MainWindow(QMainWindow):
    """Render Explorer's window: 3D scene with the observer, and what the observer sees."""

    def __init__(self, scene: Scene):
        super().__init__()
        self.setWindowTitle("Render Explorer")
        self.model = SceneModel(scene, self)
        self.scene_path: Path | None = None
        self.scene_view = SceneView()
        self.camera_panel = CameraPanel(scene.camera)
        self.tabs = [ImageOrderTab(), ObjectOrderTab(), FourViewsTab(), CompareTab()]
        self.tab_widget = QTabWidget()
        self.renderers = []
        for tab in self.tabs:
            self.tab_widget.addTab(tab.widget, tab.title)
            renderer = Renderer(self)
            renderer.progress.connect(lambda pct, partial, t=tab: self._render_progress(t, pct, partial))
            renderer.finished.connect(lambda result, t=tab: self._render_finished(t, result))
            renderer.failed.connect(self._render_failed)
            self.renderers.append(renderer)
        self._stale = set(range(len(self.tabs)))
        self.progress = QProgressBar()
        self.progress.setRange(0, 100)
        self.progress.setTextVisible(True)
        self.status_caption = QLabel()
        self.status_caption.setWordWrap(True)
        self.last_result = None

        right = QWidget()
        right_layout = QVBoxLayout(right)
        right_layout.setContentsMargins(0, 0, 0, 0)
        right_layout.addWidget(self.tab_widget, 1)
        progress_row = QHBoxLayout()
        progress_row.addWidget(self.progress, 1)
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setToolTip("Stop the render in progress (Esc)")
        self.cancel_button.setShortcut(QKeySequence("Esc"))
        self.cancel_button.clicked.connect(self.cancel_render)
        self.cancel_button.setEnabled(False)
        progress_row.addWidget(self.cancel_button)
        right_layout.addLayout(progress_row)
        right_layout.addWidget(self.status_caption)
        scene_pane = QWidget()
        scene_layout = QVBoxLayout(scene_pane)
        scene_layout.setContentsMargins(6, 6, 6, 6)
        scene_title = QLabel(
            "<b>The scene</b> — observer, viewing pyramid (frustum) and screen on the near plane")
        scene_title.setWordWrap(True)
        scene_layout.addWidget(scene_title)
        scene_layout.addWidget(self.scene_view, 1)
        splitter = QSplitter(Qt.Orientation.Horizontal)
        splitter.addWidget(scene_pane)
        splitter.addWidget(right)
        scene_pane.setMinimumWidth(320)
        splitter.setSizes([600, 700])
        self.setCentralWidget(splitter)

        dock = QDockWidget("Controls", self)
        dock.setFeatures(QDockWidget.DockWidgetFeature.DockWidgetMovable)
        dock.setTitleBarWidget(QWidget())  # the group boxes carry the titles
        self._controls = QScrollArea()
        self._controls.setWidgetResizable(True)
        self._controls.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        self._controls.setWidget(self.camera_panel)
        dock.setWidget(self._controls)
        self._fit_controls()
        self.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, dock)
        self._build_menus()

        self.camera_panel.camera_requested.connect(self._camera_requested)
        self.model.camera_changed.connect(self.camera_panel.set_camera)
        self.model.camera_changed.connect(self.scene_view.set_camera)
        self.model.camera_changed.connect(self._scene_edited)
        self.model.scene_changed.connect(lambda scene: self.camera_panel.set_camera(scene.camera))
        self.model.scene_changed.connect(self.scene_view.set_scene)
        self.model.scene_changed.connect(self._scene_edited)
        self.tab_widget.currentChanged.connect(self._tab_shown)
        image_order = self.tabs[0].widget
        image_order.settings_changed.connect(lambda _: self._rerender(0))
        image_order.pixel_picked.connect(self.pick_ray_tree)
        image_order.overlays_changed.connect(self._show_accel_overlays)
        self.ray_tree = None
        self._tree_renderer = Renderer(self)
        self._tree_renderer.finished.connect(self._show_ray_tree)
        self._tree_renderer.failed.connect(self._render_failed)
        object_order = self.tabs[1].widget
        object_order.settings_changed.connect(lambda _: self._rerender(1))
        object_order.polygon_shown.connect(self._show_polygon)
        object_order.clipped_shown.connect(self._show_clipped)

        self.scene_view.set_scene(scene)
        self._render_current()
        self.progress.setFormat("compiling the renderers on first use (numba caches them), "
                                "then rendering… %p%")
        available = self.screen().availableGeometry()
        self.resize(min(1400, available.width()), min(860, available.height()))

    # ----------------------------------------------------------------- menus
    def _action(self, menu, text, slot, shortcut=None, tip=""):
        action = QAction(text, self)
        if shortcut:
            action.setShortcut(QKeySequence(shortcut))
        action.setStatusTip(tip)
        action.setToolTip(tip)
        action.triggered.connect(slot)
        menu.addAction(action)
        return action

    def _build_menus(self):
        file_menu = self.menuBar().addMenu("&File")
        self._action(file_menu, "&Open scene…", self.open_scene_dialog, QKeySequence.StandardKey.Open,
                     "Open a scene JSON file")
        self._action(file_menu, "&Save scene as…", self.save_scene_dialog,
                     QKeySequence.StandardKey.SaveAs, "Save the scene and observer as JSON")
        self._action(file_menu, "&Lecture scene", self.reset_scene, "Ctrl+L",
                     "Back to the lecture's cube and cone on a plane")
        examples = file_menu.addMenu("&Examples")
        for group in (presets.PRESETS, PRESETS_TRACE):
            for key, (title, build) in group.items():
                self._action(examples, title, lambda _=False, b=build, k=key: self.load_preset(k, b))
            examples.addSeparator()
        file_menu.addSeparator()
        self._action(file_menu, "&Quit", self.close, QKeySequence.StandardKey.Quit)
        observer = self.menuBar().addMenu("&Observer")
        self._action(observer, "Walk left", lambda: self.orbit_by(-ORBIT_STEP_DEG, 0), "Left")
        self._action(observer, "Walk right", lambda: self.orbit_by(ORBIT_STEP_DEG, 0), "Right")
        self._action(observer, "Look from higher", lambda: self.orbit_by(0, ORBIT_STEP_DEG), "Up")
        self._action(observer, "Look from lower", lambda: self.orbit_by(0, -ORBIT_STEP_DEG), "Down")
        self._action(observer, "Step closer", lambda: self.zoom_by(1 / ZOOM_FACTOR), "+")
        self._action(observer, "Step back", lambda: self.zoom_by(ZOOM_FACTOR), "-")
        self._action(observer, "Toggle perspective / orthographic", self.toggle_projection, "P")
        view = self.menuBar().addMenu("&View")
        self._action(view, "Larger text (lecture hall)", lambda: self.scale_text(1.25),
                     QKeySequence.StandardKey.ZoomIn)
        self._action(view, "Smaller text", lambda: self.scale_text(0.8),
                     QKeySequence.StandardKey.ZoomOut)
        self._action(view, "Re-render", self._render_current, "F5")
        for i, tab in enumerate(self.tabs):
            self._action(view, tab.title, lambda _=False, i=i: self.tab_widget.setCurrentIndex(i),
                         f"Ctrl+{i + 1}")

    # ----------------------------------------------------------- observer
    def _camera_requested(self, camera):
        if not self.model.set_camera(camera) and camera != self.model.camera:
            problems = "; ".join(f"{f}: {m}" for f, m in camera_problems(camera))
            self.statusBar().showMessage(f"Observer not moved — {problems}", 6000)
            self.camera_panel.set_camera(self.model.camera)

    def orbit_by(self, d_yaw: float, d_pitch: float) -> None:
        cam = self.model.camera
        pitch = max(-89.0, min(89.0, cam.pitch_deg + d_pitch))
        self._camera_requested(cam.orbit(cam.yaw_deg + d_yaw, pitch))

    def zoom_by(self, factor: float) -> None:
        cam = self.model.camera
        self._camera_requested(cam.orbit(cam.yaw_deg, cam.pitch_deg, cam.distance * factor))

    def toggle_projection(self) -> None:
        cam = self.model.camera
        other = "orthographic" if cam.projection == "perspective" else "perspective"
        self._camera_requested(cam.replace(projection=other))

    def scale_text(self, factor: float) -> None:
        app = QApplication.instance()
        font = QFont(app.font())
        font.setPointSizeF(max(7.0, min(40.0, font.pointSizeF() * factor)))
        app.setFont(font)
        QTimer.singleShot(0, self._fit_controls)  # after the new font reached every widget

    def _fit_controls(self) -> None:
        """Keep the whole control panel visible at any text size."""
        self.camera_panel.adjustSize()
        scrollbar = self._controls.verticalScrollBar().sizeHint().width()
        self._controls.setMinimumWidth(self.camera_panel.sizeHint().width() + scrollbar + 4)

    # ------------------------------------------------------------- files
    def open_scene_dialog(self) -> None:
        path, _ = QFileDialog.getOpenFileName(self, "Open scene", "", "Scene files (*.json)")
        if path:
            self.open_scene(path)

    def open_scene(self, path) -> bool:
        """Load a scene file; on any problem show them all and keep the current scene."""
        try:
            scene = scene_file.load(path, read_mesh=read_mesh)
        except scene_file.SceneFileError as exc:
            QMessageBox.critical(self, "Cannot open scene", f"{Path(path).name}:\n\n{exc}")
            return False
        self.scene_path = Path(path)
        self.setWindowTitle(f"Render Explorer — {self.scene_path.name}")
        self.model.set_scene(scene)
        return True

    def save_scene_dialog(self) -> None:
        path, _ = QFileDialog.getSaveFileName(self, "Save scene", "scene.json",
                                              "Scene files (*.json)")
        if path:
            try:
                scene_file.save(self.model.scene, path)
            except OSError as exc:
                QMessageBox.critical(self, "Cannot save scene", f"{path}:\n\n{exc}")

    def reset_scene(self) -> None:
        self.load_preset("lecture", presets.lecture_scene)

    def load_preset(self, key: str, build) -> None:
        self.scene_path = None
        self.setWindowTitle(f"Render Explorer — example: {key}")
        self.model.set_scene(build())

    # ------------------------------------------------------------ render
    @property
    def current_tab(self) -> int:
        return self.tab_widget.currentIndex()

    def _scene_edited(self, *_):
        """The scene or observer changed: every tab is stale; redraw the visible one now."""
        self._stale = set(range(len(self.tabs)))
        self._render_current()
        if self.ray_tree is not None:  # the picked pixel now sees something else
            self.pick_ray_tree(*self.ray_tree[:2])
        self._show_accel_overlays()

    def _rerender(self, index: int) -> None:
        self._stale.add(index)
        if index == self.current_tab:
            self._render_current()

    def _tab_shown(self, index: int) -> None:
        for name in ("polygon", "clipped", "ray-tree", "spheres", "grid", "walk"):
            self.scene_view.set_overlay(name, [])
        if index == 0:
            self._show_accel_overlays()
            if self.ray_tree is not None:
                self._show_ray_tree(self.ray_tree)
        if index in self._stale:
            self._render_current()

    def _render_current(self, *_):
        index = self.current_tab
        self._stale.discard(index)
        tab = self.tabs[index]
        self.progress.setFormat(f"{tab.title}: rendering… %p%")
        self.progress.setValue(0)
        self.renderers[index].submit(tab.job(self.model.scene))
        self.cancel_button.setEnabled(True)

    def cancel_render(self) -> None:
        """Stop the visible tab's render; what was drawn so far stays on screen."""
        self.renderers[self.current_tab].cancel()
        self._stale.add(self.current_tab)
        self.cancel_button.setEnabled(False)
        self.progress.setFormat(f"{self.tabs[self.current_tab].title}: cancelled at %p% (F5 renders again)")

    def _render_progress(self, tab, percent, partial):
        if tab is self.tabs[self.current_tab]:
            self.progress.setValue(percent)
        if partial is not None:
            tab.show_progress(percent, partial)

    def _render_finished(self, tab, result):
        self.last_result = result
        caption = tab.show(result)
        if tab is self.tabs[self.current_tab]:
            self.cancel_button.setEnabled(False)
            self.progress.setValue(100)
            self.progress.setFormat(f"{tab.title}: done")
            self.status_caption.setText(caption)

    def _render_failed(self, message: str):
        self.cancel_button.setEnabled(False)
        self.progress.setFormat("render failed")
        QMessageBox.warning(self, "Render failed", message)

    # ------------------------------------------------------- image order
    def pick_ray_tree(self, x: int, y: int) -> None:
        """Trace pixel (x, y) again with every ray kept (in the background)."""
        scene, settings = self.model.scene, self.tabs[0].widget.settings
        cam = scene.camera
        if not (0 <= x < cam.width and 0 <= y < cam.height):
            self.ray_tree = None
            self.scene_view.set_overlay("ray-tree", [])
            return
        self._tree_renderer.submit(lambda cancelled, progress: (x, y, trace_pixel(scene, x, y, settings)))

    def _show_ray_tree(self, picked) -> None:
        self.ray_tree = picked
        x, y, root = picked
        if self.current_tab != 0:
            return
        self.tabs[0].widget.show_tree(x, y, root)
        low, high = three_views.scene_bounds(self.model.scene)
        miss_length = 0.6 * float(np.linalg.norm(high - low)) + 1.0
        self.scene_view.set_overlay("ray-tree", raytree_view.ray_tree_parts(root, miss_length))
        self._show_accel_overlays()

    def _show_accel_overlays(self) -> None:
        """Bounding spheres, grid cells and the picked ray's cells, as the panel's switches say."""
        panel, scene = self.tabs[0].widget, self.model.scene
        if self.current_tab != 0:
            return
        spheres = []
        if panel.show_spheres.isChecked():
            spheres = [(pv.Sphere(radius=b.radius, center=b.center, theta_resolution=24,
                                  phi_resolution=16).extract_all_edges(),
                        {"color": "#9fd3ff", "opacity": 0.35, "line_width": 1})
                       for b in bounding_spheres(scene) if not b.exact]
        self.scene_view.set_overlay("spheres", spheres)
        want_walk = panel.show_walk.isChecked() and self.ray_tree is not None
        need_grid = panel.show_grid.isChecked() or want_walk
        grid = trace_scene(scene).geometry.accel("grid")[0] if need_grid else None
        cells = []
        if panel.show_grid.isChecked():
            cells = [(vtk_convert.boxes_polydata(grid.cell_boxes(grid.occupied_cells())),
                      {"color": "#b0b0b0", "opacity": 0.25, "line_width": 1})]
        self.scene_view.set_overlay("grid", cells)
        walk = []
        if want_walk:
            root = self.ray_tree[2]
            t_max = root.t if root.t is not None else np.inf
            walked = cells_on_ray(grid, root.origin, root.direction, root.t_min, t_max)
            if len(walked):
                walk = [(vtk_convert.boxes_polydata(grid.cell_boxes(walked)),
                         {"color": KIND_COLORS["primary"], "line_width": 3})]
        self.scene_view.set_overlay("walk", walk)

    # ------------------------------------------------------- object order
    def _show_clipped(self, polygons) -> None:
        """Outline, in the 3D pane, the polygons the frustum's planes cut."""
        parts = [(vtk_convert.polygon_polydata(p).extract_all_edges(),
                  {"color": "#7cff6b", "line_width": 3}) for p in polygons]
        self.scene_view.set_overlay("clipped", parts)

    def _show_polygon(self, vertices) -> None:
        """Highlight the polygon the object-order scrubber is at, in the 3D pane."""
        if vertices is None:
            self.scene_view.set_overlay("polygon", [])
            return
        poly = vtk_convert.polygon_polydata(vertices)
        self.scene_view.set_overlay("polygon", [
            (poly, {"color": "#ff2bd6", "opacity": 0.8}),
            (poly.extract_all_edges(), {"color": "#ff2bd6", "line_width": 4}),
        ])

    def closeEvent(self, event):
        for renderer in self.renderers:
            renderer.cancel()
        self.scene_view.close()
        super().closeEvent(event)


def run(scene_path: str | None = None) -> int:
    """Open the window on ``scene_path`` (or the lecture scene); returns the exit status."""
    scene = presets.lecture_scene()
    if scene_path is not None:
        try:
            scene = scene_file.load(scene_path, read_mesh=read_mesh)
        except scene_file.SceneFileError as exc:
            print(f"python -m app: error: {exc}", file=sys.stderr)
            return 2
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("Render Explorer")
    window = MainWindow(scene)
    window.show()
    status = app.exec()
    for renderer in window.renderers:
        renderer.cancel()
    QThreadPool.globalInstance().waitForDone()
    return status
