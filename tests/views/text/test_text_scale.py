"""Text sized apart from the window's (a heading, a note, a sheet over a pane) follows the text scale."""

import pytest
from PySide6.QtCore import QPoint
from PySide6.QtWidgets import QScrollArea, QWidget

from core import hard_cases
from views.panels.hard_cases_panel import HardCasesPanel
from views.panels.pane_cover import cover


@pytest.fixture
def presented(present):
    panel = HardCasesPanel()
    window, presentation = present(panel)
    yield window, panel, presentation
    panel.shutdown()


def _heights(panel) -> tuple[int, int, int]:
    """Pixel heights of the letters of the case's title, its explanation and its plain text."""
    return tuple(w.fontMetrics().height() for w in (panel.title, panel.explanation, panel.verdict))


@pytest.mark.parametrize("scale", [1.5, 2.0])
def test_the_hard_cases_title_and_explanation_grow_with_the_text_and_stay_larger_than_it(qtbot, presented,
                                                                                         scale):
    _, panel, presentation = presented
    title, explanation, body = _heights(panel)
    assert title > explanation > body  # a heading, then a note a little larger than the text
    presentation.set_scale(scale)
    qtbot.waitUntil(lambda: _heights(panel)[2] >= scale * body - 2)
    qtbot.waitUntil(lambda: _heights(panel)[0] >= scale * title - 2)
    grown = _heights(panel)
    for before, after in zip((title, explanation, body), grown, strict=True):
        assert after == pytest.approx(scale * before, rel=0.12)
    assert grown[0] > grown[1] > grown[2]
    presentation.set_scale(1.0)
    qtbot.waitUntil(lambda: _heights(panel) == (title, explanation, body))


def test_the_sheet_over_a_stale_pane_grows_with_the_text(qtbot, presented):
    window, panel, presentation = presented
    pane = QWidget(panel)
    pane.resize(600, 400)
    cover(pane, "Not rendered: over the memory budget")
    sheet = pane.findChild(QWidget, "stale cover")
    small = sheet.fontMetrics().height()
    presentation.set_scale(2.0)
    qtbot.waitUntil(lambda: sheet.fontMetrics().height() >= 1.8 * small)
    assert sheet.fontMetrics().height() == pytest.approx(2 * small, rel=0.12)


def _scroll_area(widget) -> QScrollArea:
    """The nearest scroll area ``widget`` is drawn in."""
    while not isinstance(widget, QScrollArea):
        widget = widget.parentWidget()
    return widget


# The panel alone in a 1280 x 720 window, and about the room it gets as a tab of the window there.
@pytest.mark.parametrize("size", [(1280, 720), (730, 560)])
def test_at_x2_the_hard_cases_words_keep_the_panes_width_and_the_table_shows_every_value(qtbot, presented,
                                                                                          size):
    window, panel, presentation = presented
    window.resize(*size)
    presentation.set_scale(2.0)
    panel.select(next(iter(hard_cases.CASES)))  # shown on its own at first; worked out in the background
    qtbot.waitUntil(lambda: panel.result is not None and bool(panel.table_cells), timeout=60_000)
    outer = _scroll_area(panel.title)
    qtbot.waitUntil(lambda: panel.title.width() <= outer.viewport().width())
    for words in (panel.title, panel.slider_label, panel.verdict, panel.explanation):  # wrapped, not cut
        assert words.width() <= outer.viewport().width(), words.text()
    table = _scroll_area(panel.table_cells[0][0])

    def rows_cut() -> list[str]:
        cut = []
        for cells in panel.table_cells:  # every row whole, however tall the large text makes it
            top = cells[0].mapTo(table.viewport(), QPoint(0, 0)).y()
            if not (top >= 0 and top + cells[0].height() <= table.viewport().height()):
                cut.append(f"{cells[0].text()!r} at {top}, {cells[0].height()} tall")
            for cell in cells:  # and every value whole across: the reference's too, without scrolling
                left = cell.mapTo(table.viewport(), QPoint(0, 0)).x()
                if not (left >= 0 and left + cell.width() <= table.viewport().width()
                        and cell.width() >= cell.minimumSizeHint().width()):
                    cut.append(f"{cell.text()!r} at x {left}, {cell.width()} wide")
        return cut

    qtbot.waitUntil(lambda: rows_cut() == [], timeout=5000)
