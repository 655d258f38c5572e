"""Presentation mode: full screen, scaled text, high contrast, blanking, clicker keys, presenter window."""

import pytest
from PySide6.QtCore import QEvent, QObject, QRect, Qt
from PySide6.QtGui import QGuiApplication, QPalette
from PySide6.QtWidgets import (
    QApplication,
    QCheckBox,
    QDialog,
    QLabel,
    QMainWindow,
    QSlider,
    QSpinBox,
    QSplitter,
    QToolButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
)

from views.panels.lesson_panel import LessonPanel
from views.presentation import PRESENTING_SCALE, Presentation
from views.text.math_view import MathView
from views.text.text_scale import scaled_style


@pytest.fixture
def hall(qtbot):
    window = QMainWindow()
    panel = LessonPanel()
    other = QLabel("an image pane")
    split = QSplitter()
    split.addWidget(panel)
    split.addWidget(other)
    window.setCentralWidget(split)
    qtbot.addWidget(window)
    window.resize(1280, 720)
    window.show()
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)  # window shortcuts (F11, Esc, ".", "B") need the active window
    presentation = Presentation(window, panel)
    yield window, panel, presentation
    presentation.clicker.remove()


def _formula_height(panel: LessonPanel) -> float:
    view = panel.formula_views()[0]
    return view.pixmap().deviceIndependentSize().height()


def test_presentation_mode_goes_full_screen_and_scales_the_text(hall, qtbot):
    window, panel, presentation = hall
    panel.select(4, 1)  # the z-buffer lesson has a formula
    base_pt = panel.text.font().pointSizeF()
    qtbot.waitUntil(lambda: not panel.typesetting())  # the formulas are typeset off the GUI thread
    base_formula = _formula_height(panel)
    normal_formula_pt = MathView().size_pt()  # a formula's size at the normal text size
    qtbot.keyClick(window, Qt.Key.Key_F11)
    qtbot.waitUntil(window.isFullScreen)
    assert presentation.presenting() and presentation.scale() == PRESENTING_SCALE
    assert panel.text.font().pointSizeF() == pytest.approx(base_pt * PRESENTING_SCALE)
    assert panel.formula_views()[0].size_pt() == pytest.approx(normal_formula_pt * PRESENTING_SCALE, rel=0.01)
    presentation.set_scale(2.0)
    assert panel.text.font().pointSizeF() == pytest.approx(base_pt * 2)
    qtbot.waitUntil(lambda: _formula_height(panel) == pytest.approx(2 * base_formula, rel=0.15))
    assert presentation.high_contrast()
    assert panel.text.palette().color(QPalette.ColorRole.Window).name() == "#000000"  # white on black
    assert panel.text.palette().color(QPalette.ColorRole.WindowText).name() == "#ffffff"
    qtbot.keyClick(window, Qt.Key.Key_Escape)
    qtbot.waitUntil(lambda: not window.isFullScreen())
    assert not presentation.presenting() and panel.text.font().pointSizeF() == pytest.approx(base_pt)
    with pytest.raises(ValueError, match="scale must be one of 1, 1.5, 2"):
        presentation.set_scale(3.0)


