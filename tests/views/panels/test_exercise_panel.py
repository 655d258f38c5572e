"""The exercise panel: asked, answered, judged at once with one sentence (why, when right; what is
wrong, never the answer, when wrong), a second try, Enter to check, reveal, progress kept across
restarts and reset, and the question put to the room."""

import pytest
from PySide6.QtCore import QSettings, Qt
from PySide6.QtWidgets import QApplication
from qt_fixtures import shown_widget, wheel_over
from shipped_exercises import seed_drawing

from core.lessons.lesson_file import shipped_lessons
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
    assert not panel.room_button.isVisible()  # "Show answers (Space)" with nothing to show ...
    panel.set_room(True)
    assert not panel.room_button.isVisible()  # ... presenting too


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


def _draw(settings, lesson, index, k):
    """Make this student's seed draw variant ``k`` of the lesson's exercise ``index``."""
    ex = lesson.exercises[index]
    settings.setValue("exercise_seed", seed_drawing(ex, index, k))
    return ex.variants[k]


def test_a_right_choice_is_praised_and_recorded_as_right_at_first_try(panel, settings):
    lesson = BY_ID["zbuffer"]
    assert "(87, 74)" in _draw(settings, lesson, 0, 0).question  # this student draws pixel (87, 74)
    panel.set_lesson(lesson)
    assert panel.question.text().endswith("which one will the z-buffer keep at pixel (87, 74)?")
    labels = [b.text() for b in panel.choices.buttons()]
    panel.choices.button(labels.index("blue")).setChecked(True)  # blue is nearest at (87, 74)
    panel.check()
    assert panel.feedback.text().startswith("Right: blue.") and "nearest" in panel.feedback.text()
    assert ExerciseProgress(settings).outcome("zbuffer", 0) == FIRST_TRY  # a fresh reader: on disk


# The second segment of the ray-sphere exercises, worked by hand: (1, 5, 4) to (-1, 4, 6), centre
# (1, 7, 8), r = 5.  (i, j, k) = (-2, -1, 2): a = 4 + 1 + 4 = 9; start minus centre (0, -2, -4):
# b = 2(0 + 2 - 8) = -12, c = 0 + 4 + 16 - 25 = -5; Δ = 144 + 180 = 324, √Δ = 18;
# t1 = (12 - 18) / 18 = -1/3, t2 = (12 + 18) / 18 = 5/3.  The start is inside (c < 0): the first
# crossing is t2.
SEGMENT_2 = {"a": 9, "Δ": 324, "t1": -1 / 3, "t2": 5 / 3}


def test_a_wrong_number_gets_a_second_try_then_reveal_gives_the_pipelines_answer(panel, settings):
    lesson = BY_ID["ray_sphere"]
    _draw(settings, lesson, 0, 1)  # the exercises share one draw: every one asks this segment
    panel.set_lesson(lesson)
    panel.go(3)  # the discriminant, 324
    assert panel.question.text().startswith("Your segment from (1, 5, 4) to (-1, 4, 6)")
    panel.number_edit.setText("32.4")
    panel.check()
    assert panel.feedback.text() == "No: 32.4 is too low. Try once more."  # not the answer
    panel.number_edit.setText("300")
    panel.check()
    assert panel.feedback.text() == "Not quite: 300 is too low. Press Reveal for the answer."
    panel.number_edit.setText("forty")
    panel.check()
    assert panel.feedback.text().startswith("Type a number:") and panel.tries == 2
    panel.number_edit.setText(str(SEGMENT_2["Δ"]))
    panel.check()
    assert panel.feedback.text().startswith("Right: the pipelines compute 324")
    assert ExerciseProgress(settings).outcome("ray_sphere", 3) == LATER
    panel.go(4)  # t1
    panel.reveal()
    assert float(panel.number_edit.text()) == pytest.approx(SEGMENT_2["t1"], abs=1e-5)
    assert ExerciseProgress(settings).outcome("ray_sphere", 4) == REVEALED


