"""In the window, the traced picture is reached with Tab and its pixel picked from the keyboard: the
arrows move the pick (not the observer, whose keys they are elsewhere) and the ray tree follows;
Enter answers a click-a-pixel exercise with the pixel picked."""

import numpy as np
from hand_rays import shadow_blockers
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication, QCheckBox
from qt_fixtures import keys_listed, rgb_pixels, wheel_over
from window_helpers import RENDER_TIMEOUT_MS

from app.window.window_layout import in_front
from core.lessons.lesson_file import shipped_lessons

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def _tab_to(qtbot, window, widget) -> None:
    """Press Tab, as a user does, until ``widget`` has the keyboard focus."""
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    for _ in range(120):  # at most once round the window's focus chain
        if widget.hasFocus():
            return
        qtbot.keyClick(QApplication.focusWidget() or window, Qt.Key.Key_Tab)
    assert widget.hasFocus(), f"Tab never reached {widget}"


def test_the_arrows_move_the_traced_pixel_and_its_ray_tree_follows(qtbot, window):
    panel = window.tab("image order").widget
    image = panel.image
    assert window.current is window.tab("image order") and window.model.ray_pixel is None
    _tab_to(qtbot, window, image)
    camera = window.model.camera
    x, y = camera.width // 2, camera.height // 2
    qtbot.keyClick(image, Qt.Key.Key_Right)  # nothing picked: the centre
    qtbot.keyClick(image, Qt.Key.Key_Right)
    assert window.model.ray_pixel == (x + 1, y)
    qtbot.waitUntil(lambda: window.ray_tree is not None and window.ray_tree[:2] == (x + 1, y),
                    timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: panel.verdict.text().startswith(f"Why pixel ({x + 1}, {y}):"))
    assert panel.tree.topLevelItemCount() == 1  # the primary ray, its children under it
    assert window.model.camera == camera  # the arrows picked pixels; the observer did not orbit
    qtbot.keyClick(image, Qt.Key.Key_Down, Qt.KeyboardModifier.ShiftModifier)
    qtbot.waitUntil(lambda: panel.verdict.text().startswith(f"Why pixel ({x + 1}, {y + 10}):"),
                    timeout=RENDER_TIMEOUT_MS)
    assert "Enter" in keys_listed(window) and "Shift+arrows" in keys_listed(window)


def test_a_click_a_pixel_exercise_is_answered_from_the_keyboard(qtbot, window):
    """The shadow step picks pixel (230, 155), in the cone's shadow; the exercise asks for a pixel in
    the cube's.  Enter on the step's pick answers nothing.  The student walks to (200, 125) with
    Shift+arrows (which answer nothing either: the pixel's readout is what they look at) and answers
    with Enter."""
    lessons, exercises = window.lesson_panel, window.exercise_panel
    k = LESSONS["ray_casting"]
    lessons.select(k, 1)
    assert exercises.question.text() == "Click a pixel in the cube's shadow."
    scene = shipped_lessons()[k].steps[1].scene
    assert shadow_blockers(scene, 200, 125) == ("ground", ["cube"])  # by brute force: in the cube's shadow
    assert shadow_blockers(scene, 230, 155) == ("ground", ["cone"])
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    image = window.tab("image order").widget.image
    qtbot.waitUntil(lambda: image.picked == (230, 155), timeout=RENDER_TIMEOUT_MS)
    _tab_to(qtbot, window, image)
    qtbot.keyClick(image, Qt.Key.Key_Return)
    assert exercises.pixel_edit.text() == "" and exercises.feedback.text() == ""  # the step's pick
    for key in (Qt.Key.Key_Left, Qt.Key.Key_Up) * 3:
        qtbot.keyClick(image, key, Qt.KeyboardModifier.ShiftModifier)
    assert window.model.ray_pixel == (200, 125)
    assert exercises.pixel_edit.text() == "" and exercises.feedback.text() == ""  # nothing answered yet
    qtbot.keyClick(image, Qt.Key.Key_Return)
    assert exercises.pixel_edit.text() == "200, 125"
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("Right"), timeout=RENDER_TIMEOUT_MS)
    assert "1/3 done, 1 right at first try" in lessons.list.item(k).text()


