"""A picture zooms in and out (the wheel, + and -, 0), moves while zoomed (the right or middle button),
and pictures of the same pixels side by side zoom together.  What is checked is what is painted:
each pixel of the test picture has a colour of its own, so a screenshot of the view says which pixel
is drawn where, and the pixel a click picks must be the one drawn under the click."""

import numpy as np
import pytest
from PySide6.QtCore import QPoint, QPointF, Qt
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QHBoxLayout, QWidget
from qt_fixtures import in_a_window_with_a_shortcut, shown_widget, wheel_over

from views.images import image_view, zoom
from views.images.image_view import (
    GRID_CELL_PX,
    NOTE_COLOR,
    DisplayImage,
    ImageView,
    to_qimage,
    zoom_together,
)

W, H = 40, 30
BACKGROUND = (0x15, 0x18, 0x1F)  # what the view paints where no pixel is


@pytest.fixture(autouse=True)
def no_grid(request, monkeypatch):
    """The pixels' squares and centres drawn over them are left out, but where a test asks for them."""
    if "grid" not in request.node.name:
        monkeypatch.setattr(image_view, "GRID_CELL_PX", 10_000)


def _coded(w: int = W, h: int = H) -> DisplayImage:
    """A picture whose pixel (x, y) has red 4x + 10 and green 4y + 10 (in the 8-bit picture shown)."""
    x, y = np.meshgrid(np.arange(w), np.arange(h))
    rgb8 = np.dstack([4 * x + 10, 4 * y + 10, np.full_like(x, 200)]).astype(np.uint8)
    rgb = rgb8 / 255.0
    return DisplayImage(rgb, to_qimage(rgb, linear=False), "")


def _view(qtbot, width=400, height=300, **kwargs) -> ImageView:
    view = ImageView(**kwargs)
    view.set_image(_coded())
    return shown_widget(qtbot, view, width, height)


def _drawn_at(view: ImageView, pos: QPointF):
    """The picture's pixel painted at widget position ``pos`` (screenshot), or None: background."""
    colour = view.grab().toImage().pixelColor(int(pos.x()), int(pos.y()))
    rgb = (colour.red(), colour.green(), colour.blue())
    if rgb == BACKGROUND:
        return None
    assert rgb[2] == 200, rgb  # a pixel of the picture, not a mark painted over it
    return (rgb[0] - 10) // 4, (rgb[1] - 10) // 4


def _zoom_said(view: ImageView) -> bool:
    """Whether words in the note's colour are painted in the view's lower right corner."""
    shot = view.grab().toImage()
    note = QColor(NOTE_COLOR).rgb()
    return any(shot.pixel(x, y) == note for x in range(view.width() - 160, view.width())
               for y in range(view.height() - 50, view.height()))


def _cell(view: ImageView) -> float:
    """One pixel's width on screen."""
    return view.image_rect().width() / view.qimage.width()


def test_the_wheel_zooms_about_the_pointer_and_a_click_then_picks_the_pixel_drawn_under_it(qtbot):
    view = _view(qtbot)
    picks = []
    view.pixel_clicked.connect(lambda x, y: picks.append((x, y)))
    pointer = view.widget_pos(12, 7) + QPointF(0.3 * _cell(view), -0.2 * _cell(view))  # off its centre
    assert _drawn_at(view, pointer) == (12, 7) and not _zoom_said(view)
    whole = _cell(view)
    wheel_over(view, pointer, 3)
    assert _cell(view) == pytest.approx(whole * zoom.STEP ** 3)
    assert view.zoom_note() == "×1.95" and _zoom_said(view)  # part of it is hidden
    assert _drawn_at(view, pointer) == (12, 7)  # the pixel under the pointer stays under it
    for dx, dy in ((-110, -70), (0, 0), (95, 60), (150, -60), (-40, 100), (260, 150)):  # (not the note)
        at = QPointF((pointer + QPointF(dx, dy)).toPoint())
        view.set_picked(None)  # (its frame, drawn over the pixels around it)
        drawn = _drawn_at(view, at)
        picks.clear()
        qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=at.toPoint())
        assert picks == ([drawn] if drawn is not None else [])
    wheel_over(view, pointer, -10)  # out again, past the whole picture
    assert _cell(view) == pytest.approx(whole) and view.zoom == 1.0 and not _zoom_said(view)


