"""In the window, the traced picture is reached with Tab and its pixel picked from the keyboard: the
arrows move the pick (not the observer, whose keys they are elsewhere) and the ray tree follows;
Enter answers a click-a-pixel exercise with the pixel picked."""

from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication
from window_helpers import RENDER_TIMEOUT_MS

from app.window.window_layout import in_front
from core.files.lesson_file import shipped_lessons

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
    assert "Enter" in window.keys_text() and "Shift+arrows" in window.keys_text()


def test_a_click_a_pixel_exercise_is_answered_from_the_keyboard(qtbot, window):
    """Show me picks a pixel in the cone's shadow; the student walks off it and back with the arrows
    (which answer nothing: the shadow's readout is what they look at) and answers with Enter."""
    lessons, exercises = window.lesson_panel, window.exercise_panel
    k = LESSONS["ray_casting"]
    lessons.select(k, 0)
    assert exercises.question.text() == "Click a pixel in the cone's shadow."
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    with qtbot.waitSignal(lessons.step_selected):
        exercises.show_button.click()
    qtbot.waitUntil(lambda: window.model.ray_pixel is not None, timeout=RENDER_TIMEOUT_MS)
    x, y = window.model.ray_pixel
    image = window.tab("image order").widget.image
    assert window.current is window.tab("image order") and image.picked == (x, y)
    _tab_to(qtbot, window, image)
    qtbot.keyClick(image, Qt.Key.Key_Left)
    qtbot.keyClick(image, Qt.Key.Key_Right)
    assert window.model.ray_pixel == (x, y)
    assert exercises.pixel_edit.text() == "" and exercises.feedback.text() == ""  # nothing answered yet
    qtbot.keyClick(image, Qt.Key.Key_Return)
    assert exercises.pixel_edit.text() == f"{x}, {y}"
    qtbot.waitUntil(lambda: exercises.feedback.text().startswith("Right"), timeout=RENDER_TIMEOUT_MS)
    assert "1/2 done, 1 right at first try" in lessons.list.item(k).text()
