"""Lessons → Add this view as a step: the window's state recorded into a lesson file.

A small form asks for the step's title, text and (optionally) its facts as JSON
and one exercise about the step (a JSON object, e.g. a "choose one");
the window's scene and observer, the panes shown (the one in front first), the
image- and object-order settings, the z-buffer step, the picked pixel, the 3D
pane's viewpoint, the highlight of the lesson step shown and the image-order heat
map are recorded (:func:`core.lessons.authoring.step_record`) and appended to the lesson
file chosen (:func:`core.lessons.authoring.add_step`).  Any problem (bad facts,
an unreadable file) is shown in one dialog, field path first; nothing is written.
"""

from __future__ import annotations

import json

from PySide6.QtWidgets import (
    QDialog,
    QDialogButtonBox,
    QFileDialog,
    QFormLayout,
    QLineEdit,
    QMessageBox,
    QPlainTextEdit,
)

from core.files.safe_files import OutputError
from core.lessons.authoring import add_step, step_record
from core.lessons.lesson_file import LessonFileError


class StepForm(QDialog):
    """Title, text, facts (a JSON list, may be empty) and exercise (a JSON object, may be empty) of the
    step to record."""

    def __init__(self, parent=None):
        super().__init__(parent)
        self.setWindowTitle("Add this view as a lesson step")
        self.title = QLineEdit()
        self.text = QPlainTextEdit()
        self.facts = QPlainTextEdit()
        self.facts.setPlaceholderText('[{"fact": "zbuffer_keeps", "pixel": [80, 60], "object": "blue"}]')
        form = QFormLayout(self)
        form.addRow("Title", self.title)
        form.addRow("Text", self.text)
        self.exercise = QPlainTextEdit()
        self.exercise.setPlaceholderText('{"kind": "choose_one", "question": "Which wins at (80, 60)?", '
                                         '"choices": ["green", "blue"], "fact": {"fact": "zbuffer_keeps", '
                                         '"pixel": [80, 60], "object": "$choice"}, "why": "..."}')
        form.addRow("Facts (JSON)", self.facts)
        form.addRow("Exercise (JSON)", self.exercise)
        ok_cancel = QDialogButtonBox.StandardButton.Ok | QDialogButtonBox.StandardButton.Cancel
        buttons = QDialogButtonBox(ok_cancel)
        buttons.accepted.connect(self.accept)
        buttons.rejected.connect(self.reject)
        form.addRow(buttons)


class LessonRecorder:
    """Records ``window``'s state (a :class:`app.window.main_window.MainWindow`) as lesson steps."""

    def __init__(self, window):
        self.window = window

    def state_step(self, title: str, text: str, facts=()) -> dict:
        """The window's state as one step of the lesson-file format."""
        w, model = self.window, self.window.model
        shown = w.visible_panes()
        front = w.current.title.lower()
        panes = [front] + [p for p in shown if p != front]
        return step_record(title=title, text=text, scene=model.scene, panes=panes,
                           image_order=model.trace_settings, object_order=model.raster_settings,
                           zbuffer_step=model.step, pixel=model.ray_pixel or model.buffer_pixel, facts=facts,
                           view=self.viewpoint(), highlight=self.highlight(),
                           heat_map=w.tab("image order").widget.heat.currentText().lower())

    def viewpoint(self) -> dict:
        """The 3D pane's camera as the user left it: ``position``, ``focal_point``, ``up`` (world
        space).  Asking for it builds the pane if it was not built yet (it then frames the scene as
        it would when shown)."""
        position, focal_point, up = self.window.scene_view.plotter.camera_position
        return {"position": position, "focal_point": focal_point, "up": up}

    def highlight(self) -> dict:
        """What the lesson step shown last highlights, less the parts naming an object the window's
        scene no longer has (they could not be shown, nor loaded)."""
        step = self.window.lessons.step
        if step is None:
            return {}
        names = {o.name for o in self.window.model.scene.objects}
        return {key: part for key, part in step.highlight.items() if _named(key, part) in names | {None}}

    def record(self, path, title: str, text: str, facts_json: str = "", exercise_json: str = "") -> bool:
        """Append the window's state to the lesson file ``path``, with the exercise typed (asked about
        this step); False (and a dialog) on a problem."""
        typed = {}
        for field, words in (("facts", facts_json), ("exercise", exercise_json)):
            try:
                typed[field] = json.loads(words) if words.strip() else None
            except json.JSONDecodeError as exc:
                where = f"{field}: line {exc.lineno}, column {exc.colno}"
                return self._refuse([f"{where}: invalid JSON: {exc.msg}"])
        exercise = typed["exercise"]
        if exercise is not None and not isinstance(exercise, dict):
            return self._refuse(['exercise: expected one exercise, an object {"kind": ...}'])
        try:
            add_step(path, self.state_step(title, text, typed["facts"] or []), exercise)
        except LessonFileError as exc:
            return self._refuse(exc.problems)
        except OutputError as exc:
            return self._refuse([str(exc)])
        self.window.statusBar().showMessage(f"Step {title!r} added to {path}", 8000)
        return True

    def ask(self) -> None:
        """The menu action: the form, then the file to add the step to."""
        form = StepForm(self.window)
        if form.exec() != QDialog.DialogCode.Accepted:
            return
        path, _ = QFileDialog.getSaveFileName(self.window, "Add the step to lesson file", "lesson.json",
                                              "Lesson files (*.json)",
                                              options=QFileDialog.Option.DontConfirmOverwrite)
        if path:
            self.record(path, form.title.text(), form.text.toPlainText(), form.facts.toPlainText(),
                        form.exercise.toPlainText())

    def _refuse(self, problems) -> bool:
        box = QMessageBox(QMessageBox.Icon.Warning, "Cannot add the step",
                          "The step was not added:", QMessageBox.StandardButton.Ok, self.window)
        box.setInformativeText("\n".join(problems[:12]))
        box.setObjectName("lesson_record_error")
        box.open()
        return False


def _named(key: str, part):
    """The object a highlight's part names (``face``, ``vertex``, ``object``), or None."""
    if key in ("face", "vertex"):
        return part["object"]
    return part if key == "object" else None
