"""While an exercise waits for its answer, the window does not show it: the readouts that state what
the pipelines found (the picked pixel's ray tree and history, the polygon drawn, a face's side) are
covered with a sheet saying why, and for a pick-a-picture question the Four views too.  Answered
right, revealed, or back on the Lessons tab, they show again."""

from hand_rays import shadow_blockers
from PySide6.QtCore import QPoint
from PySide6.QtWidgets import QApplication
from window_helpers import RENDER_TIMEOUT_MS, ask_exercise

from app.lessons.runner import FACE_SIDE_OVERLAY
from app.window.window_layout import in_front
from core.lessons.lesson_file import shipped_lessons
from views.panels.pane_cover import ANSWER, PaneCover, covered_with

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


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
    exercises = ask_exercise(qtbot, window, "ray_casting", 1, 1, drawn=0)
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
    exercises = ask_exercise(qtbot, window, "two_orders", 0, 0)  # what the z-buffer keeps at a pixel
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
    exercises = ask_exercise(qtbot, window, "three_views", 1, 3)
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
    exercise asks of another face (the face and its normal go too: see the last test).  This student
    draws the face with corners A = (-1.2, 0, -1.2), B = (-1.2, 0, 1.2), C = (0, 2.2, 0):
    N = (B - A) × (C - A) = (-5.28, 2.88, 0), E - A = (3.7, 3.2, 7.7), N · (E - A) = -10.32 < 0,
    so it is culled."""
    window.lesson_panel.select(LESSONS["back_faces"], 0)
    view = window.scene_view
    qtbot.waitUntil(lambda: FACE_SIDE_OVERLAY in view.overlay_names(), timeout=RENDER_TIMEOUT_MS)
    assert list(view.overlay_parts(FACE_SIDE_OVERLAY)[0].point_data["labels"]) == ["N: back face"]
    exercises = ask_exercise(qtbot, window, "back_faces", 0, 0, drawn=1)
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
    ask_exercise(qtbot, window, "observer", 1, 1)
    assert window.statusBar().currentMessage() == ""
    view = window.scene_view
    window.lesson_panel.select(LESSONS["ray_casting"], 1)
    window.lesson_dock.raise_()
    qtbot.waitUntil(lambda: "ray-tree" in view.overlay_names(), timeout=RENDER_TIMEOUT_MS)
    ask_exercise(qtbot, window, "ray_casting", 1, 1)
    assert "ray-tree" not in view.overlay_names() and "lesson" in view.overlay_names()
    window.lesson_dock.raise_()
    qtbot.waitUntil(lambda: "ray-tree" in view.overlay_names())


def test_on_another_scene_nothing_is_covered(qtbot, window):
    """File → Lecture scene while an exercise is asked: the readouts are of a scene the exercise does
    not ask about."""
    ask_exercise(qtbot, window, "two_orders", 0, 0)
    details = window.tab("object order").widget.details
    assert covered_with(details, ANSWER) is not None
    window.load_preset("lecture", lambda: window.model.scene)
    assert covered_with(details, ANSWER) is None


def _outlined_and_named(view):
    """The 3D pane's lesson marks: the bounds of each outlined part, and the names written."""
    parts = view.overlay_parts("lesson")
    names = [str(n) for p in parts if "labels" in p.point_data for n in p.point_data["labels"]]
    return [tuple(round(b, 6) for b in p.bounds) for p in parts if "labels" not in p.point_data], names


def test_the_3d_pane_marks_what_the_question_names_not_the_object_it_asks_for(qtbot, window):
    """The frustum step outlines the box behind the observer in yellow, its example of an object
    dropped before any pixel work, and its first exercise asks "Which object is dropped before any pixel
    work?".  Asked, the outline goes and the pane writes the names of the five objects offered, each
    alike; answered, the step's outline is back.  The back-face step outlines triangle 2 of the pyramid
    with its normal; its question asks about another face, given by its corners: asked, the step's
    face and normal go (the one would pass for the face asked, the other answers for it), and the
    pyramid, which the question names, is named."""
    window.lesson_panel.select(LESSONS["frustum"], 1)
    view = window.scene_view
    box = next(o for o in window.model.scene.objects if o.name == "box")
    low, high = box.vertices.min(axis=0), box.vertices.max(axis=0)
    box_bounds = tuple(round(float(v), 6) for k in range(3) for v in (low[k], high[k]))
    qtbot.waitUntil(lambda: "lesson" in view.overlay_names(), timeout=RENDER_TIMEOUT_MS)
    assert _outlined_and_named(view)[0] == [box_bounds]
    exercises = ask_exercise(qtbot, window, "frustum", 1, 0)
    assert exercises.question.text() == "Which object is dropped before any pixel work?"
    outlined, names = _outlined_and_named(view)
    assert outlined == []
    assert sorted(names) == ["box", "cone", "cube", "ground", "sphere"]
    assert _choose(qtbot, exercises, "box").startswith("Right")
    assert _outlined_and_named(view)[0] == [box_bounds]

    window.lesson_dock.raise_()  # the Lessons tab: nothing asked
    qtbot.waitUntil(lambda: in_front(window.lesson_dock))
    window.lesson_panel.select(LESSONS["back_faces"], 0)
    pyramid = next(o for o in window.model.scene.objects if o.name == "pyramid")
    corners = pyramid.vertices[pyramid.triangles[2]]
    triangle_2 = tuple(round(float(v), 6) for k in range(3)
                       for v in (corners[:, k].min(), corners[:, k].max()))
    assert triangle_2 in _outlined_and_named(view)[0]
    exercises = ask_exercise(qtbot, window, "back_faces", 0, 0, drawn=1)
    assert "The pyramid's face with corners ((-1.2, 0, -1.2)" in exercises.question.text()
    outlined, names = _outlined_and_named(view)
    assert outlined == [] and names == ["pyramid"]


def test_an_object_the_question_offers_as_an_answer_is_not_singled_out(qtbot, window):
    """Observer B's step outlines object 5; its question offers objects 1, 3 and 5 ("whose bounding
    sphere lies entirely inside the frustum?"): asked, no outline singles one of them out, and all
    three are named."""
    window.lesson_panel.select(LESSONS["observer"], 1)
    view = window.scene_view
    qtbot.waitUntil(lambda: len(_outlined_and_named(view)[0]) == 1)
    exercises = ask_exercise(qtbot, window, "observer", 1, 1)
    assert exercises.question.text().startswith("From observer B, whose bounding sphere")
    outlined, names = _outlined_and_named(view)
    assert outlined == [] and sorted(names) == ["object 1", "object 3", "object 5"]