def test_zoomed_or_moved_the_picture_still_covers_the_pane(qtbot):
    # No zoom or move shows background where the picture whole fills the pane's width (400 x 300 px
    # for a 4:3 picture); the margin kept for the focus frame aside.
    view = _view(qtbot)
    room = view.rect().adjusted(4, 4, -4, -4)
    corners = [QPointF(room.left(), room.top()), QPointF(room.right(), room.bottom())]
    wheel_over(view, QPointF(view.width() - 10, view.height() - 10), 5)  # about the lower right corner
    assert _drawn_at(view, corners[1]) == (W - 1, H - 1)
    start = view.rect().center()
    qtbot.mousePress(view, Qt.MouseButton.RightButton, pos=start)
    qtbot.mouseMove(view, start + QPoint(2000, 1500))  # dragged far past the top left corner
    qtbot.mouseRelease(view, Qt.MouseButton.RightButton, pos=start + QPoint(2000, 1500))
    assert _drawn_at(view, corners[0]) == (0, 0)
    assert all(_drawn_at(view, corner) is not None for corner in corners)


def test_dragging_with_the_right_button_moves_the_zoomed_picture_with_the_mouse(qtbot):
    view = _view(qtbot)
    wheel_over(view, QPointF(view.rect().center()), 4)
    start = view.rect().center()
    before = _drawn_at(view, QPointF(start))
    qtbot.mousePress(view, Qt.MouseButton.RightButton, pos=start)
    qtbot.mouseMove(view, start + QPoint(60, 40))
    qtbot.mouseRelease(view, Qt.MouseButton.RightButton, pos=start + QPoint(60, 40))
    assert _drawn_at(view, QPointF(start + QPoint(60, 40))) == before  # the pixel went with the mouse
    assert view.picked is None  # moving is not picking


def test_zoomed_in_far_enough_a_large_picture_shows_its_pixel_grid_squares_and_centres(qtbot):
    # The lecture scene's 320 x 240 pixels in some 220 x 160 px, as presenting at x2 on a 1280 x 720
    # projector: no grid; zoomed in, the pixels' squares and centres.
    view = ImageView()
    view.set_image(_coded(320, 240))
    shown_widget(qtbot, view, 226, 166)
    assert not view.grid_shown()
    wheel_over(view, QPointF(view.rect().center()), 14)
    assert _cell(view) >= GRID_CELL_PX and view.grid_shown()
    centre = view.widget_pos(*view.pixel_at(QPointF(view.rect().center())))
    shot = view.grab().toImage()
    dot = shot.pixelColor(int(centre.x()), int(centre.y()))
    assert (dot.red(), dot.green(), dot.blue()) == (255, 255, 255)  # the centre's white dot


def test_pictures_of_the_same_pixels_zoom_and_move_together(qtbot):
    pair = QWidget()
    layout = QHBoxLayout(pair)
    left, right, other = ImageView(), ImageView(), ImageView()
    for view, size in ((left, (W, H)), (right, (W, H)), (other, (20, 10))):
        view.set_image(_coded(*size))
        layout.addWidget(view)
    zoom_together([left, right, other])
    shown_widget(qtbot, pair, 900, 300)
    wheel_over(left, QPointF(left.widget_pos(30, 20)), 4)
    assert left.zoom > 1 and right.zoom == left.zoom and other.zoom == 1.0  # (other: not the same pixels)
    for probe in (QPointF(50, 60), QPointF(left.width() - 30, 40)):
        assert _drawn_at(right, probe) == _drawn_at(left, probe)
    start = right.rect().center()
    qtbot.mousePress(right, Qt.MouseButton.MiddleButton, pos=start)
    qtbot.mouseMove(right, start + QPoint(-30, 25))
    qtbot.mouseRelease(right, Qt.MouseButton.MiddleButton, pos=start + QPoint(-30, 25))
    assert _drawn_at(left, QPointF(start)) == _drawn_at(right, QPointF(start))


def test_a_new_picture_of_other_pixels_is_shown_whole_one_of_the_same_keeps_the_zoom(qtbot):
    view = _view(qtbot)
    wheel_over(view, QPointF(view.widget_pos(5, 5)), 3)
    zoomed = view.image_rect()
    view.set_image(_coded())  # the next step of the same render
    assert view.image_rect() == zoomed
    view.set_image(_coded(64, 48))  # another scene
    assert view.zoom == 1.0 and _drawn_at(view, view.widget_pos(32, 24)) == (32, 24)
    assert _drawn_at(view, QPointF(2, 2)) is None  # whole: the background around it


