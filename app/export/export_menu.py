"""File → Export: save what the window shows as pictures, animations and the picked ray tree.

- *a tab's panes* (one submenu per tab, :mod:`app.export.pane_pictures`): each image
  at its full resolution, the z-buffer with its scale, a grid of panes as one
  picture — PNG or JPEG;
- *the 3D pane*: a screenshot at twice its size on screen (PNG);
- *the z-buffer steps*: one frame per step of the object-order tab's
  pipeline, the step's polygon tinted, with a frame counter (GIF or MP4);
- *an orbit*: the observer walks once around the target, each frame one
  pane's picture (GIF or MP4);
- *the picked pixel's ray tree*: the 3D pane with only the tree drawn (PNG),
  or every ray with its numbers (JSON, :mod:`app.export.ray_tree_json`).

The sheets and frames are those of ``python -m app export``
(:mod:`app.export.picture_sheet`, :mod:`app.export.animation_frames`).  Animations render
off the GUI thread (:class:`app.renders.Renderer`) behind a progress dialog
with Cancel.  A picture is taken on the GUI thread (the 3D pane's from VTK, which
lives there) and encoded and written off it; :meth:`ExportMenu.writing` lists the
files on their way, the status bar says when each is written.  Every file is
written atomically (:mod:`core.files.safe_files`); a failure shows a dialog
naming the file and the cause.  The file dialogs start
in the folder used last, also after a restart (:mod:`views.file_dialogs`).  An
entry with nothing to export is disabled and its tooltip says why.

The ``export_*`` methods take the file's path; the menu asks for it with
:meth:`ExportMenu.ask_path`, the one place a file dialog opens.
"""

from __future__ import annotations

import os
import re
from dataclasses import replace

from PySide6.QtCore import QObject, Qt, QThreadPool, QTimer, Signal
from PySide6.QtGui import QAction
from PySide6.QtWidgets import QApplication, QInputDialog, QMenu, QMessageBox, QProgressDialog

from app import render_budget
from app.export.animation_frames import MAX_FRAMES, orbit_frames, steps_problem, zbuffer_steps
from app.export.image_files import (
    ANIMATION_EXTENSIONS,
    IMAGE_EXTENSIONS,
    OutputError,
    Outputs,
    encode_animation,
    write_image,
)
from app.export.pane_pictures import PanePicture, tab_pictures
from app.export.picture_sheet import four_views
from app.export.ray_tree_json import ray_tree_json
from app.renders import Renderer
from core import budget
from core.files.safe_files import write_atomic
from core.srgb import srgb_to_linear
from views.file_dialogs import ask_save
from views.jobs import JobRun, JobSignals

SCREENSHOT_SCALE = 2
"""The 3D pane is saved at this many times its size on screen."""
FPS = 10
ORBIT_FRAMES = 36
PICTURE_FILTERS = [("PNG image", ".png"), ("JPEG image", ".jpg")]
ANIMATION_FILTERS = [("GIF animation", ".gif"), ("MP4 video", ".mp4")]
NO_PICKED_PIXEL = "No picked pixel: click a pixel of the Image order tab's image first"


def _orbit_pictures(model) -> dict:
    """Pane name -> (what a frame shows, ``picture(scene)`` with the window's current settings)."""
    from core.image_order.ray_tracing import render_trace
    from core.object_order.pipeline import render_raster

    trace = model.trace_settings
    raster = replace(model.raster_settings, record_steps=False)
    return {
        "Image order": ("the traced image", lambda scene: render_trace(scene, trace).color),
        "Object order": ("the image memory", lambda scene: render_raster(scene, raster).color),
        "Four views": ("the four views", four_views),
    }


def _file_name(*words: str) -> str:
    return re.sub(r"[^a-z0-9]+", "-", " ".join(words).lower()).strip("-")


class _CancelledError(Exception):
    """The user pressed Cancel while the frames were being made."""


