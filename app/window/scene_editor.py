"""The scene editor: the Editor dock, the Edit menu and one undo stack for every edit.

:class:`SceneEditor` connects the dock's tree and fields
(:class:`views.panels.scene_tree_panel.SceneTreePanel`) to the model: each change
asked for there is checked as the scene file's loader checks a file
(:mod:`core.checked_edits`) and, if it passes, pushed onto the window's one
``QUndoStack`` as a :class:`app.window.undo_commands.SceneEdit`; if not, the loader's
message is shown beside the field and the scene stays as it was.  Moving the
observer is not an edit and never reaches the stack.

The stack's clean state is "saved": the window's title shows ``*`` while
there are unsaved edits, and closing the window or replacing the scene (a
file, an example, a lesson step) asks first whether to save them
(:meth:`SceneEditor.may_replace_scene`).  Any new scene that is not an edit
starts a fresh stack.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from PySide6.QtCore import QObject
from PySide6.QtGui import QAction, QKeySequence, QUndoStack
from PySide6.QtWidgets import QMenu, QMessageBox

from app.renders import Renderer
from app.window.undo_commands import SceneEdit
from app.window.window_layout import dock_action, in_front, tabbed_dock
from core import checked_edits
from core.files import scene_file
from core.files.mesh_files import EXTENSIONS, read_mesh
from core.files.scene_file import SceneFileError
from views.file_dialogs import ask_open
from views.panels.scene_tree_panel import SceneTreePanel, label
from views.recent_files import SCENE

EDITABLE = ("object", "light")


class SceneEditor(QObject):
    """The scene editor of ``window`` (a :class:`app.window.main_window.MainWindow`).

    Attributes
    ----------
    stack : the QUndoStack of every scene edit.
    panel : the dock's tree and fields.
    keyed_actions : the editor's actions that have a shortcut (for Help → Keys).
    """

    def __init__(self, window):
        super().__init__(window)
        self.window, self.model = window, window.model
        self.stack = QUndoStack(self)
        self.panel = SceneTreePanel(self.model)
        self.dock = tabbed_dock(window, "Editor", "scene editor", self.panel, window.lesson_dock)
        window.lesson_dock.raise_()
        self._mesh_reader = Renderer(self)
        self._mesh_reader.finished.connect(self._mesh_read)
        self._mesh_reader.failed.connect(lambda message: self._refused("Cannot add the mesh", message))
        self.keyed_actions: list[QAction] = []
        self._build_actions()
        self.panel.field_edited.connect(self.change_field)
        self.panel.move_requested.connect(self.move)
        self.picker = None  # a views.scene3d.scene_picking.ScenePicker, once the 3D pane is built
        pane = window.scene_view
        if pane.view is not None:
            self._attach_picker(pane.view)
        else:
            pane.ready.connect(lambda: self._attach_picker(pane.view))
        self.model.scene_changed.connect(self._scene_changed)
        self.model.selection_changed.connect(self._selection_changed)
        self.stack.cleanChanged.connect(self._clean_changed)  # a method: disconnected with the editor
        window.windowTitleChanged.connect(self._title_changed)
        self._title_changed(window.windowTitle())
        self._selection_changed(self.model.selection)

    def start_rename(self) -> None:
        """Rename the selection in the tree (F2), its dock brought to the front first: the tree's
        editor opened unseen behind another tab, and typing there renamed the object."""
        self.dock.show()
        self.dock.raise_()
        self.panel.start_rename()

    def _clean_changed(self, clean: bool) -> None:
        self.window.setWindowModified(not clean)

    # ----------------------------------------------------------- actions
    def _action(self, text, slot, shortcut=None, tip="") -> QAction:
        action = QAction(text, self.window)
        action.triggered.connect(slot)
        action.setToolTip(tip)
        action.setStatusTip(tip)
        if shortcut is not None:
            action.setShortcut(QKeySequence(shortcut))
            self.keyed_actions.append(action)
        return action

    def _build_actions(self) -> None:
        w = self.window
        self.undo_action = self.stack.createUndoAction(w, "Undo")
        self.undo_action.setShortcut(QKeySequence("Ctrl+Z"))
        self.redo_action = self.stack.createRedoAction(w, "Redo")
        self.redo_action.setShortcuts([QKeySequence("Ctrl+Shift+Z"), QKeySequence("Ctrl+Y")])
        self.keyed_actions += [self.undo_action, self.redo_action]
        self.add_menu = QMenu("&Add", w)
        for type_name in checked_edits.NEW_OBJECTS:
            self.add_menu.addAction(self._action(
                type_name.replace("_", " "), lambda _=False, t=type_name: self.add_object(t),
                tip=f"Add a {type_name} at the point the observer looks at"))
        self.add_menu.addAction(self._action("Mesh from file…", self.add_mesh_dialog,
                                             tip="Add a mesh from an OBJ, STL or PLY file"))
        self.add_menu.addSeparator()
        self.add_light_action = self._action("Light", self.add_light, tip="Add a white point light "
                                             "above the point the observer looks at")
        self.add_menu.addAction(self.add_light_action)
        self.duplicate_action = self._action("&Duplicate", self.duplicate, "Ctrl+D",
                                             "A copy of the selected object or light, in the same place")
        self.rename_action = self._action("&Rename", self.start_rename, "F2",
                                          "Type a new name for the selected object or light")
        self.delete_action = self._action("De&lete", self.delete, QKeySequence.StandardKey.Delete,
                                          "Delete the selected object or light")
        self.save_action = self._action("&Save scene", self.save, QKeySequence.StandardKey.Save,
                                        "Save the scene to its file (asks for one if it has none)")
        self.add_menu.setToolTip("Add an object or a light")
        self.panel.add_button(menu=self.add_menu, text="Add")
        for action in (self.duplicate_action, self.rename_action, self.delete_action):
            self.panel.add_button(action)

        menu = QMenu("&Edit", w)
        menu.addActions([self.undo_action, self.redo_action])
        menu.addSeparator()
        menu.addMenu(self.add_menu)
        menu.addActions([self.duplicate_action, self.rename_action, self.delete_action])
        menu.addSeparator()
        show = dock_action(self.dock, "Scene editor", "Ctrl+Shift+E")
        self.keyed_actions.append(show)
        menu.addAction(show)
        bar = w.menuBar().actions()
        w.menuBar().insertMenu(bar[1] if len(bar) > 1 else None, menu)  # after File
        file_actions = bar[0].menu().actions() if bar else []
        save_as = next((a for a in file_actions if a.text().replace("&", "").startswith("Save scene as")),
                       None)
        if save_as is not None:
            bar[0].menu().insertAction(save_as, self.save_action)

    def _attach_picker(self, view) -> None:
        """Clicks in the 3D pane select, its handle moves (see :mod:`views.scene3d.scene_picking`)."""
        from views.scene3d.scene_picking import (
            ScenePicker,  # with VTK, which the window loads after its first frame
        )

        self.picker = ScenePicker(self.model, view)
        self.picker.move_requested.connect(self.move)
        self.picker.picked.connect(self._picked)

    def _picked(self, item) -> None:
        """Bring the picked item's fields to the front, unless a lesson's words are shown there."""
        if item is None:
            return
        if self.window.lessons.step is not None and in_front(self.window.lesson_dock):
            self.window.statusBar().showMessage(
                "Selected; its fields are in the Editor tab, beside Lessons", 6000)
        else:
            self.dock.raise_()

    def _selection_changed(self, item) -> None:
        editable = item is not None and item[0] in EDITABLE
        for action in (self.duplicate_action, self.rename_action, self.delete_action):
            action.setEnabled(editable)

    # ------------------------------------------------------------- edits
    @property
    def base_dir(self):
        """The folder of the scene's file (relative mesh file paths start there), or None."""
        return self.window.scene_path.parent if self.window.scene_path is not None else None

    def _push(self, text: str, scene, selected) -> None:
        self.stack.push(SceneEdit(self.model, text, scene, selected))

    def change_field(self, item, key: str, value) -> bool:
        """Set field ``key`` of ``item`` to ``value`` (as the scene file would hold it).

        Returns whether the change was made; a refused one shows the loader's message
        beside the field.
        """
        scene = self.model.scene
        name = checked_edits.name_of(scene, item)
        if key == "name":
            if not str(value).strip():
                return self._field_problem(item, key, "name: must not be empty")
            text = f"Rename {name} to {value}"
        elif item == checked_edits.BACKGROUND:
            text = "Change background colour"
        else:
            text = f"Change {label(key)} of {name}"
        try:
            edited = checked_edits.with_field(scene, item, key, value, self.base_dir, read_mesh)
        except SceneFileError as exc:
            return self._field_problem(item, key, "\n".join(exc.problems))
        self._field_problem(item, key, "")  # an unchanged value (the old one typed again) is fine too
        if edited != scene:
            self._push(text, edited, item)
        return True

    def move(self, item, position) -> bool:
        """Place ``item`` at ``position`` (its centre, base centre or position); one undo entry."""
        scene = self.model.scene
        try:
            edited = checked_edits.moved(scene, item, position, self.base_dir, read_mesh)
        except SceneFileError as exc:
            key = checked_edits.position_key(scene, item) or "position"
            return self._field_problem(item, key, "\n".join(exc.problems))
        self._field_problem(item, checked_edits.position_key(scene, item) or "position", "")
        if edited != scene:
            self._push(f"Move {checked_edits.name_of(scene, item)}", edited, item)
        return True

    def _field_problem(self, item, key, message: str) -> bool:
        """Show ``message`` beside field ``key`` of ``item`` (or in the status bar if the field is not
        shown); an empty message clears the field's problem.  Returns False (not changed)."""
        if self.model.selection == item and key in self.panel.fields:
            self.panel.show_problem(key, message)
        elif message:
            self.window.statusBar().showMessage(f"Not changed — {message}", 10000)
        return False

    def _add(self, kind: str, value: dict, known=()) -> bool:
        try:
            scene, item = checked_edits.added(self.model.scene, kind, value, None, self.base_dir,
                                              read_mesh, known)
        except SceneFileError as exc:
            return self._refused("Cannot add it", "\n".join(exc.problems))
        self._push(f"Add {value['name']}", scene, item)
        return True

    def add_object(self, type_name: str) -> bool:
        """Add a primitive of ``type_name`` near the observer's target where the observer sees it
        (:func:`core.checked_edits.plain_view_spot`), and select it."""
        scene = self.model.scene
        target = np.asarray(scene.camera.target, float)
        try:  # the new object's extent, made at the target
            at_target = checked_edits.new_object(scene, type_name, target)
            probe, item = checked_edits.added(scene, "object", at_target, None, self.base_dir, read_mesh)
        except SceneFileError:
            spot = target  # refused (the scene is full): _add says why
        else:
            low, high = checked_edits.object_bounds(probe.objects[item[1]])
            spot = checked_edits.plain_view_spot(scene, low - target, high - target)
        return self._add("object", checked_edits.new_object(scene, type_name, spot))

    def add_light(self) -> bool:
        """Add a white point light above the observer's target, and select it."""
        scene = self.model.scene
        return self._add("light", checked_edits.new_light(scene, scene.camera.target))

    def add_mesh_dialog(self) -> None:
        kinds = " ".join(f"*{ext}" for ext in EXTENSIONS)
        path = ask_open(self.window, "Add a mesh", f"Meshes ({kinds})")
        if path:
            self.add_mesh_file(path)

    def add_mesh_file(self, path) -> None:
        """Read the mesh file ``path`` in the background, then add it (one undo entry)."""
        value = checked_edits.new_mesh_file(self.model.scene, path)
        index = len(self.model.scene.objects)  # where it goes: its problems are named so
        self.window.statusBar().showMessage(f"Reading {Path(path).name}…")

        def job(cancelled, progress):
            try:
                return value, checked_edits.read_object(value, read_mesh, index)
            except SceneFileError as exc:
                return value, exc

        self._mesh_reader.submit(job)

    def _mesh_read(self, result) -> None:
        value, mesh = result
        self.window.statusBar().clearMessage()
        if isinstance(mesh, SceneFileError):
            self._refused("Cannot add the mesh", "\n".join(mesh.problems))
        else:
            value["name"] = checked_edits.unique_name(value["name"],
                                                      checked_edits.names(self.model.scene, "object"))
            self._add("object", value, known=(mesh,))

    def duplicate(self) -> bool:
        """A copy of the selected object or light just after it, selected."""
        item = self.model.selection
        if item is None or item[0] not in EDITABLE:
            return False
        scene = self.model.scene
        try:
            copied, new = checked_edits.duplicated(scene, item, self.base_dir, read_mesh)
        except SceneFileError as exc:
            return self._refused("Cannot duplicate it", "\n".join(exc.problems))
        self._push(f"Duplicate {checked_edits.name_of(scene, item)}", copied, new)
        return True

    def delete(self) -> bool:
        """Delete the selected object or light."""
        item = self.model.selection
        if item is None or item[0] not in EDITABLE:
            return False
        scene = self.model.scene
        self._push(f"Delete {checked_edits.name_of(scene, item)}", checked_edits.removed(scene, item), None)
        return True

    def _refused(self, title: str, message: str) -> bool:
        QMessageBox.warning(self.window, title, message)
        return False

    # ----------------------------------------------------- saved or not
    def _scene_changed(self, _scene) -> None:
        if not self.model.scene_was_edited:
            self.stack.clear()  # a new scene: nothing to undo, nothing unsaved

    def _title_changed(self, title: str) -> None:
        if "[*]" not in title:  # where the title shows "*" while there are unsaved edits
            self.window.setWindowTitle(f"{title}[*]")

    def saved(self, path) -> None:
        """The scene was saved to ``path``: that is now its file, and nothing is unsaved."""
        self.window.scene_path = Path(path)
        self.window.setWindowTitle(f"Render Explorer — {Path(path).name}")
        self.window.recent_files.add(SCENE, path)
        self.stack.setClean()

    def save(self) -> bool:
        """Save to the scene's file (Ctrl+S), or ask for one; returns whether it was saved."""
        path = self.window.scene_path
        if path is None:
            self.window.save_scene_dialog()
            return self.stack.isClean()
        return self.save_to(path)

    def save_to(self, path) -> bool:
        """Save the scene to ``path``, which is its file from then on; a dialog says why not."""
        try:
            scene_file.save(self.model.scene, path)
        except OSError as exc:  # the message names the whole path: the head only the file's name
            QMessageBox.critical(self.window, "Cannot save scene",
                                 f"Could not save {Path(path).name}:\n\n{exc}")
            return False
        self.saved(path)
        return True

    def may_replace_scene(self) -> bool:
        """Whether the scene may go: nothing unsaved, or the user saved or discarded it."""
        if self.stack.isClean():
            return True
        where = self.window.scene_path.name if self.window.scene_path is not None else "a file"
        # The last edit, or, undone past the last save, the first edit undone since.
        last = self.stack.undoText() or f"undone: {self.stack.redoText()}"
        box = QMessageBox(QMessageBox.Icon.Question, "Unsaved changes",
                          f"The scene has changes that are not saved ({last}, …).\n"
                          f"Save them to {where} first?",
                          QMessageBox.StandardButton.Save | QMessageBox.StandardButton.Discard
                          | QMessageBox.StandardButton.Cancel, self.window)
        box.setDefaultButton(QMessageBox.StandardButton.Save)
        answer = box.exec()
        if answer == QMessageBox.StandardButton.Save:
            return self.save()
        return answer == QMessageBox.StandardButton.Discard
