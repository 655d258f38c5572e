"""The scene an exercise asks about: the window shows it, and says so when it shows another.

An exercise is judged on the scene of its lesson step (:mod:`core.lessons.exercises`), whatever the
window shows.  When the student asks an exercise (brings the Exercises tab to the front, or goes to
another exercise there) while the window shows another step of its lesson, or no step but the scene
of one (as the window opens, the Lessons tab shows the first lesson, not yet started, on its
scene), :class:`AskedScene` shows the exercise's step: its scene and settings (a z-buffer question
asked on the cleared buffers was otherwise asked beside the finished picture of the lesson's last
step; one asked before any step was shown had none of its readouts withheld,
:mod:`app.lessons.withheld_answers`).  A student who then moves the observer (the arrow keys orbit
it), edits the scene, goes to another step or opens another scene, and answers from the window,
would be told "wrong" about what they see: while the window's scene differs from the one asked
about, the exercise panel says which it asks about, what the window shows instead, and that Show
me brings it back.
"""

from __future__ import annotations

from dataclasses import replace


class AskedScene:
    """Shows the step an exercise asks about when it is asked, and keeps ``window``'s exercise panel
    told whether the window shows that step's scene (``window``: a
    :class:`app.window.main_window.MainWindow`)."""

    def __init__(self, window):
        self.window = window
        self._lesson = None  # the lesson whose exercises were asked last
        window.model.scene_changed.connect(self.update)
        window.model.camera_changed.connect(self.update)
        window.exercise_panel.waiting.connect(self._asked)
        window.exercise_dock.visibilityChanged.connect(lambda seen: seen and self.show_its_step())

    def _asked(self, ex) -> None:
        """Another exercise is asked: its step is shown if the Exercises tab is in front; not when the
        exercises change with the lesson (a step of another lesson chosen: that step stays)."""
        lesson = self.window.exercise_panel.lesson
        if lesson is self._lesson and self.window.exercise_dock.isVisible():
            self.show_its_step()
        self._lesson = lesson
        self.update()

    def show_its_step(self) -> None:
        """While the window shows another step of the waiting exercise's lesson, or no step but the scene
        of one, show the exercise's (as Show me does, without picking a pixel); another scene, or the
        step moved or edited, stays."""
        w = self.window
        ex, lesson = w.exercise_panel.waiting_for, w.exercise_panel.lesson
        shown = w.lessons.step
        if ex is None or lesson is None or w.lesson_panel.current_lesson() is not lesson:
            return
        if shown is None:  # no step shown since the window opened or a scene was opened: the scene
            # decides (the lecture scene as the window opens is the first lesson's; a file stays)
            if any(w.model.scene == step.scene for step in lesson.steps):
                w.lesson_panel.select(w.lesson_panel.step_index()[0], ex.step)
            return
        another_step = shown is not lesson.steps[ex.step] and any(shown is step for step in lesson.steps)
        if another_step and w.model.scene == shown.scene:
            w.lesson_panel.select(w.lesson_panel.step_index()[0], ex.step)

    def elsewhere(self) -> str:
        """Why the window's scene is not the one the waiting exercise asks about, in words, or ""."""
        w = self.window
        ex, lesson = w.exercise_panel.waiting_for, w.exercise_panel.lesson
        if ex is None or lesson is None:
            return ""
        asked, shown = lesson.steps[ex.step].scene, w.model.scene
        if shown == asked:
            return ""
        k = next((k for k, step in enumerate(lesson.steps) if step.scene == shown), None)
        if k is not None:
            what = f"step {k + 1}'s"
        elif replace(shown, camera=asked.camera) == asked:
            what = "it with the observer moved"
        else:  # edited, or a file or an example opened
            what = "another scene"
        return (f"This question is about the scene of step {ex.step + 1}; the window shows {what}. "
                "Show me brings it back.")

    def update(self, *_) -> None:
        self.window.exercise_panel.set_elsewhere(self.elsewhere())