class ExportMenu(QObject):
    """The File → Export submenu of ``window`` (a :class:`app.window.main_window.MainWindow`).

    Attributes
    ----------
    menu : the QMenu, rebuilt each time it opens, so it lists what can be exported now.
    actions : its entries by path, e.g. ``"Object order/Image memory"``, ``"Ray tree/JSON"``.

    Signals
    -------
    exported(str path) : a file was written.
    """

    exported = Signal(str)

    def __init__(self, window, file_menu):
        super().__init__(window)
        self.window = window
        self.menu = file_menu.addMenu("E&xport")
        self.menu.setToolTipsVisible(True)
        self.menu.aboutToShow.connect(self.refresh)
        self.actions = {}
        self._renderer = Renderer(self)
        self._renderer.progress.connect(self._show_progress)
        self._renderer.finished.connect(self._animation_written)
        self._renderer.failed.connect(lambda message: self._animation_done(None, message))
        self._progress: QProgressDialog | None = None
        self._writing: str | None = None
        self._files: dict[int, str] = {}  # job -> a picture's or JSON's file, on its way there
        self._jobs = 0
        self._file_signals = JobSignals(self)
        self._file_signals.finished.connect(self._file_done)
        self._file_signals.failed.connect(self._file_failed)
        QApplication.instance().aboutToQuit.connect(self.cancel)
        QTimer.singleShot(0, self, self.refresh)  # once the window is built: the entries ask it what it shows

    # ------------------------------------------------------------------ menu
    def refresh(self) -> None:
        """List what can be exported now; entries with nothing to export are disabled with the reason."""
        for submenu in self.menu.findChildren(QMenu):
            submenu.deleteLater()  # the last refresh's submenus
        self.menu.clear()
        self.actions = {}
        for tab in self.window.tabs:
            pictures = tab_pictures(tab)
            if pictures:
                submenu = self._submenu(tab.title)
                for picture in pictures:
                    self._add(submenu, f"{tab.title}/{picture.pane}", f"{picture.pane}…",
                              lambda _=False, p=picture: self._ask_picture(p), picture.why_not,
                              "Save this pane's image at its full resolution")
        self.menu.addSeparator()
        self._add(self.menu, "3D pane", "3D pane (PNG)…", self._ask_3d, "",
                  f"Save the 3D pane at {SCREENSHOT_SCALE} × its size on screen")
        self.menu.addSeparator()
        self._add(self.menu, "z-buffer steps", "z-buffer steps (GIF or MP4)…", self._ask_steps,
                  self._steps_why_not(".mp4"),
                  "One frame per polygon drawn, from the cleared buffers on, the polygon of each step tinted")
        orbit = self._submenu("Orbit of the observer (GIF or MP4)")
        for pane, (shows, _) in _orbit_pictures(self.window.model).items():
            self._add(orbit, f"Orbit/{pane}", f"{pane}…", lambda _=False, p=pane: self._ask_orbit(p),
                      self._orbit_why_not(pane),
                      f"The observer walks once around the target; each frame shows {shows}")
        self.menu.addSeparator()
        tree = self._submenu("Ray tree of the picked pixel")
        why = "" if self.window.ray_tree is not None else NO_PICKED_PIXEL
        self._add(tree, "Ray tree/3D pane", "3D pane with the ray tree (PNG)…", self._ask_ray_tree_png, why,
                  "The 3D pane with only the picked pixel's rays drawn")
        self._add(tree, "Ray tree/JSON", "Every ray with its numbers (JSON)…", self._ask_ray_tree_json, why,
                  "Kind, origin, direction, t, the object hit and the colours of every ray")

    def _submenu(self, title: str):
        submenu = QMenu(title, self.menu)  # made in Python: PySide6 never hands back a stale wrapper
        submenu.setToolTipsVisible(True)
        self.menu.addMenu(submenu)
        return submenu

    def _add(self, menu, key: str, text: str, slot, why_not: str, tip: str) -> None:
        action = QAction(text, menu)
        menu.addAction(action)
        action.triggered.connect(slot)
        action.setEnabled(not why_not)
        action.setToolTip(why_not or tip)
        action.setStatusTip(why_not or tip)
        self.actions[key] = action

    def ask_path(self, title: str, name: str, filters: list[tuple[str, str]]) -> str | None:
        """Ask where to save (starting in the last folder used); ``None`` if the user cancels."""
        text = ";;".join(f"{label} (*{extension})" for label, extension in filters)
        asked = ask_save(self.window, title, name + filters[0][1], text)
        if asked is None:
            return None
        path, chosen = asked
        if not os.path.splitext(path)[1]:
            path += next((e for label, e in filters if chosen.startswith(label)), filters[0][1])
        return path

    def _ask_picture(self, picture: PanePicture) -> None:
        path = self.ask_path(f"Export {picture.tab}: {picture.pane}", _file_name(picture.tab, picture.pane),
                             PICTURE_FILTERS)
        if path:
            self.export_picture(picture, path)

    def _ask_3d(self) -> None:
        path = self.ask_path("Export the 3D pane", "scene-3d", PICTURE_FILTERS[:1])
        if path:
            self.export_3d(path)

    def _ask_steps(self) -> None:
        path = self.ask_path("Export the z-buffer steps", "zbuffer-steps", ANIMATION_FILTERS)
        if path:
            self.export_steps(path)

    def _ask_orbit(self, pane: str) -> None:
        frames, ok = QInputDialog.getInt(self.window, "Orbit of the observer",
                                         "Frames for one turn around the target:", ORBIT_FRAMES, 2,
                                         MAX_FRAMES)
        if not ok:
            return
        path = self.ask_path(f"Export an orbit of {pane}", _file_name("orbit", pane), ANIMATION_FILTERS)
        if path:
            self.export_orbit(pane, frames, path)

    def _ask_ray_tree_png(self) -> None:
        path = self.ask_path("Export the ray tree in the 3D pane", self._ray_tree_name(), PICTURE_FILTERS[:1])
        if path:
            self.export_ray_tree_png(path)

    def _ask_ray_tree_json(self) -> None:
        path = self.ask_path("Export the ray tree", self._ray_tree_name(), [("JSON", ".json")])
        if path:
            self.export_ray_tree_json(path)

    def _ray_tree_name(self) -> str:
        x, y, _ = self.window.ray_tree
        return f"ray-tree-{x}-{y}"

    # -------------------------------------------------------------- pictures
    def export_picture(self, picture: PanePicture, path: str) -> bool:
        """Start writing ``picture`` to ``path`` (PNG or JPEG by its extension); False after showing why
        not."""
        if not self._checked(path, tuple(IMAGE_EXTENSIONS)):
            return False
        pixels = picture.make()
        return self._write(path, lambda: write_image(path, pixels))

    def export_3d(self, path: str, only=None) -> bool:
        """Start writing the 3D pane at :data:`SCREENSHOT_SCALE` × its size (only the overlays ``only``,
        if given)."""
        if not self._checked(path, (".png",)):
            return False
        view = self.window.scene_view
        if only is not None:
            view.show_overlays_only(only)
        try:
            levels = view.picture(SCREENSHOT_SCALE)
        finally:
            if only is not None:  # back to what the visible tab shows
                self.window.show_overlays()
        return self._write(path, lambda: write_image(path, srgb_to_linear(levels / 255.0)))

    def export_ray_tree_png(self, path: str) -> bool:
        """Write the 3D pane with only the picked pixel's ray tree drawn over the scene."""
        return self.export_3d(path, only=("ray-tree",))

    def export_ray_tree_json(self, path: str) -> bool:
        """Write the picked pixel's ray tree as JSON (:mod:`app.export.ray_tree_json`)."""
        if not self._checked(path, (".json",)):
            return False
        x, y, root = self.window.ray_tree
        data = ray_tree_json(x, y, root, self.window.model.trace_settings.mode)
        return self._write(path, lambda: write_atomic(path, data))

    def _checked(self, path: str, extensions: tuple[str, ...]) -> bool:
        try:
            Outputs().add("Export", path, extensions)
        except ValueError as exc:
            self._fail(path, str(exc))
            return False
        return True

    def _write(self, path: str, write) -> bool:
        """Run ``write()`` (encoding, the file) off the GUI thread; then say it was written, or show
        why not."""

        def job(_cancelled, _progress):
            try:
                write()
            except OutputError as exc:
                return path, str(exc)
            return path, None

        self._jobs += 1
        self._files[self._jobs] = path
        QThreadPool.globalInstance().start(JobRun(self._jobs, job, self._file_signals))
        return True

    def writing(self) -> list[str]:
        """The files being encoded and written now (pictures, JSON; not the animations)."""
        return list(self._files.values())

    def _file_done(self, job: int, result) -> None:
        path, problem = result
        del self._files[job]
        if problem is None:
            self._written(path)
        else:
            self._fail(path, problem)

    def _file_failed(self, job: int, message: str) -> None:  # a fault of ours, not of the file system
        self._fail(self._files.pop(job), message)

    def _written(self, path: str) -> None:
        self.window.statusBar().showMessage(f"Exported {path}", 8000)
        self.exported.emit(path)

    def _fail(self, path: str, message: str) -> None:
        """Say why ``path`` was not written: the file's name once (the message may give its whole path),
        and no exception's class name (an animation's writing failed on a worker, which adds one)."""
        message = message.removeprefix(f"{OutputError.__name__}: ")
        named = os.path.basename(path) if path in message else path
        QMessageBox.critical(self.window, "Export failed", f"Could not export {named}:\n\n{message}")

    # ------------------------------------------------------------ animations
    def _steps_why_not(self, extension: str) -> str:
        problem = steps_problem(self.window.model.scene, extension, budget.default_budget())
        return f"Not as an animation: {problem}" if problem else ""

    def export_steps(self, path: str) -> bool:
        """Start writing the z-buffer steps of the current scene (object-order settings) to ``path``."""
        if not self._checked(path, ANIMATION_EXTENSIONS):
            return False
        why = self._steps_why_not(os.path.splitext(path)[1].lower())
        if why:
            self._fail(path, why)
            return False
        scene, settings = self.window.model.scene, self.window.model.raster_settings
        self._start(path, "the z-buffer steps", lambda: zbuffer_steps(scene, settings))
        return True

    def _orbit_why_not(self, pane: str) -> str:
        """Why an orbit of ``pane`` may not be made: each frame is that tab's full render of the scene,
        and the window's memory budget refuses it (as the tab itself does); "" when it may."""
        refusal, _ = render_budget.check(self.window.tab(pane), self.window.model.scene, False,
                                         self.window.model.memory_limit)
        return refusal or ""

    def export_orbit(self, pane: str, frames: int, path: str) -> bool:
        """Start writing an orbit of ``frames`` frames of ``pane`` ("Image order", ...) to ``path``."""
        refusal = self._orbit_why_not(pane)
        if refusal:
            self._fail(path, refusal)
            return False
        if not self._checked(path, ANIMATION_EXTENSIONS):
            return False
        scene = self.window.model.scene
        shows, picture = _orbit_pictures(self.window.model)[pane]
        self._start(path, f"an orbit showing {shows}", lambda: (frames, orbit_frames(scene, frames, picture)))
        return True

    def _start(self, path: str, what: str, make_frames) -> None:
        """Render and write an animation in the background, behind a progress dialog with Cancel."""
        extension, limit = os.path.splitext(path)[1].lower(), budget.default_budget()

        def job(cancelled, progress):
            count, frames = make_frames()

            def watched():
                for i, frame in enumerate(frames):
                    if cancelled.is_set():
                        raise _CancelledError
                    yield frame
                    progress(round(100 * (i + 1) / count), None)

            try:
                data = encode_animation(watched(), extension, FPS, limit)
            except _CancelledError:
                return None
            if cancelled.is_set():
                return None
            write_atomic(path, data)
            return path

        self._progress = QProgressDialog(f"Writing {what} to {os.path.basename(path)}…", "Cancel", 0, 100,
                                         self.window)
        self._progress.setWindowTitle("Export")
        self._progress.setWindowModality(Qt.WindowModality.WindowModal)
        self._progress.setAutoClose(False)
        self._progress.setAutoReset(False)
        self._progress.setMinimumDuration(0)
        self._progress.canceled.connect(self.cancel)
        self._progress.show()
        self._writing = path
        self._renderer.submit(job)

    def _show_progress(self, percent: int, _partial) -> None:
        if self._progress is not None:
            self._progress.setValue(percent)

    def cancel(self) -> None:
        """Stop the animation being written; no file is written or changed."""
        if self._renderer.busy:
            self._renderer.cancel()
            self.window.statusBar().showMessage("Export cancelled; no file was written or changed", 8000)
        self._animation_done(None, None)

    def _animation_written(self, path: str) -> None:
        self._animation_done(path, None)

    def _animation_done(self, path: str | None, message: str | None) -> None:
        dialog, self._progress = self._progress, None
        writing, self._writing = self._writing, None
        if dialog is not None:
            dialog.canceled.disconnect(self.cancel)
            dialog.hide()
            dialog.deleteLater()
        if path is not None:
            self._written(path)
        if message is not None:
            self._fail(writing, message)
