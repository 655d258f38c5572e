"""While an exercise waits for its answer, the window does not show it: the readouts that state what
the pipelines found (the picked pixel's ray tree and history, the polygon drawn, a face's side) are
covered with a sheet saying why, and for a pick-a-picture question the Four views too.  Answered
right, revealed, or back on the Lessons tab, they show again."""

from hand_rays import shadow_blockers
from PySide6.QtCore import QPoint
from PySide6.QtWidgets import QApplication
from shipped_exercises import seed_drawing
from window_helpers import RENDER_TIMEOUT_MS

from app.lessons.runner import FACE_SIDE_OVERLAY
from app.window.window_layout import in_front
from core.files.lesson_file import shipped_lessons
from views.panels.pane_cover import ANSWER, PaneCover, covered_with

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def _ask(qtbot, window, lesson: str, step: int, exercise: int, drawn: int | None = None):
    """Show ``lesson``'s step ``step`` and ask its exercise ``exercise`` with the Exercises tab in front
    (its variant ``drawn``: the student's seed is set to draw it)."""
    if drawn is not None:
        ex = shipped_lessons()[LESSONS[lesson]].exercises[exercise]
        window.exercise_panel.progress.settings.setValue("exercise_seed", seed_drawing(ex, exercise, drawn))
    window.lesson_panel.select(LESSONS[lesson], step)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    window.exercise_panel.go(exercise)
    return window.exercise_panel


def _seen_at_centre(widget):
    """The widget a user sees at the middle of ``widget``."""
    return QApplication.widgetAt(widget.mapToGlobal(QPoint(widget.width() // 2, widget.height() // 2)))


def _choose(qtbot, exercises, label: str) -> str:
    """Choose the answer ``label`` and check it; the verdict, once the pipelines have judged it."""
    next(b for b in exercises.choices.buttons() if b.text() == label).setChecked(True)
    exercises.feedback.clear()
    exercises.check()
    qtbot.waitUntil(lambda: exercises.feedback.text() != "", timeout=RENDER_TIMEOUT_MS)
    return exercises.feedback.text()


def test_the_ray_tree_that_names_the_blocker_is_covered_until_the_question_is_answered(qtbot, window):
    """The shadow-ray step picks pixel (230, 155) and its ray tree names what blocks the shadow ray,
    what the second exercise asks of another pixel.  Asked, the tree is covered; a wrong answer keeps
    it covered, the right one uncovers it.  This student draws pixel (196, 122): tested against every
    object, its ground point's shadow ray meets the cube before the light."""
    panel = window.tab("image order").widget
    exercises = _ask(qtbot, window, "ray_casting", 1, 1, drawn=0)
    assert exercises.question.text() == "What blocks the shadow ray of pixel (196, 122)?"
    scene = shipped_lessons()[LESSONS["ray_casting"]].steps[1].scene
    assert shadow_blockers(scene, 196, 122) == ("ground", ["cube"])
    qtbot.waitUntil(lambda: window.showing_full("image order") and window.model.ray_pixel == (230, 155),
                    timeout=RENDER_TIMEOUT_MS)
    why = covered_with(panel.details, ANSWER)
    assert why is not None and why.startswith("Hidden while exercise 2 waits for your answer")
    assert isinstance(_seen_at_centre(panel.tree), PaneCover)
    assert not panel.tree.isEnabled()  # Tab does not walk into it unseen
    assert _choose(qtbot, exercises, "cone").startswith("“cone” is not the answer")
    assert covered_with(panel.details, ANSWER) is not None
    assert _choose(qtbot, exercises, "cube").startswith("Right")
    assert covered_with(panel.details, ANSWER) is None
    assert _seen_at_centre(panel.tree) is panel.tree.viewport() and panel.tree.isEnabled()
    exercises.go(0)  # asked again: "Click a pixel in the cube's shadow."
    assert covered_with(panel.details, ANSWER) is not None


def test_reveal_or_the_lessons_tab_shows_the_readouts_again_and_every_pane_that_reads_a_pixel_is_covered(
        qtbot, window):
    exercises = _ask(qtbot, window, "two_orders", 0, 0)  # what object order's z-buffer keeps at a pixel
    readouts = [window.tab("object order").widget.details, window.tab("object order").widget.step_caption,
                window.tab("image order").widget.details, window.tab("compare").widget.pixel_box]
    assert all(covered_with(pane, ANSWER) for pane in readouts)
    assert covered_with(window.tab("object order").widget.step_caption, ANSWER) \
        == "Hidden until exercise 1 is answered"
    assert covered_with(window.tab("four views").widget, ANSWER) is None  # no picture is asked for
    window.lesson_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.lesson_dock))
    assert not any(covered_with(pane, ANSWER) for pane in readouts)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: all(covered_with(pane, ANSWER) for pane in readouts))
    exercises.reveal()
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("The answer:"), timeout=RENDER_TIMEOUT_MS)
    assert not any(covered_with(pane, ANSWER) for pane in readouts)


