"""Answers withheld: while an exercise waits for its answer, the readouts that would give it away
are covered.

An exercise asks the student to predict what the pipelines find; the window's readouts state just
that (the picked pixel's history and ray tree, the worked math, the polygon drawn, a face's side), and
for a lesson step that picks the pixel the question names they stated the answer beside the question.
While the Exercises tab is in front and its exercise is not yet answered right or revealed, the
readouts :func:`core.lessons.exercises.withheld` names are covered with an opaque sheet saying why
(:mod:`views.panels.pane_cover`); the pictures stay, the student reasons from them.  Back on the
Lessons tab, or once answered, everything shows again.
"""

from __future__ import annotations

from PySide6.QtWidgets import QLabel

from app.lessons.runner import FACE_SIDE_OVERLAY
from core.lessons.exercises import PICTURES, RESULTS, withheld
from views.panels.pane_cover import ANSWER, cover, uncover


class WithheldAnswers:
    """Covers ``window``'s readouts (a :class:`app.window.main_window.MainWindow`) while its
    exercise waits for an answer."""

    def __init__(self, window):
        self.window = window
        self._asking = False  # the Exercises tab in front
        window.exercise_panel.waiting.connect(self.update)
        window.exercise_dock.visibilityChanged.connect(self._seen)

    def _seen(self, seen: bool) -> None:
        self._asking = seen
        self.update()

    def hidden(self) -> tuple[str, ...]:
        """What is withheld now: :data:`core.lessons.exercises.RESULTS`, ``PICTURES``, or nothing."""
        ex = self.window.exercise_panel.waiting_for
        return withheld(ex) if ex is not None and self._asking else ()

    def panes(self, what: str) -> list:
        """The widgets that show ``what``."""
        w = self.window
        if what == PICTURES:
            return [w.tab("four views").widget]
        object_order = w.tab("object order").widget
        return [object_order.details, w.tab("image order").widget.details,
                w.tab("compare").widget.pixel_box, object_order.step_caption]

    def overlays(self) -> tuple[str, ...]:
        """The 3D pane's overlays that state a result, shown unless withheld (:meth:`hidden`)."""
        return () if RESULTS in self.hidden() else (FACE_SIDE_OVERLAY,)

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
        self.window.show_overlays()
