"""Answers withheld: while an exercise waits for its answer, the readouts that would give it away
are covered.

An exercise asks the student to predict what the pipelines find; the window's readouts state just
that (the picked pixel's history and ray tree, the worked math, the polygon drawn, a face's side), and
for a lesson step that picks the pixel the question names they stated the answer beside the question.
While the Exercises tab is in front, the window shows a step of the lesson (the scene the exercise
asks about) and its exercise is not yet answered right or revealed, the readouts
:func:`core.lessons.exercises.withheld` names are covered with an opaque sheet saying why
(:mod:`views.panels.pane_cover`), the 3D pane leaves out the overlays that draw results
(:data:`RESULT_OVERLAYS`) and marks only the objects the question names (the step's outline may be
its answer), the image-order pane leaves out its heat map when the question is what the map shows,
and the status bar drops the step's "Look at ..." (which may name the answer); the pictures stay,
the student reasons from them.  Back on the Lessons tab, once answered, or on another scene,
everything shows again.
"""

from __future__ import annotations

import shiboken6
from PySide6.QtWidgets import QLabel

from app.lessons.runner import FACE_SIDE_OVERLAY
from core.lessons.exercises import HEAT_MAP, PICTURES, RESULTS, offered, withheld
from views.panels.pane_cover import ANSWER, cover, uncover

RESULT_OVERLAYS = ("ray-tree", "walk", "polygon", "clipped", FACE_SIDE_OVERLAY)
"""The 3D pane's overlays that draw what the pipelines found: the picked pixel's rays and the grid
cells they walk, the polygon drawn at the step and its clipped pieces, a face's side."""


class WithheldAnswers:
    """Covers ``window``'s readouts (a :class:`app.window.main_window.MainWindow`) while its
    exercise waits for an answer."""

    def __init__(self, window):
        self.window = window
        self._asking = False  # the Exercises tab in front
        self._overlays = ()  # the overlays the 3D pane was last told to leave out
        window.exercise_panel.waiting.connect(self.update)
        window.exercise_dock.visibilityChanged.connect(self._seen)
        window.lesson_panel.step_selected.connect(self.update)  # after the step is shown: its "Look at"

    def _seen(self, seen: bool) -> None:
        self._asking = seen
        if shiboken6.isValid(self.window):  # the docks hide as the closed window goes
            self.update()

    def hidden(self) -> tuple[str, ...]:
        """What is withheld now: :data:`core.lessons.exercises.RESULTS`, ``PICTURES``, or nothing."""
        ex = self.window.exercise_panel.waiting_for
        asked = ex is not None and self._asking and self.window.lessons.step is not None  # on its scene
        return withheld(ex) if asked else ()

    def panes(self, what: str) -> list:
        """The widgets that show ``what``."""
        w = self.window
        if what == PICTURES:
            return [w.tab("four views").widget]
        object_order = w.tab("object order").widget
        return [object_order.details, w.tab("image order").widget.details,
                w.tab("compare").widget.pixel_box, object_order.step_caption]

    def overlays(self) -> tuple[str, ...]:
        """The 3D pane's overlays withheld now (:data:`RESULT_OVERLAYS`, or none)."""
        return RESULT_OVERLAYS if RESULTS in self.hidden() else ()

    def update(self, *_) -> None:
        hidden = self.hidden()
        n = self.window.exercise_panel.index + 1
        why = f"Hidden while exercise {n} waits for your answer: this would give it away. " \
              "Answer it, or press Reveal."
        for what in (RESULTS, PICTURES):
            for pane in self.panes(what):
                if what not in hidden:
                    uncover(pane, ANSWER)
                else:  # a label is one line: the step drawn
                    cover(pane, f"Hidden until exercise {n} is answered" if isinstance(pane, QLabel)
                          else why, ANSWER)
        self.window.tab("image order").widget.withhold_heat(  # under the map's choice: one short line
            f"Heat map hidden until exercise {n} is answered" if HEAT_MAP in hidden else "")
        # The 3D pane marks what the question names, not what the step's words name (its outline of
        # the box behind the observer answered "Which object is dropped before any pixel work?").
        ex = self.window.exercise_panel.waiting_for
        self.window.lessons.ask((ex.question, offered(ex)) if RESULTS in hidden else None)
        status = self.window.statusBar()
        if RESULTS in hidden and status.currentMessage().startswith("Look at "):
            status.clearMessage()  # the step's pointer may name the answer ("Look at object 'object 5'")
        if self.overlays() != self._overlays:  # the 3D pane is told only of a change (each step, each tab)
            self._overlays = self.overlays()
            self.window.show_overlays()
