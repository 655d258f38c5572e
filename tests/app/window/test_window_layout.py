"""The window shares its screen so that the images are the largest thing on it, at every text scale."""

import pytest
from PySide6.QtCore import QCoreApplication, QEvent, QObject, QRect, Qt, QTimer
from PySide6.QtGui import QFont, QFontDatabase, QFontMetrics, QScreen
from PySide6.QtWidgets import QApplication, QDockWidget, QLabel, QTabBar, QToolButton
from window_helpers import RENDER_TIMEOUT_MS, open_window, presenting_on_1280x720

from app.window.window_layout import in_front
from views.panels.hard_cases_panel import HardCasesPanel
from views.panels.raytree_view import COLUMNS as RAY_TREE_COLUMNS
from views.panels.raytree_view import RayKindLegend
from views.panels.side_column import SideColumn
from views.presentation import SCALES
from views.text.math_view import MathView
from views.text.text_scale import normal_text_pt

SCREENS = [(1280, 720), (1920, 1080)]
ROWS = 3
"""A table shows at least this many rows."""


@pytest.fixture
def normal_text():
    """The platform's normal text size for the application (another test may have enlarged it)."""
    app = QApplication.instance()
    before = app.font()
    app.setFont(QFontDatabase.systemFont(QFontDatabase.SystemFont.GeneralFont))
    yield
    app.setFont(before)


def _rows_shown(view) -> float:
    return view.viewport().height() / view.fontMetrics().height()


