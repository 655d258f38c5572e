"""A picture is reached with Tab and its pixel picked from the keyboard, as a click picks it."""

import numpy as np
from PySide6.QtCore import Qt
from PySide6.QtGui import QPalette
from PySide6.QtWidgets import QApplication, QLineEdit, QPushButton, QVBoxLayout, QWidget
from qt_fixtures import in_a_window_with_a_shortcut, shown_widget

from views.images.image_view import FOCUS_MARGIN, SHIFT_STEP, ImageView

W, H = 40, 30  # the image's pixels; its centre pixel is (20, 15)


class _Form(QWidget):
    """A line edit, the picture and a button, in that Tab order; notes the keys that reach it."""

    def __init__(self, view: ImageView):
        super().__init__()
        self.edit, self.view, self.button = QLineEdit(), view, QPushButton("Check")
        layout = QVBoxLayout(self)
        for w in (self.edit, view, self.button):
            layout.addWidget(w)
        layout.setStretch(1, 1)
        self.keys: list[int] = []

    def keyPressEvent(self, event):
        if event.key() not in (Qt.Key.Key_Shift, Qt.Key.Key_Control):  # pressed with a modified key
            self.keys.append(event.key())


def _form(qtbot, view=None) -> _Form:
    view = view or ImageView()
    view.set_image(np.full((H, W, 3), 0.2))
    form = shown_widget(qtbot, _Form(view), 500, 420)
    form.activateWindow()
    qtbot.waitUntil(form.isActiveWindow)
    return form


def _focus(qtbot, widget):
    widget.setFocus()
    qtbot.waitUntil(widget.hasFocus)


def _picks(view) -> list[tuple[int, int]]:
    picks = []
    view.pixel_clicked.connect(lambda x, y: picks.append((x, y)))
    return picks


def _marked(view, x, y) -> bool:
    """Whether the picked pixel's white marker is drawn around pixel (x, y) of the picture on screen."""
    shot = view.grab().toImage()
    rect = view.image_rect()
    sx = rect.width() / W
    pad = max(3.0, sx)
    left = rect.x() + x * sx - pad  # the marker's white side, left of the pixel
    centre = view.widget_pos(x, y)
    colour = shot.pixelColor(int(left), int(centre.y()))
    return min(colour.red(), colour.green(), colour.blue()) > 230


