"""Object order's pixel history reads whole presenting at x2 on a 1280 x 720 screen: its caption's
lines and every fragment's row (up to three) inside the table's view, unscrolled; and the verdict over
a pixel's evidence (its fragments, its ray tree) takes the lines the evidence's rows do not need."""

from window_helpers import RENDER_TIMEOUT_MS, presenting_on_1280x720


def test_presenting_at_x2_on_1280x720_a_picked_pixels_history_shows_its_rows_whole(qtbot, monkeypatch):
    # The details under the buffers kept two fifths of the tab: the caption showed two of its three
    # lines and the table its header and the top half of the first fragment's row.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    window.show_tab("Object order")
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    panel.pick_pixel(160, 150)  # the cone over the ground: two fragments
    table, caption = panel.history, panel.history_caption
    qtbot.waitUntil(lambda: table.rowCount() == 2, timeout=RENDER_TIMEOUT_MS)

    def whole() -> bool:
        assert window.frameGeometry().height() <= 720  # and the window stays on the screen
        assert caption.isVisible() and caption.height() >= caption.heightForWidth(caption.width())
        view = table.viewport().rect()
        for row in range(table.rowCount()):
            assert view.contains(table.visualRect(table.model().index(row, 0))), row
        return True

    qtbot.waitUntil(whole, timeout=5000)
    window.presentation.set_presenting(False)


def _verdict_takes_the_rows_room(qtbot, window, verdict, last_row) -> None:
    """Wait until ``verdict`` reads whole, on more than one line, with the evidence's last row (its
    rectangle in its view, and the view's rectangle, from ``last_row()``) whole in view; then stop
    presenting."""
    full = f"Why pixel ({verdict.shown.pixel[0]}, {verdict.shown.pixel[1]}): {verdict.shown.sentence}"

    def whole() -> bool:
        assert window.frameGeometry().height() <= 720
        lines = verdict.shown_lines()
        assert len(lines) > 1 and " ".join(lines) == full, lines
        row, view = last_row()
        assert view.contains(row), (row, view)
        return True

    qtbot.waitUntil(whole, timeout=5000)
    window.presentation.set_presenting(False)


def _step(window, lesson_id: str, step: int) -> None:
    from core.lessons.lesson_file import shipped_lessons

    window.lesson_panel.select([lesson.id for lesson in shipped_lessons()].index(lesson_id), step)


def test_presenting_at_x1_5_on_1280x720_a_one_fragment_pixels_verdict_takes_the_rows_room(qtbot, monkeypatch):
    # The rasterization lesson's pixel (3, 7) has one fragment: its verdict was cut short with "…" on
    # one line above a table with two empty rows' room.  It takes the lines the rows do not need, and
    # the fragment's row stays whole in view.
    window = presenting_on_1280x720(qtbot, monkeypatch, 1.5)
    _step(window, "rasterization", 0)
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    table, verdict = panel.history, panel.verdict
    qtbot.waitUntil(lambda: table.rowCount() == 1 and verdict.shown is not None, timeout=RENDER_TIMEOUT_MS)
    assert verdict.shown.pixel == (3, 7)
    _verdict_takes_the_rows_room(qtbot, window, verdict, lambda: (
        table.visualRect(table.model().index(0, 0)), table.viewport().rect()))


def test_presenting_at_x2_on_1280x720_a_short_ray_trees_verdict_takes_the_rows_room(qtbot, monkeypatch):
    # The shadow-ray step's pixel (230, 155) has a ray tree of two rays, the primary and its shadow
    # ray: its verdict kept one line, "Why pixel (230, 155): The primary ray hits ground …", above a
    # tree with two empty rows' room, the room kept for four rays.  It takes the lines the rays do not
    # need, and both rays' rows stay whole in view.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    _step(window, "ray_casting", 1)
    panel = window.tab("image order").widget
    tree, verdict = panel.tree, panel.verdict
    qtbot.waitUntil(lambda: tree.row_count() == 2 and verdict.shown is not None, timeout=RENDER_TIMEOUT_MS)
    assert verdict.shown.pixel == (230, 155)
    _verdict_takes_the_rows_room(qtbot, window, verdict, lambda: (
        tree.visualItemRect(tree.topLevelItem(0).child(0)), tree.viewport().rect()))
