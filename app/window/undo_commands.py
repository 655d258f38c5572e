"""Edits of the scene as undoable commands, for the window's one ``QUndoStack``.

Every edit (a changed field, an added, duplicated, renamed, moved or deleted
object or light, a new background) is a :class:`SceneEdit`: the scene's
objects, lights and background before and after it, and the selection
before and after.  Undo and redo put them back into the model as an *edit*
(:meth:`app.window.state.SceneModel.set_scene` with ``edit=True``), so the 3D pane
keeps its view.  The observer is not part of an edit: undoing the colour of a
cube leaves the camera where the user has since moved it.
"""

from __future__ import annotations

from dataclasses import replace

from PySide6.QtGui import QUndoCommand, QUndoStack

from core.scene import Scene


def _content(scene: Scene) -> dict:
    return {"objects": scene.objects, "lights": scene.lights, "background": scene.background}


class SceneEdit(QUndoCommand):
    """One edit: its name (``"Change colour of cube"``), the scene after it, the item selected then.

    Parameters
    ----------
    model : the :class:`app.window.state.SceneModel`; its current scene and selection are "before".
    text : the edit's name, shown in Edit → Undo / Redo.
    after : the scene as the edit leaves it (its camera is ignored).
    selected_after : the item to select once the edit is done (``None``: nothing).
    """

    def __init__(self, model, text: str, after: Scene, selected_after):
        super().__init__(text)
        self.model = model
        self.before, self.after = _content(model.scene), _content(after)
        self.selected_before, self.selected_after = model.selection, selected_after

    def redo(self) -> None:
        self._apply(self.after, self.selected_after)

    def undo(self) -> None:
        self._apply(self.before, self.selected_before)

    def _apply(self, content: dict, selection) -> None:
        self.model.set_scene(replace(self.model.scene, **content), edit=True)
        self.model.set_selection(selection)


def scene_at(stack: QUndoStack, index: int, current: Scene) -> Scene | None:
    """The scene as it was after the first ``index`` edits of ``stack`` (with ``current``'s camera).

    ``index`` is a stack index such as ``stack.cleanIndex()``; ``-1`` (a state no
    longer reachable) gives ``None``.
    """
    if index < 0:
        return None
    if stack.count() == 0:
        return current
    command = stack.command(index - 1) if index > 0 else stack.command(0)
    content = command.after if index > 0 else command.before
    return replace(current, **content)