def test_arrows_pick_the_centre_first_then_move_one_pixel_and_shift_arrows_ten(qtbot):
    form = _form(qtbot)
    view = form.view
    _focus(qtbot, view)
    picks = _picks(view)
    with qtbot.waitSignal(view.pixel_clicked):
        qtbot.keyClick(view, Qt.Key.Key_Right)
    assert picks == [(W // 2, H // 2)]  # nothing was picked: the first arrow picks the centre
    qtbot.keyClick(view, Qt.Key.Key_Right)
    qtbot.keyClick(view, Qt.Key.Key_Down, Qt.KeyboardModifier.ShiftModifier)
    qtbot.keyClick(view, Qt.Key.Key_Left, Qt.KeyboardModifier.ShiftModifier)
    qtbot.keyClick(view, Qt.Key.Key_Up)
    assert picks == [(20, 15), (21, 15), (21, 15 + SHIFT_STEP), (21 - SHIFT_STEP, 25), (11, 24)]
    assert view.picked == (11, 24)
    assert _marked(view, 11, 24) and not _marked(view, 20, 15)  # the marker moved with the pick


def test_arrows_go_on_from_a_clicked_pixel_and_stop_at_the_border(qtbot):
    form = _form(qtbot)
    view = form.view
    picks = _picks(view)
    qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=view.widget_pos(2, 28).toPoint())
    assert view.hasFocus()  # a click gives the picture the keys too
    assert picks == [(2, 28)]
    qtbot.keyClick(view, Qt.Key.Key_Left, Qt.KeyboardModifier.ShiftModifier)  # 10 left of 2: the border
    qtbot.keyClick(view, Qt.Key.Key_Down)
    qtbot.keyClick(view, Qt.Key.Key_Down)
    assert picks == [(2, 28), (0, 28), (0, 29)]
    with qtbot.assertNotEmitted(view.pixel_clicked):  # already at the border: nothing moves
        qtbot.keyClick(view, Qt.Key.Key_Left)
        qtbot.keyClick(view, Qt.Key.Key_Down, Qt.KeyboardModifier.ShiftModifier)
    assert view.picked == (0, 29) and _marked(view, 0, 29)
    view.set_picked((W - 3, 0))  # its owner picked another pixel meanwhile: the keys go on from it
    qtbot.keyClick(view, Qt.Key.Key_Right, Qt.KeyboardModifier.ShiftModifier)
    qtbot.keyClick(view, Qt.Key.Key_Up)
    assert picks[-1] == (W - 1, 0) and _marked(view, W - 1, 0)


def test_tab_reaches_the_picture_which_then_wears_a_focus_frame(qtbot):
    form = _form(qtbot)
    view = form.view
    rect = view.image_rect()
    beside = (int(rect.center().x()), int(rect.y()) - FOCUS_MARGIN + 1)  # above the image, in its margin
    highlight = view.palette().color(QPalette.ColorRole.Highlight)
    assert view.grab().toImage().pixelColor(*beside) != highlight
    _focus(qtbot, form.edit)
    qtbot.keyClick(QApplication.focusWidget(), Qt.Key.Key_Tab)
    qtbot.waitUntil(view.hasFocus)
    qtbot.waitUntil(lambda: view.grab().toImage().pixelColor(*beside) == highlight)
    inside = view.grab().toImage().pixelColor(int(rect.center().x()), int(rect.y()) + 1)
    assert inside != highlight  # the frame lies around the image: every pixel is still seen
    qtbot.keyClick(view, Qt.Key.Key_Tab)
    qtbot.waitUntil(form.button.hasFocus)
    qtbot.waitUntil(lambda: view.grab().toImage().pixelColor(*beside) != highlight)


def test_enter_goes_on_to_the_parent_and_chooses_the_picked_pixel(qtbot):
    form = _form(qtbot)
    view = form.view
    _focus(qtbot, view)
    chosen = []
    view.pixel_chosen.connect(lambda x, y: chosen.append((x, y)))
    qtbot.keyClick(view, Qt.Key.Key_Return)
    assert form.keys == [Qt.Key.Key_Return] and chosen == []  # nothing picked yet: nothing chosen
    qtbot.keyClick(view, Qt.Key.Key_Up)  # picks the centre
    qtbot.keyClick(view, Qt.Key.Key_Up)
    qtbot.keyClick(view, Qt.Key.Key_Enter)
    assert form.keys == [Qt.Key.Key_Return, Qt.Key.Key_Enter]  # Enter is not the picture's
    assert chosen == [(20, 14)]
    qtbot.keyClick(view, Qt.Key.Key_A)
    qtbot.keyClick(view, Qt.Key.Key_Left, Qt.KeyboardModifier.ControlModifier)
    assert form.keys[2:] == [Qt.Key.Key_A, Qt.Key.Key_Left]  # other keys go on too
    assert view.picked == (20, 14)


def test_a_focused_picture_keeps_the_arrows_a_window_shortcut_also_has(qtbot):
    view = ImageView()
    view.set_image(np.zeros((H, W, 3)))
    window, orbits = in_a_window_with_a_shortcut(qtbot, view, "Left")
    _focus(qtbot, view)
    qtbot.keyClick(view, Qt.Key.Key_Left)
    qtbot.keyClick(view, Qt.Key.Key_Left)
    assert view.picked == (W // 2 - 1, H // 2) and orbits == []
    view.clearFocus()
    qtbot.waitUntil(lambda: not view.hasFocus())
    qtbot.keyClick(window, Qt.Key.Key_Left)
    assert orbits == [1] and view.picked == (W // 2 - 1, H // 2)  # unfocused, the window's again


def test_a_picture_only_looked_at_takes_neither_the_focus_nor_a_pick(qtbot):
    form = _form(qtbot, ImageView(pickable=False))
    view = form.view
    picks = _picks(view)
    _focus(qtbot, form.edit)
    qtbot.keyClick(form.edit, Qt.Key.Key_Tab)
    qtbot.waitUntil(form.button.hasFocus)  # Tab passes it by
    qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=view.widget_pos(3, 3).toPoint())
    assert picks == [] and view.picked is None and not view.hasFocus()