def test_an_order_and_a_clicked_pixel_are_judged(panel, qtbot):
    panel.set_lesson(BY_ID["transparency"])
    assert [panel.order_list.item(i).text() for i in range(3)] == ["red pane", "green pane", "blue pane"]
    panel.check()  # as listed: nearest first, wrong; only the green pane, in the middle, is in its place
    assert panel.feedback.text() == "Not that order: 1 of 3 in its place. Try once more."
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


def test_resizes_and_a_new_text_size_in_one_turn_lay_the_question_out_once(panel, monkeypatch):
    # Entering presentation mode resizes the panel and its scroll area and sets a new text size, all in
    # one turn; each sizing of the question put to the room lays out the window's layouts first.
    panel.set_lesson(BY_ID["zbuffer"])
    panel.set_room(True)
    QApplication.processEvents()
    laid_out = []
    rest_height = panel._rest_height
    monkeypatch.setattr(panel, "_rest_height", lambda: laid_out.append(1) or rest_height())
    font = panel.font()
    font.setPointSizeF(1.5 * font.pointSizeF())
    panel.resize(520, 640)
    panel.setFont(font)
    panel.resize(560, 700)
    QApplication.processEvents()
    assert len(laid_out) == 1
    assert panel.question.font().pointSizeF() > font.pointSizeF()  # sized for the new text size


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


def test_no_wrong_answer_is_told_the_right_one(panel, settings):
    """A wrong choice, number, order or pixel is told what is wrong with it, not the answer: the
    second try would be pointless otherwise, and so would Reveal."""
    panel.set_lesson(BY_ID["two_orders"])  # the cone is in front at (155, 110): the z-buffer keeps it
    labels = [b.text() for b in panel.choices.buttons()]
    panel.choices.button(labels.index("cube")).setChecked(True)
    panel.check()
    assert panel.feedback.text() == "“cube” is not the answer. Try once more."
    panel.set_lesson(BY_ID["perspective"])  # A′ lands at one pixel: a wrong click may not say where
    panel.click(1, 1)
    assert panel.feedback.text() == "Not there: it does not land at pixel (1, 1). Try once more."
    _draw(settings, BY_ID["ray_sphere"], 0, 1)
    panel.set_lesson(BY_ID["ray_sphere"])
    panel.go(7)  # continued as a ray, the first crossing is the larger root: the start is inside
    labels = [b.text() for b in panel.choices.buttons()]
    assert labels == ["t1, the smaller root", "t2, the larger root"]  # the question's names, not code's
    panel.choices.button(0).setChecked(True)
    panel.check()
    assert panel.feedback.text() == "“t1, the smaller root” is not the answer. Try once more."
    panel.go(5)  # t2 = 5/3 = 1.667: no hint of it before an answer
    assert "1.6" not in panel.number_edit.placeholderText()
    panel.number_edit.setText("x")
    panel.check()
    assert "1.6" not in panel.feedback.text()


def test_enter_checks_a_typed_number_a_chosen_answer_and_an_order(panel, qtbot, settings):
    _draw(settings, BY_ID["ray_sphere"], 0, 1)
    panel.set_lesson(BY_ID["ray_sphere"])  # a = 2² + 1² + 2² = 9
    panel.number_edit.setFocus()
    qtbot.keyClicks(panel.number_edit, str(SEGMENT_2["a"]))
    qtbot.keyClick(panel.number_edit, Qt.Key.Key_Return)
    assert panel.feedback.text().startswith("Right: the pipelines compute 9") and panel.tries == 1
    # Why, in the drawn segment's numbers: its own (i, j, k), not the lecture's (8, 5, 4).
    assert panel.feedback.text().endswith("a = i² + j² + k² with (i, j, k) = (-2, -1, 2).")
    # The last step's triangle, corners on the centres of (2, 2), (12, 2), (8, 10): pixel (10, 6)'s
    # centre (10.5, 6.5) lies halfway along the edge from (12.5, 2.5) to (8.5, 10.5), a right edge
    # (the third corner lies to its left): the top-left rule leaves the pixel to the background.
    assert "(10, 6)" in _draw(settings, BY_ID["rasterization"], 0, 0).question
    panel.set_lesson(BY_ID["rasterization"])
    labels = [b.text() for b in panel.choices.buttons()]
    button = panel.choices.button(labels.index("nothing (the background)"))
    button.setFocus()
    qtbot.keyClick(button, Qt.Key.Key_Space)  # chosen from the keyboard
    qtbot.keyClick(button, Qt.Key.Key_Enter)
    assert panel.feedback.text().startswith("Right: nothing (the background).") and panel.tries == 1


