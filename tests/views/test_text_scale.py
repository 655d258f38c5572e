"""Text sized apart from the window's (a heading, a note, a sheet over a pane) follows the text scale."""

import pytest
from PySide6.QtWidgets import QMainWindow, QWidget

from views.hard_cases_panel import HardCasesPanel
from views.presentation import Presentation
from views.stale_cover import cover


@pytest.fixture
def presented(qtbot):
    window = QMainWindow()
    panel = HardCasesPanel()
    window.setCentralWidget(panel)
    qtbot.addWidget(window)
    window.resize(1280, 720)
    window.show()
    return window, panel, Presentation(window)


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
