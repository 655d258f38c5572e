"""Object order's pixel history reads whole presenting at x2 on a 1280 x 720 screen: its caption's
lines and every fragment's row (up to three) inside the table's view, unscrolled."""

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