def test_the_z_buffer_picture_answers_a_click_a_pixel_exercise_too(qtbot, window):
    lessons, exercises = window.lesson_panel, window.exercise_panel
    lessons.select(LESSONS["observer"], 0)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    exercises.go(2)
    window.show_tab("Object order")
    depth = window.tab("object order").widget.depth.image
    qtbot.waitUntil(lambda: depth.qimage is not None and depth.isVisible(), timeout=RENDER_TIMEOUT_MS)
    qtbot.mouseClick(depth, Qt.MouseButton.LeftButton, pos=depth.widget_pos(0, 0).toPoint())
    assert exercises.pixel_edit.text() == "0, 0"
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("Not there"), timeout=RENDER_TIMEOUT_MS)


def test_presenting_a_focused_picture_keeps_the_arrow_keys_which_step_through_the_lesson_elsewhere(
        qtbot, window):
    lessons = window.lesson_panel
    lessons.select(LESSONS["ray_casting"], 1)
    window.presentation.set_presenting(True)
    qtbot.waitUntil(window.presentation.settled)
    image = window.tab("image order").widget.image
    qtbot.waitUntil(lambda: image.picked == (230, 155), timeout=RENDER_TIMEOUT_MS)
    _tab_to(qtbot, window, image)
    qtbot.keyClick(image, Qt.Key.Key_Right)
    qtbot.keyClick(image, Qt.Key.Key_Right)
    assert window.model.ray_pixel == (232, 155) and lessons.step_index() == (LESSONS["ray_casting"], 1)
    button = window.tab("image order").widget.findChild(QCheckBox)  # elsewhere the arrows are the clicker's
    button.setFocus()
    qtbot.waitUntil(button.hasFocus)
    qtbot.keyClick(button, Qt.Key.Key_Right)
    assert lessons.step_index() != (LESSONS["ray_casting"], 1)  # the next step
    window.presentation.set_presenting(False)


def test_the_object_order_buffers_zoom_together_and_the_keys_zoom_not_the_observer(qtbot, window):
    """The image memory and the z-buffer show the same pixels: zoomed in one (here with +, which moves
    the observer closer when no picture has the focus), the other shows the same part; 0 shows both
    whole again.  Help → Keys says so."""
    window.tab_widget.setCurrentIndex(window.tabs.index(window.tab("object order")))
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    image, depth = panel.image, panel.depth.image
    camera = window.model.camera
    _tab_to(qtbot, window, image)
    qtbot.keyClick(image, Qt.Key.Key_Plus, Qt.KeyboardModifier.ShiftModifier)
    qtbot.keyClick(image, Qt.Key.Key_Plus, Qt.KeyboardModifier.ShiftModifier)
    assert image.zoom > 1 and depth.zoom == image.zoom and depth.focus == image.focus
    assert window.model.camera == camera  # the observer did not step closer
    qtbot.keyClick(image, Qt.Key.Key_0)
    assert image.zoom == depth.zoom == 1.0
    assert "Scroll" in keys_listed(window) and "zoom" in keys_listed(window)


def test_a_lesson_step_or_a_new_scene_shows_the_pictures_whole_the_observer_moving_keeps_the_zoom(
        qtbot, window):
    """Zoomed into the lecture scene's pixels, the next lesson step (here one of other pixels at the same
    count) would have shown its picture zoomed into wherever that was."""
    lessons = window.lesson_panel
    k = LESSONS["rasterization"]
    lessons.select(k, 1)  # the lecture scene, 320 x 240
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: panel.image.qimage is not None, timeout=RENDER_TIMEOUT_MS)
    assert wheel_over(panel.image, panel.image.rect().center(), 4)
    assert panel.image.zoom > 1 and panel.depth.image.zoom > 1
    window.model.set_camera(window.model.camera.replace(eye=(0.5, 1.6, 6.2)))  # the observer moves
    assert panel.image.zoom > 1
    size = (window.model.camera.width, window.model.camera.height)
    other = next((i, j) for i, lesson in enumerate(shipped_lessons()) for j, step in enumerate(lesson.steps)
                 if (i, j) != (k, 1) and "object order" in step.panes
                 and (step.scene.camera.width, step.scene.camera.height) == size)
    lessons.select(*other)  # another step, pictures of as many pixels
    assert panel.image.zoom == panel.depth.image.zoom == 1.0
    assert wheel_over(panel.image, panel.image.rect().center(), 4)
    opened = next(step.scene for lesson in shipped_lessons() for step in lesson.steps
                  if step.scene != window.model.scene)
    window.model.set_scene(opened)  # another scene, as from a file
    assert panel.image.zoom == panel.depth.image.zoom == 1.0


