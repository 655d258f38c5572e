"""The scene an exercise asks about: when the window shows another, the exercise says so.

An exercise is judged on the scene of its lesson step (:mod:`core.lessons.exercises`), whatever the
window shows.  A student who moved the observer (the arrow keys orbit it), edited the scene, went to
another step or opened another scene and then answered from the window would be told "wrong" about
what they see.  :class:`AskedScene` compares the window's scene with the one the exercise waiting
for its answer asks about, and while they differ the exercise panel says which it asks about, what
the window shows instead, and that Show me brings it back.
"""

from __future__ import annotations

from dataclasses import replace


class AskedScene:
    """Keeps ``window``'s exercise panel told whether the window shows the scene its exercise asks
    about (``window``: a :class:`app.window.main_window.MainWindow`)."""

    def __init__(self, window):
        self.window = window
        window.model.scene_changed.connect(self.update)
        window.model.camera_changed.connect(self.update)
        window.exercise_panel.waiting.connect(self.update)

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