def test_a_pick_a_picture_question_covers_the_four_views_whose_titled_pictures_are_the_answer(qtbot, window):
    exercises = _ask(qtbot, window, "three_views", 1, 3)
    assert exercises.question.text() == "Question 3. Which picture is the top view?"
    four_views = window.tab("four views").widget
    qtbot.waitUntil(lambda: window.current.title == "Four views" and four_views.isVisible())
    assert covered_with(four_views, ANSWER) is not None
    assert isinstance(_seen_at_centre(four_views), PaneCover)
    qtbot.waitUntil(lambda: len(exercises.picture_keys) == 4, timeout=RENDER_TIMEOUT_MS)
    exercises.choices.button(exercises.picture_keys.index("top")).setChecked(True)
    exercises.check()
    qtbot.waitUntil(lambda: exercises.waiting_for is None)
    assert covered_with(four_views, ANSWER) is None


def test_the_face_sides_words_leave_the_3d_pane_while_the_back_face_question_is_asked(qtbot, window):
    """The back-face step labels triangle 2's normal "N: back face": a face's side, what its first
    exercise asks of another face.  The face and its normal stay drawn.  This student draws the face
    with corners A = (-1.2, 0, -1.2), B = (-1.2, 0, 1.2), C = (0, 2.2, 0): N = (B - A) × (C - A) =
    (-5.28, 2.88, 0), E - A = (3.7, 3.2, 7.7), N · (E - A) = -10.32 < 0, so it is culled."""
    window.lesson_panel.select(LESSONS["back_faces"], 0)
    view = window.scene_view
    qtbot.waitUntil(lambda: FACE_SIDE_OVERLAY in view.overlay_names(), timeout=RENDER_TIMEOUT_MS)
    assert list(view.overlay_parts(FACE_SIDE_OVERLAY)[0].point_data["labels"]) == ["N: back face"]
    exercises = _ask(qtbot, window, "back_faces", 0, 0, drawn=1)
    assert "corners ((-1.2, 0, -1.2), (-1.2, 0, 1.2), (0, 2.2, 0))" in exercises.question.text()
    assert FACE_SIDE_OVERLAY not in view.overlay_names() and "lesson" in view.overlay_names()
    assert _choose(qtbot, exercises, "yes").startswith("Right")
    assert FACE_SIDE_OVERLAY in view.overlay_names()


def test_the_picked_pixels_rays_leave_the_3d_pane_and_the_steps_pointer_the_status_bar(qtbot, window):
    """The observer lesson's second exercise asks about the objects' places in observer B's frustum;
    its step points at one of them: "Look at object 'object 5'".  The shadow step's 3D pane draws the
    picked pixel's shadow ray ending at the cone, what the second exercise there asks of a pixel."""
    window.lesson_panel.select(LESSONS["observer"], 1)
    assert window.statusBar().currentMessage() == "Look at object 'object 5'"
    _ask(qtbot, window, "observer", 1, 1)
    assert window.statusBar().currentMessage() == ""
    view = window.scene_view
    window.lesson_panel.select(LESSONS["ray_casting"], 1)
    window.lesson_dock.raise_()
    qtbot.waitUntil(lambda: "ray-tree" in view.overlay_names(), timeout=RENDER_TIMEOUT_MS)
    _ask(qtbot, window, "ray_casting", 1, 1)
    assert "ray-tree" not in view.overlay_names() and "lesson" in view.overlay_names()
    window.lesson_dock.raise_()
    qtbot.waitUntil(lambda: "ray-tree" in view.overlay_names())


def test_on_another_scene_nothing_is_covered(qtbot, window):
    """File → Lecture scene while an exercise is asked: the readouts are of a scene the exercise does
    not ask about."""
    _ask(qtbot, window, "two_orders", 0, 0)
    details = window.tab("object order").widget.details
    assert covered_with(details, ANSWER) is not None
    window.load_preset("lecture", lambda: window.model.scene)
    assert covered_with(details, ANSWER) is None
