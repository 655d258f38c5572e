"""The main window: builds the panes and connects them to the one model.

No algorithms and no drawing live here.  The model (:class:`app.window.state.SceneModel`)
holds the window's state; panels write to it and views follow its signals.
When each tab renders (only the visible one; previews while the observer
moves) is decided by :class:`app.renders.RenderSchedule`.

Tabs are registered in :data:`app.window.tabs.TABS` and found by name,
``window.tab("image order")``.
"""

from __future__ import annotations

import os
import sys
from pathlib import Path

from PySide6.QtCore import Qt, QThreadPool, QTimer, Signal
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import (
    QApplication,
    QDialog,
    QDockWidget,
    QHBoxLayout,
    QLabel,
    QMainWindow,
    QMessageBox,
    QPushButton,
    QScrollArea,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from app import render_budget
from app.export.export_menu import ExportMenu
from app.lessons.asked_scene import AskedScene
from app.lessons.exercise_jobs import ExerciseJobs
from app.lessons.fact_check import LessonFactCheck
from app.lessons.recorder import LessonRecorder
from app.lessons.runner import FACE_SIDE_OVERLAY, LESSON_OVERLAY, LessonRunner
from app.lessons.withheld_answers import WithheldAnswers
from app.process import gui_thread_collection
from app.process.lock_turns import hand_over_often
from app.process.long_lived import set_aside_once_loaded
from app.renders import Renderer, RenderSchedule
from app.window import session
from app.window.background_compile import BackgroundCompile
from app.window.close_on_signal import CloseOnSignal
from app.window.dropped_files import DroppedFiles
from app.window.first_frame import AfterFirstFrame
from app.window.scene_editor import SceneEditor
from app.window.state import SceneModel
from app.window.tabs import TABS
from app.window.window_layout import LEFT_SHARE, dock_action, fit_window, keys_only_in_front, tabbed_dock
from core import presets
from core.files import scene_file
from core.files.mesh_files import read_mesh
from core.image_order.ray_tree import trace_pixel
from core.lessons.exercises import named_pane
from core.presets_trace import PRESETS_TRACE
from core.scene import Scene
from views.dock_title import DockTitle
from views.file_dialogs import ask_open, ask_save
from views.images.image_view import PICTURE_GESTURES, PICTURE_KEYS, ImageView
from views.keyboard_focus import follow_focus
from views.on_screen import KeepWindowsOnScreen
from views.panels.camera_panel import CameraPanel
from views.panels.exercise_panel import ExercisePanel, ExerciseProgress
from views.panels.lesson_panel import LessonPanel
from views.presentation import Presentation
from views.recent_files import LESSON, SCENE, RecentFiles
from views.scene3d.deferred_scene_view import DeferredSceneView
from views.scene3d.observer_keys import MOUSE_GESTURES, OBSERVER_KEYS, EditorsKeepTheirKeys
from views.scene3d.scene_overlays import SCENE_OVERLAYS, SceneOverlays
from views.text import math_view
from views.text.elided_label import ElidedLabel, ElidedProgressBar
from views.text.tab_titles import TitlesThatFit
from views.text.table_dialog import Section, table_dialog
from views.user_settings import user_settings


class MainWindow(QMainWindow):
    """Render Explorer's window: 3D scene with the observer, and what the observer sees.

    Signals
    -------
    image_shown(str title, bool preview) : a tab showed a new image (a preview or the full one).
    full_image_shown(str title) : a tab showed the full render of the current scene.
    scene_file_done(str path, bool opened) : :meth:`open_scene` is done with the file ``path``: it is
        the scene shown, or not (a problem with the file, or the user kept unsaved changes).
    """

    image_shown = Signal(str, bool)
    full_image_shown = Signal(str)
    scene_file_done = Signal(str, bool)

    def __init__(self, scene: Scene, memory_limit: int | None = None):
        super().__init__()
        gui_thread_collection.collect_on_gui_thread(self)  # before any thread starts
        self.setWindowTitle("Render Explorer")
        self.model = SceneModel(scene, self, memory_limit)
        self.scene_path: Path | None = None
        self.scene_view = DeferredSceneView(self.model)  # VTK loads once the window is on screen
        self.overlays = SceneOverlays(self.model, self.scene_view)
        self.camera_panel = CameraPanel(self.model)
        self.tab_widget = QTabWidget()
        self.tab_widget.setElideMode(Qt.TextElideMode.ElideRight)  # every tab stays in view, however narrow
        self.tab_widget.setUsesScrollButtons(False)
        self._tab_titles = TitlesThatFit(self.tab_widget, {})  # short ones before elided ones
        self.tabs: list = []
        self.renders = RenderSchedule(self.model, self)
        self.progress = ElidedProgressBar()
        self.progress.setRange(0, 100)
        self.progress.setTextVisible(True)
        self.status_caption = QLabel()
        self.status_caption.setWordWrap(True)
        for cls in TABS:
            self.add_tab(cls(self.model))

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
        scene_layout.setContentsMargins(2, 2, 2, 2)
        scene_hint = ElidedLabel("Drag the camera or the orange target to move them; "
                                 "drag elsewhere to turn the view")
        scene_layout.addWidget(self.scene_view, 1)
        scene_layout.addWidget(scene_hint)
        # Above the controls and lessons, beside the tabs: the tabs' images get the window's width.
        self.scene_pane = QDockWidget("The scene: observer, frustum, screen", self)
        self.scene_pane.setObjectName("scene")
        self.scene_pane.setFeatures(QDockWidget.DockWidgetFeature.DockWidgetMovable)
        self.scene_pane.setWidget(scene_pane)
        DockTitle(self.scene_pane)
        self.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, self.scene_pane)
        self.setCentralWidget(right)

        dock = self.controls_dock = QDockWidget("Controls", self)
        dock.setObjectName("controls")
        dock.setFeatures(QDockWidget.DockWidgetFeature.DockWidgetMovable)
        dock.setTitleBarWidget(QWidget())  # the group boxes carry the titles
        self._controls = QScrollArea()
        self._controls.setWidgetResizable(True)
        self._controls.setWidget(self.camera_panel)
        dock.setWidget(self._controls)
        self._fit_controls()
        self.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, dock)
        self.splitDockWidget(self.scene_pane, dock, Qt.Orientation.Vertical)
        keys_only_in_front(dock)  # the first of the tabs beside it (tabbed_dock does the others)
        # The panel opens on the first lesson without applying it: the scene stays
        # the one given until the user picks a step.
        self.lesson_panel = LessonPanel()
        self.lessons = LessonRunner(self)
        # Beside the controls, as a second tab of the same dock area: the image panes keep the width.
        self.lesson_dock = tabbed_dock(self, "Lessons", "lessons", self.lesson_panel, dock)
        self.exercise_jobs = ExerciseJobs(self, lambda why: self.statusBar().showMessage(
            f"The exercise could not be checked: {why}", 10000))
        self.exercise_panel = ExercisePanel(ExerciseProgress(user_settings()), run=self.exercise_jobs)
        self.exercise_dock = tabbed_dock(self, "Exercises", "exercises", self.exercise_panel, dock)
        self.lesson_dock.raise_()
        self._keyed_actions: list[QAction] = []
        self._editor_keys = follow_focus(EditorsKeepTheirKeys(self))
        self._on_screen = KeepWindowsOnScreen(self)  # the window and its dialogs, frames and all
        self._on_screen.watch(self)
        # After the editors' filter, so that PageUp/PageDown reach the lessons first, from anywhere.
        self.presentation = Presentation(self, self.lesson_panel)
        self._build_menus()
        self.editor = SceneEditor(self)
        self._keyed_actions += self.editor.keyed_actions
        self.lesson_panel.step_selected.connect(self.apply_lesson_step)
        self._wire_exercises()
        self.withheld_answers = WithheldAnswers(self)
        self.asked_scene = AskedScene(self)
        self.fact_check = LessonFactCheck(self)  # File → Open lesson: are the new lesson's facts true?
        self.lesson_panel.lesson_opened.connect(self.fact_check.check)
        self.lesson_panel.lesson_opened.connect(
            lambda lesson: lesson.path is not None and self.recent_files.add(LESSON, lesson.path))
        self.dropped_files = DroppedFiles(self)
        self.presentation.presenting_changed.connect(self._presenting_changed)
        self.presentation.scale_changed.connect(self._scale_changed)
        self.scene_pane.visibilityChanged.connect(lambda shown: shown and self._refit())

        self.model.camera_refused.connect(
            lambda why: self.statusBar().showMessage(f"Observer not moved — {why}", 6000))
        self.model.trace_settings_changed.connect(
            lambda _: self.renders.settings_changed(self.tab("image order")))
        self.model.raster_settings_changed.connect(
            lambda _: self.renders.settings_changed(self.tab("object order")))
        self.renders.status_changed.connect(self._show_status)
        self.renders.image_shown.connect(self.image_shown)
        self.renders.full_image_shown.connect(self.full_image_shown)
        self.renders.image_shown.connect(self.scene_view.build_soon)  # the first image before VTK
        self.renders.image_shown.connect(lambda *_: math_view.load_typesetting_soon())  # and mathtext
        self.renders.warned.connect(lambda warning: self.statusBar().showMessage(warning, 10000))
        self.renders.refused.connect(lambda refusal: self.statusBar().showMessage(refusal, 10000))
        self.renders.rested.connect(self._observer_rested)
        self.model.ray_pixel_changed.connect(self._ray_pixel_changed)
        self.model.scene_changed.connect(lambda _: self.model.scene_was_edited or self.show_pictures_whole())
        self.tab_widget.currentChanged.connect(self._tab_shown)
        self.ray_tree = None
        self._tree_renderer = Renderer(self)
        self._tree_renderer.finished.connect(self._show_ray_tree)
        self._tree_renderer.failed.connect(lambda message: self.statusBar().showMessage(message, 6000))
        self._scene_reader = Renderer(self)  # a scene file's meshes may take seconds to read
        self._opening = ""  # the scene file it reads last
        self._scene_reader.finished.connect(self._scene_read)
        self._scene_reader.failed.connect(self._scene_read_failed)
        object_order = self.tab("object order").widget
        object_order.polygon_shown.connect(self.overlays.show_polygon)
        object_order.clipped_shown.connect(self.overlays.show_clipped)

        self.renders.hold()  # the first render starts once the window is on screen
        self.background_compile = BackgroundCompile()
        self._compile_watch = QTimer(self, interval=1000, timeout=self._say_background_compile)
        QApplication.instance().aboutToQuit.connect(self._quitting)
        AfterFirstFrame(self.tab_widget, self._first_frame_shown)
        self._tab_shown()
        available = self.screen().availableGeometry()
        self.resize(min(1400, available.width()), min(860, available.height()))

    # ------------------------------------------------------------------ tabs
    def add_tab(self, tab) -> None:
        """Show ``tab`` (see :mod:`app.window.tabs` for what a tab provides) as the last tab."""
        self.tabs.append(tab)
        self.tab_widget.addTab(tab.widget, tab.title)
        self._tab_titles.short[tab.title] = getattr(tab, "short_title", tab.title)
        self.renders.add(tab)

    def tab(self, name: str):
        """The tab titled ``name`` (case does not matter)."""
        for tab in self.tabs:
            if tab.title.lower() == name.lower():
                return tab
        raise KeyError(f"no tab named {name!r}; the tabs are {self.tab_titles()}")

    def tab_titles(self) -> list[str]:
        return [tab.title for tab in self.tabs]

    def show_tab(self, name: str) -> None:
        """Bring the tab titled ``name`` to the front (showing it if a lesson had hidden it)."""
        widget = self.tab(name).widget
        self.tab_widget.setTabVisible(self.tab_widget.indexOf(widget), True)
        self.tab_widget.setCurrentWidget(widget)

    def show_all_panes(self) -> None:
        """Every tab and the 3D pane, as before any lesson."""
        self.scene_pane.setVisible(True)
        for i in range(self.tab_widget.count()):
            self.tab_widget.setTabVisible(i, True)

    def visible_panes(self) -> list[str]:
        """The panes shown, by their lesson names ("scene 3D" and the tab titles, lower case)."""
        shown = ["scene 3D"] if self.scene_pane.isVisible() else []
        return shown + [t.title.lower() for t in self.tabs
                        if self.tab_widget.isTabVisible(self.tab_widget.indexOf(t.widget))]

    # --------------------------------------------------------------- lessons
    def apply_lesson_step(self, step) -> None:
        """Show a :class:`core.lessons.lesson_file.LessonStep`; see :mod:`app.lessons.runner`."""
        if self.editor.may_replace_scene():
            self.lessons.apply(step)
            self._refit()  # the step's words may need another share of the left column

    def _wire_exercises(self) -> None:
        """The exercises follow the lesson; clicks in the images answer pixel exercises; "show me"
        shows the exercise's step (and pixel); progress shows in the lesson list."""
        panel, exercises = self.lesson_panel, self.exercise_panel
        panel.step_selected.connect(lambda _step: exercises.set_lesson(panel.current_lesson()))
        exercises.set_lesson(panel.current_lesson())  # the lesson the panel shows as the window opens
        object_order = self.tab("object order").widget
        for image in (self.tab("image order").widget.image, object_order.image, object_order.depth.image):
            image.pixel_chosen.connect(exercises.click)  # a click, or Enter

        def show_me(step: int, pixel) -> None:
            panel.select(panel.step_index()[0], step)
            shown = f"step {step + 1}, whose scene it asks about"
            if pixel is not None:
                self.model.set_ray_pixel(tuple(pixel))
                self.model.set_buffer_pixel(tuple(pixel))
                shown += f", with pixel ({pixel[0]}, {pixel[1]}) picked"
                pane = named_pane(exercises.exercise())  # the pane that reads that pixel
                if pane is not None:
                    self.show_tab(pane.capitalize())
                    shown += f" in the {pane.capitalize()} tab"
            # In place of the step's own "Look at ...", which may name another object than the question.
            self.statusBar().showMessage(f"Exercise {exercises.index + 1}: showing {shown}", 15000)

        exercises.show_me.connect(show_me)
        self.presentation.presenting_changed.connect(exercises.set_room)
        exercises.waiting.connect(lambda _: self._refit())  # another question, its answers shown or
        exercises.answers_hidden.connect(lambda _: self._refit())  # hidden: the room they need
        self.exercise_dock.visibilityChanged.connect(lambda shown: shown and self._refit())

        def progressed(lesson_id: str) -> None:
            for k, lesson in enumerate(panel.lessons()):
                if lesson.id == lesson_id:
                    panel.set_note(k, exercises.progress.summary(lesson))

        exercises.progressed.connect(progressed)
        for lesson in panel.lessons():
            progressed(lesson.id)

    def _presenting_changed(self, presenting: bool) -> None:
        # Esc leaves full screen while presenting; one key, one meaning.
        self.cancel_button.setShortcut(QKeySequence() if presenting else QKeySequence("Esc"))
        self._refit()

    def _scale_changed(self, scale: float) -> None:
        # The formulas follow the window's font, which the scale enlarged already; the 3D pane does not.
        self.scene_view.set_line_scale(scale)
        self._refit()

    def _refit(self) -> None:
        """Share the room again once the new text size or screen reached every widget."""
        QTimer.singleShot(0, self, self._fit)  # (not after the window is gone)

    def _fit(self) -> None:
        self._fit_controls()
        self._share_room()

    def resizeEvent(self, event):
        super().resizeEvent(event)
        self._share_room()

    def _share_room(self) -> None:
        fit_window(self, self.presentation.scale())
        self.tab("image order").widget.tree.widen_soon()  # the window may be wider now

    @property
    def current(self):
        """The visible tab."""
        return self.tabs[self.tab_widget.currentIndex()]

    def show_pictures_whole(self) -> None:
        """Every picture shown whole, not zoomed in: a new scene (a file, an example) or a lesson step,
        whose pictures may have the pixel count of the last ones and keep their zoom otherwise."""
        for view in self.findChildren(ImageView):
            view.set_zoom(1.0, None)

    def frame_pictures(self) -> None:
        """Zoom every picture in view onto what it singles out: a step's highlighted polygon, else
        the picked pixel (:meth:`ImageView.frame_singled_out`), large enough for a lecture hall.
        Pressed again, nothing having moved, they are shown whole."""
        views = [view for view in self.findChildren(ImageView) if view.isVisible()]
        before = [(view.zoom, view.focus) for view in views]
        framed = [view.frame_singled_out() for view in views]
        if not any(framed):
            self.statusBar().showMessage("Nothing to zoom onto: no highlighted polygon or picked pixel", 8000)
        elif [(view.zoom, view.focus) for view in views] == before:
            for view in views:
                view.set_zoom(1.0, None)

    def showing_full(self, name: str) -> bool:
        """Whether tab ``name`` shows the full render of the current scene and settings, and the
        pictures its panel makes of that render on a worker (the object-order step's) are painted."""
        tab = self.tab(name)
        return self.renders.showing_full(tab) and not getattr(tab.widget, "pending", False)

    # ----------------------------------------------------------------- menus
    def _action(self, menu, text, slot, shortcut=None, tip=""):
        """A menu entry; ``shortcut`` a key, or a list of keys that do the same."""
        action = QAction(text, self)
        if shortcut:
            keys = shortcut if isinstance(shortcut, list) else [shortcut]
            action.setShortcuts([QKeySequence(k) for k in keys])
            self._keyed_actions.append(action)
        action.setStatusTip(tip)
        action.setToolTip(tip)
        action.triggered.connect(slot)
        menu.addAction(action)
        return action

    def _build_menus(self):
        file_menu = self.menuBar().addMenu("&File")
        self._action(file_menu, "&Open scene…", self.open_scene_dialog, QKeySequence.StandardKey.Open,
                     "Open a scene JSON file")
        self._action(file_menu, "Save scene &as…", self.save_scene_dialog,
                     QKeySequence.StandardKey.SaveAs, "Save the scene and observer as JSON")
        self._action(file_menu, "&Lecture scene", self.reset_scene, "Ctrl+L",
                     "Back to the lecture's cube and cone on a plane")
        self._action(file_menu, "Open lesso&n…", lambda: self.lesson_panel.open_lesson_file(),
                     tip="Open a lesson JSON file and start it")
        self.recent_files = RecentFiles(file_menu.addMenu("Open &recent"), self)
        self.recent_files.chosen.connect(self._open_recent)
        examples = file_menu.addMenu("&Examples")
        for group in (presets.PRESETS, PRESETS_TRACE):
            for key, (title, build) in group.items():
                self._action(examples, title, lambda _=False, b=build, k=key: self.load_preset(k, b))
            examples.addSeparator()
        self.exports = ExportMenu(self, file_menu)
        file_menu.addSeparator()
        self._action(file_menu, "&Quit", self.close, QKeySequence.StandardKey.Quit)
        observer = self.menuBar().addMenu("&Observer")
        for key, text, move in OBSERVER_KEYS:
            self._action(observer, text,
                         lambda _=False, m=move: self.model.set_camera(m(self.model.camera)), key)
        view = self.menuBar().addMenu("&View")
        self._action(view, "Larger text (lecture hall)", lambda: self.scale_text(1.25),
                     [QKeySequence.StandardKey.ZoomIn, "Ctrl+="])  # Ctrl+= : the + key without Shift
        self._action(view, "Smaller text", lambda: self.scale_text(0.8),
                     QKeySequence.StandardKey.ZoomOut)
        self._action(view, "Re-render", self.rerender, "F5")
        self._action(view, "Zoom the pictures to the highlight", self.frame_pictures, "Z",
                     "Every picture in view zoomed onto its highlighted polygon, or its picked pixel; "
                     "again: whole")
        for i, tab in enumerate(self.tabs):
            self._action(view, tab.title, lambda _=False, t=tab.title: self.show_tab(t), f"Ctrl+{i + 1}")
        self._action(view, "Show all panes", self.show_all_panes,
                     tip="Every tab and the 3D pane again, after a lesson showed only some")
        view.addSeparator()
        # The exercises' dock may be closed by its title's button: this brings it back.
        for dock, text, key in ((self.lesson_dock, "Lessons", "Ctrl+Shift+L"),
                                (self.exercise_dock, "Exercises", "Ctrl+Shift+X")):
            shown = dock_action(dock, text, key)
            view.addAction(shown)
            self._keyed_actions.append(shown)
        acts = self.presentation.actions
        for key in ("present", "leave", "blank", "contrast", "presenter"):
            view.addAction(acts[key])
            if not acts[key].shortcut().isEmpty():
                self._keyed_actions.append(acts[key])
        sizes = view.addMenu("Text size")
        for key in ("scale 1", "scale 1.5", "scale 2"):
            sizes.addAction(acts[key])
        lessons_menu = self.menuBar().addMenu("&Lessons")
        self.recorder = LessonRecorder(self)
        self._action(lessons_menu, "&Add this view as a step…", self.recorder.ask,
                     tip="Record the scene, observer, panes, settings, step and pixel into a lesson file")
        help_menu = self.menuBar().addMenu("&Help")
        self._action(help_menu, "&Keys and mouse", self.show_keys, tip="Every key and mouse gesture")

    def keys_sections(self) -> list[Section]:
        """Every keyboard shortcut and mouse gesture, in sections of ``(keys, what they do)``."""
        native = QKeySequence.SequenceFormat.NativeText
        keys = [(" or ".join(k.toString(native) for k in a.shortcuts()), a.text().replace("&", ""))
                for a in self._keyed_actions]
        keys += [("PageDown", "Next lesson step (from anywhere)"),
                 ("PageUp", "Previous lesson step (from anywhere)"),
                 ("Esc", "Cancel the render in progress (while presenting: leave full screen)"),
                 *PICTURE_KEYS]
        return [("Keys (a focused number box or picture keeps the arrow keys, a focused picture also +, - "
                 "and 0):", keys),
                ("Mouse in the 3D pane:", list(MOUSE_GESTURES)),
                ("Mouse over a picture:", list(PICTURE_GESTURES))]

    def show_keys(self) -> QDialog:
        """Show every key and mouse gesture (scrolled on a small screen); returns the dialog."""
        dialog = table_dialog(self, "Keys and mouse", self.keys_sections())
        dialog.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
        dialog.show()
        return dialog

    def scale_text(self, factor: float) -> None:
        """Make the normal text size ``factor`` times larger (presentation's scale applies on top)."""
        self.presentation.scale_normal_text(factor)
        QTimer.singleShot(0, self, self._fit_controls)  # after the new font reached every widget

    def _fit_controls(self) -> None:
        """Keep the whole control panel visible at any text size (scrolling sideways on a small screen)."""
        self.camera_panel.adjustSize()
        scrollbar = self._controls.verticalScrollBar().sizeHint().width()
        most = round(self.screen().availableGeometry().width() * LEFT_SHARE[max(LEFT_SHARE)])
        self._controls.setMinimumWidth(min(most, self.camera_panel.minimumSizeHint().width() + scrollbar + 4))

    # ------------------------------------------------------------- files
    def open_scene_dialog(self) -> None:
        path = ask_open(self, "Open scene", "Scene files (*.json)")
        if path:
            self.open_scene(path)

    def open_scene(self, path) -> None:
        """Read the scene file ``path`` off the GUI thread (the meshes it names may take seconds), then
        show it; on any problem show them all and keep the current scene (``scene_file_done`` says which).
        A file opened meanwhile takes its place."""
        path = self._opening = str(path)
        self.statusBar().showMessage(f"Opening {Path(path).name}…")

        def job(cancelled, progress):
            try:
                return path, scene_file.load(path, read_mesh=read_mesh)
            except scene_file.SceneFileError as exc:
                return path, exc

        self._scene_reader.submit(job)

    def _scene_read(self, result) -> None:
        path, scene = result
        if self.statusBar().currentMessage().startswith("Opening "):
            self.statusBar().clearMessage()
        if isinstance(scene, scene_file.SceneFileError):
            # The file's name once, with its problems; then its folder (a full path wraps badly).
            QMessageBox.critical(self, "Cannot open scene",
                                 f"{scene.headed(Path(path).name)}\n\nin {Path(path).resolve().parent}")
            self.scene_file_done.emit(path, False)
            return
        if not self.editor.may_replace_scene():
            self.scene_file_done.emit(path, False)
            return
        self.scene_path = Path(path)
        self.setWindowTitle(f"Render Explorer — {self.scene_path.name}")
        self.model.set_scene(scene)
        self.editor.stack.clear()  # even a scene equal to the one shown starts with nothing to undo
        self.leave_lesson_step(f"The window shows {self.scene_path.name} now.")
        self.recent_files.add(SCENE, path)
        self.explain_if_too_large(self.scene_path.name)
        self.scene_file_done.emit(path, True)

    def _scene_read_failed(self, message: str) -> None:
        """Reading a scene file failed other than by its contents (say, memory ran out)."""
        self.statusBar().clearMessage()
        QMessageBox.critical(self, "Cannot open scene", f"{Path(self._opening).name}:\n\n{message}")
        self.scene_file_done.emit(self._opening, False)

    def _open_recent(self, kind: str, path: str) -> None:
        if kind == LESSON:
            self.lesson_panel.open_lesson_file(path)
        else:
            self.open_scene(path)

    def explain_if_too_large(self, name: str) -> None:
        """Say in a dialog why tabs will not render the scene just opened (from file ``name``), if so."""
        refused = render_budget.refusals(self.tabs, self.model.scene, self.model.memory_limit)
        if not refused:
            return
        first = refused.get(self.current.title, next(iter(refused.values())))
        box = QMessageBox(QMessageBox.Icon.Warning, "Scene too large to render", f"{name}:\n\n{first}",
                          parent=self)
        others = [title for title, why in refused.items() if why is not first]
        box.setInformativeText((f"Too large for {', '.join(others)} as well. " if others else "")
                               + "The scene is open: the tabs render it once it is small enough.")
        box.setAttribute(Qt.WidgetAttribute.WA_DeleteOnClose)
        box.open()  # the window stays responsive behind it

    def save_scene_dialog(self) -> None:
        path, _ = ask_save(self, "Save scene", "scene.json", "Scene files (*.json)") or ("", "")
        if path:
            self.editor.save_to(path)

    def reset_scene(self) -> None:
        self.load_preset("lecture", presets.lecture_scene)

    def load_preset(self, key: str, build) -> None:
        if not self.editor.may_replace_scene():
            return
        self.scene_path = None
        self.setWindowTitle(f"Render Explorer — example: {key}")
        self.model.set_scene(build())
        self.editor.stack.clear()  # even a scene equal to the one shown starts with nothing to undo
        self.leave_lesson_step(f"The window shows the example {key!r} now.")

    def leave_lesson_step(self, why: str) -> None:
        """Another scene replaced the step's: its words give way to ``why`` and its marks go."""
        self.lesson_panel.leave_step(why)
        self.lessons.leave()
        self.withheld_answers.update()  # the scene shown is no longer the one the exercises ask about

    # ------------------------------------------------------------ render
    @property
    def last_result(self):
        """The result a tab showed last (preview or full)."""
        return self.renders.last_result

    def rerender(self) -> None:
        """Render the visible tab again in full (F5)."""
        self.renders.rerender()

    def cancel_render(self) -> None:
        """Stop the visible tab's render; what was drawn so far stays on screen."""
        self.renders.cancel()

    def show_overlays(self) -> None:
        """Show the 3D overlays of the visible tab, of the scene and of the lesson step (less what an
        exercise waiting for its answer withholds)."""
        withheld = self.withheld_answers.overlays()
        shown = (*self.current.overlays, *SCENE_OVERLAYS, LESSON_OVERLAY, FACE_SIDE_OVERLAY)
        self.scene_view.show_overlays_only([name for name in shown if name not in withheld])

    def _tab_shown(self, *_) -> None:
        tab = self.current
        self.show_overlays()
        self.renders.show_tab(tab)
        self._show_status(tab)

    def _first_frame_shown(self) -> None:
        self.renders.release()
        self.background_compile.start()
        self._compile_watch.start()

    def _say_background_compile(self) -> None:
        """While the kernels compile in the background, the status bar says so."""
        if self.background_compile.running:
            self.statusBar().showMessage(BACKGROUND_COMPILE, 2000)
        elif self.background_compile.checked.is_set():
            self._compile_watch.stop()
            if self.statusBar().currentMessage() == BACKGROUND_COMPILE:
                self.statusBar().showMessage("The renderers' kernels are compiled: they load at once "
                                             "from now on", 4000)

    def _show_status(self, tab) -> None:
        if tab is not self.current:
            return
        percent, text, caption = self.renders.status(tab)
        if percent != self.progress.value():
            # QProgressBar.setValue repaints at once, which composes the whole window
            # (the 3D pane is an OpenGL widget); paint it with the next frame instead.
            self.progress.setUpdatesEnabled(False)
            self.progress.setValue(percent)
            self.progress.setUpdatesEnabled(True)
        self.progress.setFormat(text)
        self.status_caption.setText(caption)
        self.cancel_button.setEnabled(self.renders.busy(tab))

    # ------------------------------------------------------- image order
    def pick_ray_tree(self, x: int, y: int) -> None:
        """Pick pixel (x, y) of the traced image: its ray tree is traced with every ray kept."""
        self.model.set_ray_pixel((x, y))

    def _observer_rested(self) -> None:
        if self.model.ray_pixel is not None:  # the picked pixel now sees something else
            self._trace_picked(self.model.ray_pixel)

    def _ray_pixel_changed(self, pixel) -> None:
        if pixel is None:
            self.ray_tree = None
            self._tree_renderer.cancel()
            self.overlays.show_ray_tree(None)
        else:
            self._trace_picked(pixel)

    def _trace_picked(self, pixel) -> None:
        """Trace the picked pixel again with every ray kept (in the background)."""
        x, y = pixel
        scene, settings = self.model.scene, self.model.trace_settings
        self._tree_renderer.submit(
            lambda cancelled, progress: (x, y, trace_pixel(scene, x, y, settings), scene))

    def _show_ray_tree(self, picked) -> None:
        x, y, root, scene = picked
        if (x, y) != self.model.ray_pixel:
            return
        self.ray_tree = (x, y, root)
        self.tab("image order").widget.show_tree(x, y, root, scene)  # the tree and its worked math
        self.overlays.show_ray_tree(root)

    def _quitting(self) -> None:
        """The application is quitting, with or without this window closed: stop what runs on other
        threads that the interpreter's shutdown must not meet."""
        self.background_compile.stop()
        math_view.stop_typesetting(EXIT_WAIT_MS)

    def closeEvent(self, event):
        if not self.editor.may_replace_scene():
            event.ignore()
            return
        self._editor_keys.stop()
        self._on_screen.stop()
        self.presentation.clicker.remove()
        self.renders.stop()
        self.background_compile.stop()
        for tab in self.tabs:
            getattr(tab, "shutdown", lambda: None)()
        self._tree_renderer.cancel()
        self.scene_view.close()
        super().closeEvent(event)