def test_an_order_is_made_from_the_keyboard_with_alt_up_and_down(panel, qtbot):
    """Sorted as the lecture says, the panes are drawn farthest first: blue, green, red (the red pane
    at z = 1.4 is nearest; listed red, green, blue)."""
    panel.set_lesson(BY_ID["transparency"])
    items = panel.order_list
    assert [items.item(i).text() for i in range(3)] == ["red pane", "green pane", "blue pane"]
    assert items.height() < 6 * items.sizeHintForRow(0)  # as tall as its three rows, not a screenful
    font = items.font()
    font.setPointSizeF(2 * font.pointSizeF())
    items.setFont(font)  # a text size twice as large: the rows still all show
    qtbot.waitUntil(lambda: items.height() >= 3 * items.sizeHintForRow(0))
    items.setFocus()
    items.setCurrentRow(2)
    qtbot.keyClick(items, Qt.Key.Key_Up, Qt.KeyboardModifier.AltModifier)
    qtbot.keyClick(items, Qt.Key.Key_Up, Qt.KeyboardModifier.AltModifier)  # blue to the top: blue, red, green
    assert items.currentItem().text() == "blue pane"  # the moved item stays selected
    qtbot.keyClick(items, Qt.Key.Key_Down)  # select red
    qtbot.keyClick(items, Qt.Key.Key_Down, Qt.KeyboardModifier.AltModifier)  # red below green
    assert [items.item(i).text() for i in range(3)] == ["blue pane", "green pane", "red pane"]
    qtbot.keyClick(items, Qt.Key.Key_Return)
    assert panel.feedback.text().startswith("Right: blue pane → green pane → red pane.")


def test_show_me_picks_the_pixel_the_question_names(panel, qtbot):
    panel.set_lesson(BY_ID["two_orders"])
    assert "(155, 110)" in panel.question.text()
    with qtbot.waitSignal(panel.show_me) as shown:
        panel.show_button.click()
    assert shown.args == [0, (155, 110)]
    panel.set_lesson(BY_ID["ray_sphere"])  # names no pixel: the step alone
    with qtbot.waitSignal(panel.show_me) as shown:
        panel.show_button.click()
    assert shown.args == [1, None]


def test_in_a_short_dock_check_and_the_verdict_stay_in_view_below_the_pictures(qtbot, settings):
    """Four pictures filled a 340 x 330 dock (the Exercises tab under the 3D pane at 1280 x 720) and
    pushed Check and the verdict out of view: the pictures now scroll, Check and the verdict not."""
    panel = shown_widget(qtbot, ExercisePanel(ExerciseProgress(settings)), 340, 260)
    lesson = BY_ID["three_views"]
    panel.set_lesson(lesson)
    panel.go(next(i for i, e in enumerate(lesson.exercises) if e.question.endswith("top view?")))
    qtbot.waitUntil(lambda: len(panel.picture_views) == 4)
    qtbot.waitUntil(lambda: panel.scroll.verticalScrollBar().maximum() > 0)  # the pictures do not all fit

    def shown_whole(widget):
        top_left = widget.mapTo(panel, widget.rect().topLeft())
        return widget.isVisible() and top_left.y() >= 0 and top_left.y() + widget.height() <= panel.height()

    assert shown_whole(panel.check_button) and shown_whole(panel.reveal_button)
    wrong = next(i for i, key in enumerate(panel.picture_keys) if key != "top")
    panel.picture_views[wrong].pixel_clicked.emit(5, 5)
    panel.check()
    qtbot.waitUntil(lambda: shown_whole(panel.feedback) and panel.feedback.height() > 0)
    assert panel.feedback.text().startswith("Not that one")