def _outline_extent(view) -> tuple[float, float, float, float] | None:
    """Where the highlight's outline (its own magenta) is painted in ``view`` (a screenshot): its
    bounding box's centre and size, as shares of the room the picture is drawn in (None: nowhere)."""
    ys, xs = np.nonzero((rgb_pixels(view.grab().toImage()) == (0xFF, 0x2B, 0xD6)).all(axis=2))
    if not len(xs):
        return None
    room = view.rect().adjusted(3, 3, -3, -3)  # image_view.FOCUS_MARGIN
    return ((min(xs) + max(xs)) / 2 / view.width(), (min(ys) + max(ys)) / 2 / view.height(),
            (max(xs) - min(xs)) / room.width(), (max(ys) - min(ys)) / room.height())


def test_z_zooms_the_buffers_onto_the_highlighted_face_for_the_hall_and_again_shows_them_whole(qtbot, window):
    """Presenting at x2 on a 1280 x 720 projector, the rasterization step's highlighted face of the cube
    is a few screen pixels tall in the buffers.  View → Zoom the pictures to the highlight (Z) zooms
    both onto it: its outline then spans 60% of each pane along one side and no more along the other,
    in the middle; Z again shows them whole."""
    window.presentation.set_presenting(True)
    window.presentation.set_scale(2.0)
    qtbot.waitUntil(window.presentation.settled)
    try:
        window.lesson_panel.select(LESSONS["rasterization"], 1)
        panel = window.tab("object order").widget
        image, depth = panel.image, panel.depth.image
        qtbot.waitUntil(lambda: window.showing_full("object order") and _outline_extent(image) is not None,
                        timeout=RENDER_TIMEOUT_MS)
        whole = _outline_extent(image)
        assert max(whole[2:]) < 0.35  # small before
        window.activateWindow()
        qtbot.waitUntil(window.isActiveWindow)
        qtbot.keyClick(window, Qt.Key.Key_Z)
        assert image.zoom > 2 and depth.zoom > 2  # each framed in its own pane
        for view in (image, depth):
            x, y, w, h = _outline_extent(view)
            assert abs(max(w, h) - 0.6) < 0.05 and min(w, h) < 0.65, (w, h)
            assert abs(x - 0.5) < 0.05 and abs(y - 0.5) < 0.05, (x, y)
        qtbot.keyClick(window, Qt.Key.Key_Z)
        assert image.zoom == depth.zoom == 1.0
        assert _outline_extent(image) == whole
        assert "Zoom the pictures to the highlight" in keys_listed(window)
    finally:
        window.presentation.set_presenting(False)


def test_z_zooms_the_traced_picture_onto_its_picked_pixel(qtbot, window):
    """With no highlight, a picture is framed on its picked pixel (the shadow step's, here) and the
    few pixels around it: the picked pixel is drawn in the middle of the pane, large."""
    window.lesson_panel.select(LESSONS["ray_casting"], 1)
    image = window.tab("image order").widget.image
    qtbot.waitUntil(lambda: image.picked == (230, 155), timeout=RENDER_TIMEOUT_MS)
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.keyClick(window, Qt.Key.Key_Z)
    assert image.zoom > 4
    centre, picked = image.rect().center(), image.widget_pos(230, 155)
    assert abs(picked.x() - centre.x()) <= image.zoom and abs(picked.y() - centre.y()) <= image.zoom


def test_z_with_nothing_singled_out_says_so_and_changes_no_zoom(qtbot, window):
    window.tab_widget.setCurrentIndex(window.tabs.index(window.tab("object order")))
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    assert window.model.step is None and panel.image.picked is None  # the whole picture, no pixel picked
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.keyClick(window, Qt.Key.Key_Z)
    assert panel.image.zoom == panel.depth.image.zoom == 1.0
    assert window.statusBar().currentMessage().startswith("Nothing to zoom onto")