def test_blank_and_unblank_with_the_clicker_keys(hall, qtbot):
    window, panel, presentation = hall
    qtbot.keyClick(window, Qt.Key.Key_Period)
    assert not presentation.blanked()  # only while presenting: "." and "B" are ordinary keys otherwise
    presentation.set_presenting(True)
    qtbot.waitUntil(window.isFullScreen)
    with qtbot.waitSignal(presentation.blanked_changed) as signal:
        qtbot.keyClick(window, Qt.Key.Key_Period)
    assert signal.args == [True] and presentation.blanked()
    sheet = presentation._blank
    assert sheet.isVisible() and sheet.geometry() == window.rect()
    image = window.grab().toImage()
    assert image.pixelColor(image.width() // 2, image.height() // 2).name() == "#000000"
    with qtbot.waitSignal(presentation.blanked_changed) as signal:
        qtbot.keyClick(window, Qt.Key.Key_B)
    assert signal.args == [False] and not sheet.isVisible()


def test_page_down_advances_the_step_and_arrows_do_too_while_presenting(hall, qtbot):
    window, panel, presentation = hall
    other = window.centralWidget().widget(1)
    other.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
    other.setFocus()
    with qtbot.waitSignal(panel.step_selected) as first:
        qtbot.keyClick(other, Qt.Key.Key_PageDown)
    assert panel.step_index() == (0, 0) and first.args[0] is panel.lessons()[0].steps[0]  # shown, not skipped
    qtbot.keyClick(other, Qt.Key.Key_PageDown)
    assert panel.step_index() == (0, 1)
    qtbot.keyClick(other, Qt.Key.Key_Right)
    assert panel.step_index() == (0, 1)  # not presenting: the arrows are the widget's
    presentation.set_presenting(True)
    qtbot.keyClick(other, Qt.Key.Key_Right)
    assert panel.step_index() == (1, 0)
    qtbot.keyClick(other, Qt.Key.Key_PageUp)
    assert panel.step_index() == (0, 1)


def test_the_presenter_window_shows_notes_the_next_step_and_a_clock(hall, qtbot):
    window, panel, presentation = hall
    k = next(i for i, lesson in enumerate(panel.lessons()) if lesson.id == "zbuffer")
    panel.select(k, 0)
    presenter = presentation.show_presenter()
    qtbot.addWidget(presenter)
    qtbot.waitExposed(presenter)
    lesson = panel.lessons()[k]
    assert lesson.steps[0].notes in presenter.notes.text()
    assert lesson.steps[1].title in presenter.upcoming.text()
    assert presenter.clock.text().count(":") == 2
    panel.next()
    assert "step 2 of 4" in presenter.current.text()
    assert lesson.steps[2].title in presenter.upcoming.text()


def test_presenting_hides_the_lesson_list_and_leaving_brings_it_back(hall, qtbot):
    window, panel, presentation = hall
    assert panel.list.isVisible()
    presentation.set_presenting(True)
    assert not panel.list.isVisible() and panel.text.isVisible() and panel.next_button.isVisible()
    presentation.set_presenting(False)
    assert panel.list.isVisible()


def test_high_contrast_keeps_every_table_row_and_disabled_control_readable(hall, qtbot):
    window, panel, presentation = hall
    table = QTreeWidget(window)
    table.setAlternatingRowColors(True)
    table.addTopLevelItems([QTreeWidgetItem([f"row {i}"]) for i in range(4)])
    off = QSpinBox(window)
    off.setEnabled(False)
    presentation.set_high_contrast(True)
    for widget in (table, off):
        widget.ensurePolished()
    text, odd_rows = table.palette().color(QPalette.ColorRole.Text), table.palette().alternateBase().color()
    assert text.lightnessF() - odd_rows.lightnessF() > 0.7  # white text on (nearly) black rows
    enabled = table.palette().color(QPalette.ColorRole.Text).lightnessF()
    disabled = off.palette().color(QPalette.ColorGroup.Disabled, QPalette.ColorRole.Text).lightnessF()
    assert 0.3 < disabled < enabled  # a switched-off control looks switched off


def test_high_contrast_check_boxes_show_their_box_and_whether_they_are_on(hall, qtbot):
    window, panel, presentation = hall
    presentation.set_high_contrast(True)
    box = QCheckBox("bounding spheres", window)
    box.show()
    box.ensurePolished()

    def indicator_colours():
        picture = box.grab().toImage()
        side = picture.height()  # the indicator is at the left, about a text line high
        # Inside the widget's own edge (3 px): the indicator's pixels, not a frame around the widget.
        return {picture.pixelColor(x, y).name() for x in range(3, side) for y in range(3, side - 3)}

    def background_right():
        picture = box.grab().toImage()
        return picture.pixelColor(picture.width() - 4, picture.height() // 2).name()

    box.resize(box.sizeHint().width() + 40, box.sizeHint().height())
    unchecked = indicator_colours()
    assert "#ffffff" in unchecked and "#ffd400" not in unchecked  # a white box on black
    box.setChecked(True)
    assert "#ffd400" in indicator_colours()  # filled with the accent when on
    assert background_right() == "#000000"  # only the box, not the whole row, turns yellow


def test_high_contrast_tool_buttons_keep_their_words_readable(hall, qtbot):
    # The scene editor's Add, Duplicate, Rename and Delete (tool buttons) were white on white.
    window, panel, presentation = hall
    presentation.set_high_contrast(True)
    button = QToolButton(window)
    button.setText("Duplicate")
    button.show()
    button.resize(button.sizeHint())
    picture = button.grab().toImage()
    colours = [picture.pixelColor(x, y) for x in range(4, picture.width() - 4)
               for y in range(4, picture.height() - 4)]
    light = sum(c.lightnessF() > 0.8 for c in colours)
    dark = sum(c.lightnessF() < 0.3 for c in colours)
    assert light > 0 and dark > 0.03 * len(colours)  # dark letters on the white button


def test_high_contrast_sliders_show_their_handle_and_how_far_they_are(hall, qtbot):
    # The hard cases' and the step scrubber's sliders drew a black handle on black.
    window, panel, presentation = hall
    presentation.set_high_contrast(True)
    slider = QSlider(Qt.Orientation.Horizontal, window)
    slider.setRange(0, 100)
    slider.setValue(40)
    slider.resize(400, slider.sizeHint().height())
    slider.show()
    picture = slider.grab().toImage()
    middle = picture.height() // 2
    row = [picture.pixelColor(x, middle).name() for x in range(picture.width())]
    white = [x for x, colour in enumerate(row) if colour == "#ffffff"]
    assert white and 0.3 * 400 < sum(white) / len(white) < 0.5 * 400  # the handle, at 40 %
    assert len(white) >= 0.5 * slider.fontMetrics().height()  # as wide as half a line of text
    assert row[10] == "#ffd400" and row[390] != "#ffd400"  # the way done in the accent, the rest not


def test_the_text_size_reaches_widgets_with_their_own_style_sheets_under_high_contrast(hall, qtbot):
    # The size is the window's font now (a style sheet of sizes re-styled every widget, a second
    # long); widgets with style sheets of their own must follow that font all the same.
    window, panel, presentation = hall
    host = window.centralWidget().widget(1)
    coloured = QLabel("refused: the radius must be positive", host)
    coloured.setStyleSheet("color: #d00000;")  # as the scene editor's error beside a field
    heading = QLabel("Hard case", host)
    scaled_style(heading, "font-weight: bold;", 15)  # 15 pt at ×1, as a hard case's title
    heading.move(0, 40)
    for label in (coloured, heading):
        label.show()
    base_pt = coloured.font().pointSizeF()
    presentation.set_high_contrast(True)
    for scale in (2.0, 1.5, 1.0):
        presentation.set_scale(scale)
        assert coloured.font().pointSizeF() == pytest.approx(base_pt * scale)
        assert panel.text.font().pointSizeF() == pytest.approx(base_pt * scale)
        assert heading.font().pointSizeF() == pytest.approx(15 * scale)  # 15 pt times the scale
        assert heading.font().bold()


def test_page_down_steps_from_a_dialog_too(hall, qtbot):
    # The clicker's keys follow the keyboard focus from window to window.
    window, panel, presentation = hall
    dialog = QDialog(window)
    spin = QSpinBox(dialog)
    spin.setRange(0, 100)
    spin.setValue(50)
    QVBoxLayout(dialog).addWidget(spin)
    dialog.show()
    dialog.activateWindow()
    qtbot.waitUntil(dialog.isActiveWindow)
    spin.setFocus()
    qtbot.waitUntil(spin.hasFocus)
    with qtbot.waitSignal(panel.step_selected):
        qtbot.keyClick(spin, Qt.Key.Key_PageDown)
    assert panel.step_index() == (0, 0) and spin.value() == 50  # a step, and the box kept its value
    with qtbot.waitSignal(spin.destroyed):  # the focused box goes, and its window with it
        dialog.deleteLater()
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    qtbot.keyClick(QApplication.focusWidget() or window, Qt.Key.Key_PageDown)  # where a typed key goes
    assert panel.step_index() == (0, 1)  # back in the main window, the keys step there too


def test_entering_and_leaving_presentation_mode_show_only_their_final_look(hall, qtbot):
    # Entering takes three turns of the event loop (text size, colours, full screen).  Painted at
    # each, the hall saw the big text in the small window, then the colours, then the full screen,
    # and each turn held the window for a paint of everything.
    window, panel, presentation = hall
    painted = []

    class Paints(QObject):
        def eventFilter(self, watched, event):
            if event.type() == QEvent.Type.Paint:
                painted.append((panel.text.font().pointSizeF(), window.isFullScreen(),
                                panel.text.palette().color(QPalette.ColorRole.Window).name()))
            return False

    paints = Paints()
    panel.text.installEventFilter(paints)
    base_pt = panel.text.font().pointSizeF()
    normal_background = panel.text.palette().color(QPalette.ColorRole.Window).name()
    for on, look in ((True, (base_pt * PRESENTING_SCALE, True, "#000000")),
                     (False, (base_pt, False, normal_background))):
        painted.clear()
        presentation.set_presenting(on)
        qtbot.waitUntil(lambda: presentation.settled() and bool(painted))  # noqa: B023
        assert painted == [look] * len(painted)


def test_on_one_screen_the_presenter_window_says_the_room_may_see_it(hall, qtbot, monkeypatch):
    """Its notes may hold the exercises' answers: on the only screen, which a projector may mirror,
    the presenter window says so; on a second screen of its own it does not."""
    window, panel, presentation = hall
    presenter = presentation.show_presenter()
    qtbot.addWidget(presenter)
    qtbot.waitExposed(presenter)
    assert len(QGuiApplication.screens()) == 1
    assert presenter.one_screen.isVisible()
    assert "a projector that shows this screen" in presenter.one_screen.text()
    presenter.hide()

    class Second:  # a second screen, beside the first
        def availableGeometry(self):
            return QRect(1920, 0, 1280, 720)

    monkeypatch.setattr(QGuiApplication, "screens", staticmethod(lambda: [window.screen(), Second()]))
    presentation.show_presenter()
    qtbot.waitExposed(presenter)
    assert not presenter.one_screen.isVisible()