def test_plus_minus_and_0_zoom_a_focused_picture_about_its_picked_pixel_not_the_observer(qtbot):
    view = ImageView()
    view.set_image(_coded())
    _window, closer = in_a_window_with_a_shortcut(qtbot, view, "+")  # the observer's step closer
    qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=view.widget_pos(33, 4).toPoint())
    qtbot.waitUntil(view.hasFocus)
    at, whole = view.widget_pos(33, 4), _cell(view)
    qtbot.keyClick(view, Qt.Key.Key_Plus, Qt.KeyboardModifier.ShiftModifier)
    qtbot.keyClick(view, Qt.Key.Key_Plus, Qt.KeyboardModifier.ShiftModifier)
    assert _cell(view) == pytest.approx(whole * zoom.STEP ** 2) and closer == []
    assert _drawn_at(view, at) == (33, 4)
    qtbot.keyClick(view, Qt.Key.Key_Minus)
    assert _cell(view) == pytest.approx(whole * zoom.STEP)
    qtbot.keyClick(view, Qt.Key.Key_0)
    assert _cell(view) == pytest.approx(whole)


def test_zoomed_in_the_picture_follows_the_pixel_the_arrow_keys_pick(qtbot):
    view = _view(qtbot)
    qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=view.widget_pos(2, 2).toPoint())
    wheel_over(view, QPointF(view.widget_pos(2, 2)), 8)
    for _ in range(30):  # far out of the part first in view
        qtbot.keyClick(view, Qt.Key.Key_Right)
    assert view.picked == (32, 2)
    assert _drawn_at(view, view.widget_pos(32, 2)) == (32, 2)
    assert view.rect().contains(view.widget_pos(32, 2).toPoint())


def _span(view: ImageView, horizontal: bool, pixels: range) -> int:
    """Screen pixels of the line through the middle of the pane, across (``horizontal``) or down,
    where the picture's columns (or rows) ``pixels`` are painted (a screenshot; marks over them, the
    highlight's outline, not counted)."""
    shot = view.grab().toImage()
    room = view.rect().adjusted(3, 3, -3, -3)  # image_view.FOCUS_MARGIN
    centre = room.center()
    line = range(room.left(), room.right() + 1) if horizontal else range(room.top(), room.bottom() + 1)
    count = 0
    for p in line:
        colour = shot.pixelColor(p, centre.y()) if horizontal else shot.pixelColor(centre.x(), p)
        if colour.blue() == 200:  # a pixel of the picture
            count += ((colour.red() if horizontal else colour.green()) - 10) // 4 in pixels
    return count


def test_framed_the_highlighted_pixels_take_three_fifths_of_the_pane_in_its_middle(qtbot):
    view = _view(qtbot)  # 40 x 30 pixels in 400 x 300
    mask = np.zeros((H, W), bool)
    mask[5:8, 10:18] = True  # 8 x 3 pixels: the width decides
    view.set_highlight(mask)
    assert view.frame_singled_out()
    room = view.rect().adjusted(3, 3, -3, -3)
    assert _drawn_at(view, QPointF(room.center())) in {(13, 6), (14, 6)}  # its middle in the middle
    across, down = _span(view, True, range(10, 18)), _span(view, False, range(5, 8))
    # (the outline, painted just inside the pixels' border on either side, hides up to 12 screen pixels)
    assert abs(across - zoom.FRAMED_SHARE * room.width()) <= 12, across
    assert abs(down - across * 3 / 8) <= 12, (down, across)


def test_framed_with_no_highlight_the_picked_pixel_and_a_few_around_it_fill_three_fifths(qtbot):
    view = _view(qtbot)
    view.set_picked((20, 15))
    assert view.frame_singled_out()
    room = view.rect().adjusted(3, 3, -3, -3)
    assert _drawn_at(view, QPointF(room.center())) == (20, 15)
    context = image_view.PICKED_CONTEXT
    down = _span(view, False, range(15 - context, 16 + context))  # 9 rows of 30: the height decides
    assert abs(down - zoom.FRAMED_SHARE * room.height()) <= 10, down  # less the picked pixel's frame


def test_a_picture_that_singles_out_nothing_or_all_its_pixels_stays_whole(qtbot):
    view = _view(qtbot)
    assert not view.frame_singled_out() and view.zoom == 1.0
    view.set_highlight(np.ones((H, W), bool))
    assert view.frame_singled_out() and view.zoom == 1.0
    room = view.rect().adjusted(3, 3, -3, -3)
    assert _drawn_at(view, QPointF(room.left() + 5, room.top() + 5)) == (0, 0)
    assert _drawn_at(view, QPointF(room.right() - 5, room.bottom() - 5)) == (W - 1, H - 1)
