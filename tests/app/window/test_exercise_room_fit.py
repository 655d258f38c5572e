"""Presenting at x2 on a 1280 x 720 screen, a question put to the room reads whole in the Exercises dock,
with its Show answers button in view under it."""

import pytest
from PySide6.QtCore import Qt
from window_helpers import presenting_on_1280x720

from app.window.window_layout import in_front
from core.lessons.lesson_file import shipped_lessons
from views.panels.exercise_panel import ROOM_LEAST


@pytest.mark.parametrize(("lesson_id", "k"), [("ray_sphere", 0), ("ray_tracing", 2)])
def test_presenting_at_x2_on_1280x720_a_long_question_and_its_show_answers_are_in_view(
        qtbot, monkeypatch, lesson_id, k):
    # At 1.8 times the text of x2, ray_sphere's first question took seven lines and ran below the fold,
    # Show answers a scroll away.  The question takes the size that leaves them in view, and the 3D pane
    # gives the exercises its room as it does to a lesson's words.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    lessons = [lesson.id for lesson in shipped_lessons()]
    lesson = shipped_lessons()[lessons.index(lesson_id)]
    window.lesson_panel.select(lessons.index(lesson_id), lesson.exercises[k].step)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    panel = window.exercise_panel
    panel.go(k)
    question, view = panel.question, panel.scroll.viewport()

    def in_view() -> bool:
        bottom = panel.room_button.mapTo(view, panel.room_button.rect().bottomLeft()).y()
        assert question.height() >= question.heightForWidth(question.width())
        assert panel.room_button.isVisible() and bottom <= view.height()
        assert panel.scroll.verticalScrollBar().value() == 0
        return True

    qtbot.waitUntil(in_view, timeout=5000)
    assert question.font().pointSizeF() >= ROOM_LEAST * panel.font().pointSizeF() and question.font().bold()
    window.editor.stack.setClean()
    window.presentation.set_presenting(False)


def _pictures_put_to_the_room(qtbot, window):
    """The Exercises dock in front with "Which picture is the top view?" put to the room and its
    answers shown: the panel, once its four pictures are drawn."""
    lessons = [lesson.id for lesson in shipped_lessons()]
    lesson = shipped_lessons()[lessons.index("three_views")]
    k = next(i for i, e in enumerate(lesson.exercises) if e.question.endswith("top view?"))
    window.lesson_panel.select(lessons.index("three_views"), lesson.exercises[k].step)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    panel = window.exercise_panel
    panel.go(k)
    qtbot.waitUntil(lambda: len(panel.picture_views) == 4, timeout=60_000)
    panel.setFocus()
    qtbot.keyClick(panel, Qt.Key.Key_Space)  # the answers, put to the room
    return panel


def _all_in_view(panel, least=(128, 96)) -> bool:
    view = panel.scroll.viewport()
    for picture in panel.picture_views:
        shown = picture.image_rect()
        bottom = picture.mapTo(view, picture.rect().bottomLeft()).y()
        assert shown.width() >= least[0] and shown.height() >= least[1], shown
        assert picture.isVisible() and bottom <= view.height()
    return True


def test_presenting_at_x2_on_1280x720_the_pictures_to_pick_take_the_room_and_are_all_in_view(
        qtbot, monkeypatch):
    # At a fixed 120 pixels high, the four pictures of "Which picture is the top view?" showed 88 x 66
    # under a question at 1.8 times the text, the column as narrow as with the 3D pane above it.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    panel = _pictures_put_to_the_room(qtbot, window)
    qtbot.waitUntil(lambda: _all_in_view(panel), timeout=5000)
    window.editor.stack.setClean()
    window.presentation.set_presenting(False)


def test_the_pictures_to_pick_refit_when_the_words_under_them_take_lines_and_give_them_back(
        qtbot, monkeypatch):
    # The words under the scroll area (the verdict) take its room without resizing the panel: the
    # pictures fitted only when the panel resized, so a verdict of several lines pushed the lower
    # row below the fold, and once it was short again they stayed small (once, 116 x 87 in the test
    # above: fitted while a message stood there).  Back to the same room, the same sizes.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    panel = _pictures_put_to_the_room(qtbot, window)
    qtbot.waitUntil(lambda: _all_in_view(panel), timeout=5000)
    roomy, said = panel.picture_views[0].image_rect().size(), panel.feedback.text()
    panel.feedback.setText("\n".join(["A verdict of three lines."] * 3))
    qtbot.waitUntil(lambda: _all_in_view(panel, least=(88, 66))
                    and panel.picture_views[0].image_rect().height() < roomy.height(), timeout=5000)
    panel.feedback.setText(said)
    qtbot.waitUntil(lambda: _all_in_view(panel) and panel.picture_views[0].image_rect().size() == roomy,
                    timeout=5000)
    window.editor.stack.setClean()
    window.presentation.set_presenting(False)