EXIT_WAIT_MS = 3000
"""How long a closing window waits for its render threads before it ends the process regardless."""
BACKGROUND_COMPILE = ("Compiling the renderers' kernels in the background (once per machine and version of "
                      "the code)…")


def run(scene_path: str | None = None, memory_limit: int | None = None) -> int:
    """Open the window on ``scene_path`` (or the lecture scene); returns the exit status.

    ``memory_limit``: renders estimated to need more bytes are refused (default: half of
    the memory available).
    """
    scene = presets.lecture_scene()
    if scene_path is not None:
        try:
            scene = scene_file.load(scene_path, read_mesh=read_mesh)
        except scene_file.SceneFileError as exc:
            print(f"python -m app: error: {exc}", file=sys.stderr)
            return 2
    app = QApplication.instance() or QApplication(sys.argv[:1])
    app.setApplicationName("Render Explorer")
    window = MainWindow(scene, memory_limit)
    if scene_path is None:
        session.restore(window)
    else:
        window.scene_path = Path(scene_path)
        window.setWindowTitle(f"Render Explorer — {window.scene_path.name}")
        window.recent_files.add(SCENE, scene_path)
    window.show()
    closer = CloseOnSignal(window)
    set_aside_once_loaded(window)
    hand_over_often()
    if scene_path is not None:
        window.explain_if_too_large(Path(scene_path).name)
    status = app.exec()
    closer.release()
    if closer.received is not None:  # closed by a signal (Ctrl+C, SIGTERM, SIGHUP): the status says which
        status = 128 + closer.received
    session.remember(window)
    if not QThreadPool.globalInstance().waitForDone(EXIT_WAIT_MS) or not math_view.stop_typesetting(0):
        # A render thread still inside a kernel compile (minutes on a fresh machine; it cannot be
        # interrupted), or a formula still being typeset: end the process now rather than hang after the
        # window closed, or crash in the interpreter's shutdown. Every file is written whole or not at
        # all, and numba writes each compiled kernel by renaming it into place.
        sys.stdout.flush()
        sys.stderr.flush()
        os._exit(status)
    return status