def test_a_show_me_answered_after_the_student_moved_on_shows_nothing(qtbot, settings):
    """Show me on a click-a-pixel exercise asks the pipelines for a right pixel, off the GUI thread;
    if the student goes to another lesson meanwhile, the late answer must not show the old exercise's
    step in the new lesson (it selected step 2 of a lesson of one step, and raised)."""
    pending = []
    panel = shown_widget(qtbot, ExercisePanel(ExerciseProgress(settings),
                                              run=lambda work, done: pending.append((work, done))), 500, 600)
    shown = []
    panel.show_me.connect(lambda step, pixel: shown.append((step, pixel)))
    panel.set_lesson(BY_ID["ray_casting"])
    assert panel.exercise().kind == "click_pixel"
    panel.show_button.click()
    panel.set_lesson(BY_ID["ray_triangle"])  # the student moves on before the pixel is found
    work, done = pending.pop()
    done(work())
    assert shown == []
    panel.set_lesson(BY_ID["ray_casting"])
    panel.show_button.click()
    work, done = pending.pop()
    done(work())
    assert shown and shown[0][0] == panel.exercise().step  # in time, it shows the step


def test_the_last_exercises_answer_field_never_becomes_a_window_of_its_own(panel, qtbot):
    # A number question, then a choice in the same turn (a script, a GUI test, a lesson opened and
    # an exercise chosen at once): the number field, taken out of the panel, was shown a moment later
    # as a window of its own, by the show Qt had queued when the field went into the panel.
    kinds = {}
    for lesson in (BY_ID["ray_sphere"], BY_ID["transparency"], BY_ID["three_views"], BY_ID["ray_casting"]):
        for i, ex in enumerate(lesson.exercises):
            kinds.setdefault(ex.kind, (lesson, i))
    assert set(kinds) == {"number", "click_pixel", "choose_one", "order", "pick_picture"}
    fields = (panel.number_edit, panel.pixel_edit, panel.order_list, panel.picture_grid)
    for first, then in ((a, b) for a in kinds.values() for b in kinds.values() if a is not b):
        panel.set_lesson(first[0])
        panel.go(first[1])
        panel.set_lesson(then[0])
        panel.go(then[1])
        QApplication.sendPostedEvents()
        QApplication.processEvents()
        assert not [w for w in QApplication.topLevelWidgets() if w.isVisible() and w is not panel]
        assert not any(field.isWindow() for field in fields)
        shown = [field for field in fields if field.isVisible()]
        assert len(shown) == (panel.exercise().kind != "choose_one"), panel.exercise().kind


def test_over_an_exercises_pictures_the_wheel_is_left_to_the_panel_and_ctrl_wheel_zooms_them(panel, qtbot):
    # The pictures zoom with the wheel elsewhere; here four of them may not fit the panel, which scrolls,
    # and the wheel over a picture would no longer scroll it.  A wheel event a picture leaves (does not
    # accept) goes on to the scroll area around it (Qt passes on only the real ones: so it is checked
    # here that the picture leaves it).
    lesson = BY_ID["three_views"]
    panel.set_lesson(lesson)
    panel.go(next(i for i, e in enumerate(lesson.exercises) if e.question.endswith("top view?")))
    qtbot.waitUntil(lambda: len(panel.picture_views) == 4)
    first = panel.picture_views[0]
    at = first.rect().center()

    def wheel(notches: int, modifiers) -> bool:
        return wheel_over(first, at, notches, modifiers)

    assert not wheel(-1, Qt.KeyboardModifier.NoModifier) and not wheel(1, Qt.KeyboardModifier.NoModifier)
    assert first.zoom == 1.0  # left to the panel, to scroll it
    assert not wheel(-1, Qt.KeyboardModifier.ControlModifier)  # out: whole already, left too
    assert wheel(1, Qt.KeyboardModifier.ControlModifier) and first.zoom > 1
    assert all(view.zoom == first.zoom for view in panel.picture_views)  # together
