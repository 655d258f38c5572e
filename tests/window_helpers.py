"""The main window as the GUI tests open it: on the lecture scene, its first image shown."""

from app.window.main_window import MainWindow
from core import presets

RENDER_TIMEOUT_MS = 180_000  # the first render compiles the numba kernels when no cache exists


def open_window(qtbot) -> MainWindow:
    """Open the window on the lecture scene; wait until the image-order tab shows its full image
    and the 3D pane is built (it comes in after the first image, see views.scene3d.deferred_scene_view)."""
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    win.show()
    qtbot.waitUntil(lambda: win.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: win.scene_view.view is not None, timeout=RENDER_TIMEOUT_MS)
    return win


def run_as_the_app(script: str, config_home) -> str:
    """Run ``script`` (which opens the window with ``app.cli.main``) in a process of its own, as
    ``python -m app`` runs, with no last session (the lecture scene); its standard output."""
    import os
    import subprocess
    import sys

    from checkout import ROOT

    out = subprocess.run([sys.executable, "-c", script], cwd=ROOT, capture_output=True, text=True,
                         env={**os.environ, "XDG_CONFIG_HOME": str(config_home)}, timeout=300)
    assert out.returncode == 0, out.stderr
    return out.stdout


def presenting_on_1280x720(qtbot, monkeypatch, scale: float = 1.5) -> MainWindow:
    """The window on a 1280x720 screen (a lecture hall's projector), presenting, text ``scale`` times."""
    from PySide6.QtCore import QRect
    from PySide6.QtGui import QScreen

    screen = QRect(0, 0, 1280, 720)
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: screen)
    monkeypatch.setattr(QScreen, "geometry", lambda self: screen)
    window = open_window(qtbot)
    window.presentation.set_presenting(True)
    window.presentation.set_scale(scale)
    qtbot.waitUntil(window.presentation.settled)
    return window


def ask_exercise(qtbot, window: MainWindow, lesson_id: str, step: int, exercise: int,
                 drawn: int | None = None):
    """Show the shipped lesson ``lesson_id``'s step ``step`` and ask its exercise ``exercise`` with the
    Exercises tab in front, as a student does (its variant ``drawn``: the student's seed is set to draw
    it); the exercise panel."""
    from shipped_exercises import seed_drawing

    from app.window.window_layout import in_front
    from core.lessons.lesson_file import shipped_lessons

    lessons = shipped_lessons()
    k = [lesson.id for lesson in lessons].index(lesson_id)
    if drawn is not None:
        seed = seed_drawing(lessons[k].exercises[exercise], exercise, drawn)
        window.exercise_panel.progress.settings.setValue("exercise_seed", seed)
    window.lesson_panel.select(k, step)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    window.exercise_panel.go(exercise)
    return window.exercise_panel


def open_scene_file(qtbot, window: MainWindow, path) -> bool:
    """File → Open scene… with ``path``, waiting until the file is read (off the GUI thread) and shown,
    or refused; whether it is the scene shown now."""
    with qtbot.waitSignal(window.scene_file_done, timeout=30_000) as done:
        window.open_scene(path)
    return done.args[1]
