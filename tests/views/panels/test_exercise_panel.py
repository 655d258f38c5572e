"""The exercise panel: asked, answered, judged at once with one sentence why, a second try,
reveal, progress kept across restarts and reset, and the question put to the room."""

import math

import pytest
from PySide6.QtCore import QSettings, Qt
from qt_fixtures import shown_widget

from core.files.lesson_file import shipped_lessons
from views.panels.exercise_panel import FIRST_TRY, LATER, REVEALED, ExercisePanel, ExerciseProgress

BY_ID = {lesson.id: lesson for lesson in shipped_lessons()}


@pytest.fixture
def settings(tmp_path):
    return QSettings(str(tmp_path / "progress.ini"), QSettings.Format.IniFormat)


@pytest.fixture
def panel(qtbot, settings):
    p = ExercisePanel(ExerciseProgress(settings))
    return shown_widget(qtbot, p, 500, 600)


def test_before_a_lesson_is_open_the_panel_says_how_to_open_one(panel):
    assert panel.position.text() == "No lesson open"
    assert "Lessons tab" in panel.question.text() and "PageDown" in panel.question.text()
    assert not panel.check_button.isEnabled()


def test_the_next_exercise_shows_only_its_own_answers(panel, qtbot):
    # One lesson's choices, then another lesson's number: no earlier radio button stays on screen.
    from PySide6.QtWidgets import QRadioButton

    def shown_choices():
        return sorted(b.text() for b in panel.findChildren(QRadioButton) if b.isVisible())

    panel.set_lesson(BY_ID["two_orders"])
    first = panel.exercise()
    assert first.kind == "choose_one"
    qtbot.waitUntil(lambda: len(shown_choices()) == len(first.args["choices"]))
    panel.set_lesson(BY_ID["ray_sphere"])  # its first exercise asks for a number
    assert panel.exercise().kind == "number"
    qtbot.waitUntil(lambda: shown_choices() == [] and panel.number_edit.isVisible())


def test_a_right_choice_is_praised_and_recorded_as_right_at_first_try(panel, settings):
    from core.lessons.exercises import variant

    lesson = BY_ID["zbuffer"]
    seed = next(s for s in range(100) if "(87, 74)" in variant(lesson.exercises[0], s).question)
    settings.setValue("exercise_seed", seed)  # this student draws pixel (87, 74)
    panel.set_lesson(lesson)
    assert panel.question.text().endswith("which one does the z-buffer keep at pixel (87, 74)?")
    labels = [b.text() for b in panel.choices.buttons()]
    panel.choices.button(labels.index("blue")).setChecked(True)  # blue is nearest at (87, 74)
    panel.check()
    assert panel.feedback.text().startswith("Right: blue.") and "nearest" in panel.feedback.text()
    assert ExerciseProgress(settings).outcome("zbuffer", 0) == FIRST_TRY  # a fresh reader: on disk


def test_a_wrong_number_gets_a_second_try_then_reveal_gives_the_pipelines_answer(panel, settings):
    panel.set_lesson(BY_ID["ray_sphere"])
    panel.go(3)  # the discriminant: 126² + 4·105·59 = 40656
    panel.number_edit.setText("4065.6")
    panel.check()
    assert panel.feedback.text().startswith("Not quite: the pipelines compute 40656")
    assert "Try once more" in panel.feedback.text()
    panel.number_edit.setText("forty")
    panel.check()
    assert panel.feedback.text() == "Type a number (for example 1.56)." and panel.tries == 1
    panel.number_edit.setText("40656")
    panel.check()
    assert panel.feedback.text().startswith("Right")
    assert ExerciseProgress(settings).outcome("ray_sphere", 3) == LATER
    panel.go(4)  # t1 = (126 - √40656) / 210
    panel.reveal()
    assert float(panel.number_edit.text()) == pytest.approx((126 - math.sqrt(40656)) / 210, abs=1e-5)
    assert ExerciseProgress(settings).outcome("ray_sphere", 4) == REVEALED


def test_an_order_and_a_clicked_pixel_are_judged(panel, qtbot):
    panel.set_lesson(BY_ID["transparency"])
    assert [panel.order_list.item(i).text() for i in range(3)] == ["red pane", "green pane", "blue pane"]
    panel.check()  # as listed: nearest first, wrong
    assert panel.feedback.text().startswith("Not that order: blue pane → green pane → red pane")
    panel.set_lesson(BY_ID["ray_casting"])
    with qtbot.waitSignal(panel.show_me) as shown:
        panel.show_button.click()
    step, pixel = shown.args
    assert step == 1 and pixel is not None
    panel.click(0, 0)  # the sky: nothing there casts a shadow
    assert panel.feedback.text().startswith("Not there: at pixel (0, 0)")
    panel.click(*pixel)
    assert panel.feedback.text().startswith(f"Right: at pixel {tuple(pixel)}")


def test_progress_is_summarised_and_reset(panel, settings):
    progress = ExerciseProgress(settings)
    lesson = BY_ID["ray_triangle"]
    progress.record(lesson.id, 0, FIRST_TRY)
    progress.record(lesson.id, 1, LATER)
    progress.record(lesson.id, 0, REVEALED)  # the first outcome stays
    assert progress.summary(lesson) == f"2/{len(lesson.exercises)} done, 1 right at first try"
    panel.set_lesson(lesson)
    panel.reset_button.click()
    assert ExerciseProgress(settings).summary(lesson) == ""


def test_put_to_the_room_the_question_is_large_and_the_answers_wait_for_space(panel, qtbot):
    panel.set_lesson(BY_ID["zbuffer"])
    size = panel.question.font().pointSizeF()
    panel.set_room(True)
    assert panel.question.font().pointSizeF() > 1.5 * size
    assert not panel.answer_area.isVisible() and panel.room_button.isVisible()
    panel.setFocus()
    qtbot.keyClick(panel, Qt.Key.Key_Space)
    assert panel.answer_area.isVisible()
    panel.go(1)  # the next question hides its answers again
    assert not panel.answer_area.isVisible()


def test_a_picture_is_picked_by_clicking_it_and_judged(panel, qtbot):
    lesson = BY_ID["three_views"]
    panel.set_lesson(lesson)
    k = next(i for i, e in enumerate(lesson.exercises) if e.question.endswith("top view?"))
    panel.go(k)
    qtbot.waitUntil(lambda: len(panel.picture_views) == 4)
    assert sorted(panel.picture_keys) == ["front", "observer", "side", "top"]
    wrong = next(i for i, key in enumerate(panel.picture_keys) if key != "top")
    panel.picture_views[wrong].pixel_clicked.emit(5, 5)  # a click on a picture picks it
    panel.check()
    assert panel.feedback.text().startswith("Not that one")
    panel.picture_views[panel.picture_keys.index("top")].pixel_clicked.emit(5, 5)
    panel.check()
    assert panel.feedback.text().startswith("Right: that is the top view.")