@pytest.mark.parametrize("screen", SCREENS, ids=lambda s: f"{s[0]}x{s[1]}")
def test_the_traced_image_outsizes_the_3d_pane_and_the_window_fits_its_screen(qtbot, monkeypatch, screen,
                                                                             normal_text):
    # A laptop's screen on this display: the window takes what the screen makes available.
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: QRect(0, 0, *screen))
    window = open_window(qtbot)
    image_order = window.tab("image order").widget
    cam = window.model.camera
    with qtbot.waitSignal(window._tree_renderer.finished, timeout=RENDER_TIMEOUT_MS):
        window.pick_ray_tree(cam.width // 2, cam.height // 2)  # its tree and caption are shown too
    for scale in SCALES:
        window.presentation.set_scale(scale)
        window.setGeometry(window.screen().availableGeometry())

        def laid_out(scale=scale):
            hint = window.minimumSizeHint()
            assert hint.width() <= screen[0] and hint.height() <= screen[1], (scale, hint)
            assert window.width() <= screen[0] and window.height() <= screen[1], (scale, window.size())
            shown = image_order.image.image_rect()
            pane = window.scene_view.size()
            assert shown.width() * shown.height() > pane.width() * pane.height(), (scale, shown, pane)
            assert _rows_shown(image_order.tree) >= ROWS, scale

        qtbot.waitUntil(laid_out, timeout=5000)
    window.show_tab("object order")
    history = window.tab("object order").widget.history
    qtbot.waitUntil(lambda: _rows_shown(history) >= ROWS, timeout=5000)


def test_table_headers_and_rows_grow_with_the_text_scale(qtbot, window):
    window.show_tab("object order")
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    cam = window.model.camera
    panel.pick_pixel(cam.width // 2, cam.height // 2)  # listed at the normal size, then enlarged
    normal = QFontMetrics(QFont()).height()
    window.presentation.set_scale(2.0)
    tables = [(panel.history.horizontalHeader(), [panel.history.horizontalHeaderItem(c).text()
                                                  for c in range(panel.history.columnCount())]),
              (window.tab("image order").widget.tree.header(), RAY_TREE_COLUMNS)]
    for header, labels in tables:
        metrics = header.fontMetrics()
        assert metrics.height() >= 2 * 0.9 * normal  # the header's text is scaled
        assert header.height() >= metrics.height()
        for column, label in enumerate(labels):
            assert header.sectionSize(column) >= metrics.horizontalAdvance(label), label
    assert panel.history.rowCount() > 0
    assert panel.history.rowHeight(0) >= panel.history.fontMetrics().height()


def test_worked_math_and_lesson_formulas_share_one_size_at_every_scale(qtbot, window):
    lessons = [lesson.id for lesson in window.lesson_panel.lessons()]
    window.lesson_panel.select(lessons.index("perspective"), 0)  # a lesson that follows a vertex
    worked = window.tab("object order").widget.vertex_math.findChildren(MathView)
    assert worked
    normal = MathView().size_pt()  # a formula's size at the normal text size
    for scale in SCALES:
        window.presentation.set_scale(scale)
        lesson = window.lesson_panel.formula_views()[0].size_pt()
        assert lesson == pytest.approx(scale * normal, rel=0.01)
        assert {round(view.size_pt(), 3) for view in worked} == {round(lesson, 3)}


def _settle():
    """Let the layout requests a change posts (one layout level at a time) all run."""
    for _ in range(10):
        QApplication.processEvents()


def test_every_tab_and_lesson_step_fits_a_small_screen_at_every_text_scale(qtbot, monkeypatch, normal_text):
    # The widest things at large text were the scene editor's button row and the lesson that shows
    # the Object order tab beside its words: the window's least width must stay within the screen.
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: QRect(0, 0, 1280, 720))
    window = open_window(qtbot)
    for scale in SCALES:
        window.presentation.set_scale(scale)
        for tab in window.tabs:
            window.show_tab(tab.title)
            _settle()
            hint = window.minimumSizeHint()
            assert hint.width() <= 1280 and hint.height() <= 720, (scale, tab.title, hint)
    panel = window.lesson_panel
    for li, lesson in enumerate(panel.lessons()):
        for si in range(len(lesson.steps)):
            panel.select(li, si)
            _settle()  # the step's words and panes are laid out
            hint = window.minimumSizeHint()
            assert hint.width() <= 1280 and hint.height() <= 720, (lesson.id, si, hint)
            assert window.width() <= 1280 and window.height() <= 720, (lesson.id, si, window.size())


def test_compare_reads_the_picked_pixel_in_two_columns_that_fit_a_small_screen_at_x2(qtbot, monkeypatch,
                                                                                      normal_text):
    monkeypatch.setattr(QScreen, "availableGeometry", lambda self: QRect(0, 0, 1280, 720))
    window = open_window(qtbot)
    window.presentation.set_scale(2.0)
    window.setGeometry(window.screen().availableGeometry())
    window.show_tab("compare")
    qtbot.waitUntil(lambda: window.showing_full("compare"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("compare").widget
    cam = window.model.camera
    panel.pick(cam.width // 2, cam.height // 2)  # the cone, in both outputs
    qtbot.waitUntil(lambda: panel.readout[0].rgb is not None, timeout=RENDER_TIMEOUT_MS)
    a, b, why = panel.readout
    assert "cone" in a.found.text() and "cone" in b.found.text() and why.found.text()

    def laid_out():
        hint = window.minimumSizeHint()
        assert hint.width() <= 1280 and hint.height() <= 720, hint
        assert window.width() <= 1280 and window.height() <= 720, window.size()
        ga, gb, gw = a.geometry(), b.geometry(), why.geometry()
        assert ga.top() == gb.top() and ga.right() < gb.left(), (ga, gb)  # A and B side by side
        assert gw.top() > max(ga.bottom(), gb.bottom()), (gw, ga, gb)  # why they differ under both
        assert gw.left() <= ga.left() and gw.right() >= gb.right(), (gw, ga, gb)
        shown = a.parentWidget().parentWidget().width()  # the scroll area's viewport: nothing beyond it
        assert max(gb.right(), gw.right()) < shown, (gb, gw, shown)
        for row in panel.readout:
            for label in (row.title, row.numbers, row.found):  # every word on screen, whole
                assert label.width() >= label.minimumSizeHint().width(), label.text()
                assert label.height() >= label.heightForWidth(label.width()), label.text()

    qtbot.waitUntil(laid_out, timeout=5000)


def test_presenting_at_x2_on_a_small_screen_the_traced_image_keeps_half_its_row_and_the_ray_colours_show(
        qtbot, monkeypatch, normal_text):
    # The ray colours' legend kept three kinds to a line (520 px at x2), so the settings beside the
    # traced image took 538 px of the row's 732 and the image, the tab's subject, 176.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    panel = window.tab("image order").widget
    column = panel.findChild(SideColumn)
    legend = column.findChild(RayKindLegend)

    def laid_out():
        image = panel.image.width()
        assert image >= 0.45 * (image + column.width()), (image, column.width())
        names = [label for label in legend.findChildren(QLabel) if label.text()]
        assert len(names) == 5
        for label in names:  # every kind's name whole, inside the column's view
            right = label.mapTo(column.viewport(), label.rect().topRight()).x()
            assert label.width() >= label.sizeHint().width(), label.text()
            assert right < column.viewport().width(), label.text()

    qtbot.waitUntil(laid_out, timeout=5000)
    window.presentation.set_presenting(False)


def test_what_is_made_after_the_text_is_scaled_is_as_large_as_the_rest(qtbot, normal_text):
    # Presenting at x2, then: a hard case's table, the next exercise's answers and the editor's fields
    # for a picked object are made. Each is at twice the normal size, as every label made before is.
    window = open_window(qtbot)
    normal = normal_text_pt()
    window.presentation.set_scale(2.0)
    qtbot.waitUntil(lambda: window.camera_panel.font().pointSizeF() == pytest.approx(2 * normal))
    window.show_tab("hard cases")
    hard_cases = window.findChild(HardCasesPanel)
    qtbot.waitUntil(lambda: bool(hard_cases.table_cells))
    window.lesson_panel.select(0, 0)  # the first lesson's first exercise: choose one
    exercises = window.exercise_panel
    qtbot.waitUntil(lambda: bool(exercises.choices.buttons()))
    tree = window.editor.panel.tree
    tree.setCurrentItem(tree.topLevelItem(0).child(0))  # an object: its fields are made now
    qtbot.waitUntil(lambda: bool(window.editor.panel.fields))
    made = [cell for row in hard_cases.table_cells for cell in row]
    made += exercises.choices.buttons()
    made += [box for field in window.editor.panel.fields.values() for box in field.boxes]
    sizes = {round(w.font().pointSizeF(), 2) for w in made}
    assert sizes == {round(2 * normal, 2)}, sizes


def test_the_dock_titles_and_tool_icons_follow_the_text_scale_and_close_their_docks(qtbot, normal_text):
    window = open_window(qtbot)
    normal = normal_text_pt()
    titles = {dock.windowTitle(): dock.titleBarWidget() for dock in window.findChildren(QDockWidget)}
    line = QFontMetrics(QFont()).height()  # a line of text at the normal size
    scrubber = window.tab("object order").widget.scrubber
    window.presentation.set_scale(2.0)
    icons = [titles["Lessons"].close_button, *scrubber.findChildren(QToolButton)]
    assert len(icons) == 6 and all(b.iconSize().height() >= 2 * 0.9 * line for b in icons)
    for name in ("The scene: observer, frustum, screen", "Lessons", "Exercises", "Editor"):
        label = titles[name].label
        assert label.text() == name
        assert label.font().pointSizeF() == pytest.approx(2 * normal), name
    assert window.lesson_dock.isVisible()
    qtbot.mouseClick(titles["Lessons"].close_button, Qt.MouseButton.LeftButton)
    assert not window.lesson_dock.isVisible()
    view = next(a.menu() for a in window.menuBar().actions() if a.text() == "&View")
    next(a for a in view.actions() if a.text() == "Lessons").trigger()
    assert window.lesson_dock.isVisible()


class _Paints(QObject):
    """An event filter that calls ``note()`` at each paint of the widgets it filters."""

    def __init__(self, note):
        super().__init__()
        self._note = note

    def eventFilter(self, watched, event):
        if event.type() == QEvent.Type.Paint:
            self._note()
        return False


def test_a_new_text_size_is_painted_once_laid_out_with_the_room_shared_again(qtbot, normal_text):
    # Laid out, shared out (the window's refit, a turn later) and painted in one turn, a new text
    # size held the window 51-61 ms; and its first paint showed the large text in the left column's
    # old width, which the refit then changed.
    window = open_window(qtbot)
    text = window.lesson_panel.text
    painted = []
    paints = _Paints(lambda: painted.append((text.font().pointSizeF(), window.lesson_dock.width())))
    text.installEventFilter(paints)
    normal = text.font().pointSizeF()
    for scale in (1.5, 1.0):
        painted.clear()
        window.presentation.set_scale(scale)
        turns = []  # two turns of the event loop after the window's refit (asked for in this one)
        QTimer.singleShot(0, lambda: (turns.append(1), QTimer.singleShot(0, lambda: turns.append(2))))  # noqa: B023
        qtbot.waitUntil(lambda: turns == [1, 2] and window.presentation.settled() and bool(painted))  # noqa: B023
        final = (pytest.approx(normal * scale), window.lesson_dock.width())
        assert painted == [final] * len(painted)
    text.removeEventFilter(paints)


def test_a_new_text_size_is_painted_though_qt_asked_for_a_paint_while_it_was_held(qtbot, normal_text):
    # The window's updates are held while a new text size is laid out.  Where Qt's request to paint
    # came in meanwhile, Qt kept what to paint and asked for nothing more once updates were on again:
    # the window stayed as it was, the new text unpainted (about half the runs of the test above,
    # once the 3D pane no longer made the window's panes windows of the window system, whose
    # exposes had painted it).
    window = open_window(qtbot)
    text = window.lesson_panel.text
    painted = []
    paints = _Paints(lambda: painted.append(text.font().pointSizeF()))
    text.installEventFilter(paints)
    normal = text.font().pointSizeF()
    for scale in (1.5, 1.0):
        painted.clear()
        window.presentation.set_scale(scale)
        assert not window.updatesEnabled()  # held for the layouts
        QCoreApplication.sendPostedEvents(window, QEvent.Type.UpdateRequest)  # Qt's request, while held
        qtbot.waitUntil(lambda: window.presentation.settled() and bool(painted))  # noqa: B023
        assert painted[-1] == pytest.approx(scale * normal)
    text.removeEventFilter(paints)


def test_presenting_at_x2_the_z_buffer_format_choice_does_not_widen_the_stage_switches(qtbot, monkeypatch,
                                                                                     normal_text):
    # At its longest choice's width ("float32-reversed (4 bytes)", 341 px at x2 against 278 for the
    # widest switch) it widened the object-order pane's side column, and on a 1280x720 screen that
    # narrowed the left column to 463 px: the dock tabs beside it read "Contr…", "Lesso…".
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    window.show_tab("object order")
    panel = window.tab("object order").widget
    qtbot.waitUntil(panel.depth_format.isVisible)
    widest_switch = max(box.sizeHint().width() for box in [*panel.switches.values(), panel.overdraw])
    assert panel.depth_format.minimumSizeHint().width() <= widest_switch
    assert panel.depth_format.sizeHint().width() <= widest_switch
    window.presentation.set_presenting(False)


def test_presenting_at_x2_on_a_small_screen_the_dock_tabs_show_their_names_whole(qtbot, monkeypatch,
                                                                                 normal_text):
    # A step showing the traced image alone narrowed the left column to 452 px, and its tabs read
    # "Contr…", "Less…", "Exerci…", "Edi…" (their names need 476 px at x2).
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    lessons = window.lesson_panel.lessons()
    window.lesson_panel.select([lesson.id for lesson in lessons].index("ray_casting"), 0)
    qtbot.waitUntil(lambda: window.visible_panes() == ["scene 3D", "image order"]
                    and not window.lesson_panel.typesetting())  # the room shared for the step's words
    bar = next(bar for bar in window.findChildren(QTabBar)
               if bar.isVisible() and "Lessons" in [bar.tabText(i) for i in range(bar.count())])
    qtbot.waitUntil(lambda: _names_whole(bar), timeout=5000)
    window.presentation.set_presenting(False)


def test_presenting_at_x2_on_a_small_screen_the_dock_tabs_show_their_names_whole_over_an_exercise(
        qtbot, monkeypatch, normal_text):
    # With the exercises in front the column was measured by the lessons' dock, behind them, which
    # kept the width it had: in the window (maximized by openbox) 434 px, "Contr…", "Less…",
    # "Exerci…", "Ed…" under the question.  Unmaximized, the fitting left the lessons' dock wider and
    # this test passed before the fix too: here the lessons' dock is first made narrower.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    lessons = window.lesson_panel.lessons()
    k = [lesson.id for lesson in lessons].index("rasterization")
    window.lesson_panel.select(k, 1)
    bar = next(bar for bar in window.findChildren(QTabBar)
               if bar.isVisible() and "Lessons" in [bar.tabText(i) for i in range(bar.count())])
    qtbot.waitUntil(lambda: _names_whole(bar), timeout=5000)  # the lessons in front: fitted

    def narrowed() -> bool:  # as a drag of the column's edge would (the fitting may come after one)
        window.resizeDocks([window.lesson_dock], [380], Qt.Orientation.Horizontal)
        return window.lesson_dock.width() < 400

    qtbot.waitUntil(narrowed)
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    window.exercise_panel.go(len(lessons[k].exercises) - 1)
    qtbot.waitUntil(lambda: _names_whole(bar), timeout=5000)
    window.presentation.set_presenting(False)


def _names_whole(bar) -> bool:
    """The dock tabs' names, each shown whole."""
    names = [bar.tabText(i) for i in range(bar.count())]
    assert names == ["Controls", "Lessons", "Exercises", "Editor"]
    for i, name in enumerate(names):
        assert bar.tabRect(i).width() >= bar.tabSizeHint(i).width(), name
    assert bar.tabRect(bar.count() - 1).right() < bar.width()
    return True
