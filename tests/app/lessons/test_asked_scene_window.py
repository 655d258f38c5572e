"""An exercise is judged on its step's scene: when the window shows another (the observer moved by
the arrow keys, another step, another scene), the exercise says which scene it asks about, and Show me
brings that scene back."""

from PySide6.QtCore import Qt
from window_helpers import ask_exercise

from app.window.window_layout import in_front
from core import presets
from core.lessons.lesson_file import shipped_lessons

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def test_an_exercise_says_when_the_window_no_longer_shows_the_scene_it_asks_about(qtbot, window):
    exercises = ask_exercise(qtbot, window, "observer", 1, 1)
    assert exercises.question.text().startswith("From observer B, ")
    assert exercises.elsewhere.isHidden()  # the window shows observer B's scene
    asked = window.model.scene
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.keyClick(window, Qt.Key.Key_Left)  # the arrow keys orbit the observer
    qtbot.waitUntil(lambda: window.model.camera != asked.camera)
    assert exercises.elsewhere.isVisible()
    assert exercises.elsewhere.text() == ("<i>This question is about the scene of step 2; the window "
                                          "shows it with the observer moved. Show me brings it back.</i>")
    exercises.show_button.click()
    assert window.model.scene == asked
    assert exercises.elsewhere.isHidden()

    window.lesson_panel.select(LESSONS["observer"], 0)  # observer A, while the question is about B
    assert exercises.index == 1
    assert "the window shows step 1's." in exercises.elsewhere.text()
    window.load_preset("lecture", presets.lecture_scene)  # File → an example: another scene
    assert "the window shows another scene." in exercises.elsewhere.text()
    ask_exercise(qtbot, window, "observer", 1, 1)
    assert exercises.elsewhere.isHidden()


def test_once_answered_or_revealed_nothing_is_said(qtbot, window):
    exercises = ask_exercise(qtbot, window, "observer", 1, 1)
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.keyClick(window, Qt.Key.Key_Left)
    qtbot.waitUntil(exercises.elsewhere.isVisible)
    exercises.reveal()
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("The answer:"))
    assert exercises.elsewhere.isHidden()


def test_after_show_me_no_exercise_says_the_window_shows_another_scene(qtbot, window):
    """Each of the shipped exercises, its step shown by Show me: the window shows the scene it asks
    about, and nothing says otherwise (a step's own settings, camera and all, are its scene)."""
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    exercises = window.exercise_panel
    for lesson in shipped_lessons():
        window.lesson_panel.select(LESSONS[lesson.id], 0)
        for k in range(len(lesson.exercises)):
            exercises.go(k)
            window.statusBar().clearMessage()
            exercises.show_button.click()  # a click-a-pixel exercise's pixel is found off the GUI thread
            said = f"Exercise {k + 1}: showing"
            qtbot.waitUntil(lambda said=said: window.statusBar().currentMessage().startswith(said))
            assert window.lesson_panel.step_index()[1] == exercises.exercise().step
            assert exercises.elsewhere.isHidden(), (lesson.id, k, exercises.elsewhere.text())


def test_asking_an_exercise_shows_the_step_it_asks_about(qtbot, window):
    """The z-buffer lesson's first question is asked on the cleared buffers ("Once all three polygons
    are drawn, which one will the z-buffer keep ...?"): asked while the window shows the finished
    picture of the last step, the picture answered it.  Bringing the Exercises tab to the front, and
    going to another exercise there, shows the step each asks about; a step the student picks while
    the question waits stays, and says so if its scene differs."""
    k = LESSONS["zbuffer"]
    window.lesson_panel.select(k, 3)  # on the Lessons tab: the finished picture
    exercises = window.exercise_panel
    assert exercises.exercise().step == 0
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: window.lesson_panel.step_index() == (k, 0))
    assert window.model.step == 0  # the buffers as cleared: nothing drawn yet
    exercises.next_button.click()  # "Green and blue are drawn; yellow comes next. ..."
    assert window.lesson_panel.step_index() == (k, 2) and window.model.step == 2
    window.lesson_panel.next()  # the student goes on to the last step: it stays
    assert window.lesson_panel.step_index() == (k, 3)
    window.lesson_panel.select(LESSONS["observer"], 1)  # another lesson: its step stays
    assert window.lesson_panel.step_index() == (LESSONS["observer"], 1)


def test_as_the_window_opens_the_exercises_ask_about_the_lesson_shown_and_start_its_step(qtbot, window):
    """As the window opens, the Lessons tab shows the first lesson, not yet started, on its scene (the
    lecture scene): the Exercises tab said "No lesson open" beside it.  Now it asks that lesson's
    questions, and brought to the front it starts the step the question asks about, whose readout of
    the asked pixel is then covered (asked on no step, nothing was withheld: a click on pixel
    (155, 110) answered "which object does the z-buffer keep there?")."""
    from views.panels.pane_cover import ANSWER, covered_with

    exercises, first = window.exercise_panel, window.lesson_panel.current_lesson()
    assert window.lessons.step is None and first.id == shipped_lessons()[0].id
    assert exercises.lesson is first and exercises.position.text() == "Exercise 1 of 3"
    assert window.model.scene == presets.lecture_scene() == first.steps[0].scene
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: window.lessons.step is not None)
    assert window.lessons.step is first.steps[exercises.exercise().step]
    assert window.windowTitle().startswith(f"Render Explorer — lesson: {window.lessons.step.title}")
    why = covered_with(window.tab("compare").widget.pixel_box, ANSWER)
    assert why is not None and why.startswith("Hidden while exercise 1 waits for your answer")


def test_a_scene_opened_before_any_step_stays_when_the_exercises_are_asked(qtbot, window):
    # Not the lesson's scene: an example from the File menu. Asking the exercises keeps it, and the
    # question says which scene it is about.
    from core import presets_trace

    window.load_preset("mirror_and_glass", presets_trace.mirror_and_glass)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    assert window.lessons.step is None
    assert window.model.scene == presets_trace.mirror_and_glass()
    assert window.exercise_panel.elsewhere.text() == (
        "<i>This question is about the scene of step 1; the window shows another scene. "
        "Show me brings it back.</i>")
