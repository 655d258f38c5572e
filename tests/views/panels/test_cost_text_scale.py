"""Presentation mode's text scale reaches the Cost tab's plot: its text grows on the screen with the rest."""

import pytest

from views.panels.cost_panel import CostPanel


def _texts_px(panel) -> dict[str, tuple[float, object]]:
    """Every shown text of the plot: its height on the canvas (logical pixels) and its box."""
    renderer = panel.plot_figure.canvas.get_renderer()
    ratio = panel.canvas.devicePixelRatioF()
    ax = panel.plot_figure.axes[0]
    ticks = [label for axis in (ax.xaxis, ax.yaxis) for at, label in zip(
        axis.get_majorticklocs(), axis.get_majorticklabels(), strict=True)
        if min(axis.get_view_interval()) <= at <= max(axis.get_view_interval())]  # drawn ones only
    texts = [ax.title, ax.xaxis.label, *ticks, *ax.texts]
    shown = {}
    for t in texts:
        if t.get_visible() and t.get_text().strip():
            box = t.get_window_extent(renderer)
            shown[t.get_text().replace("\n", " ")] = (min(box.width, box.height) / ratio, box)
    return shown


@pytest.mark.parametrize("scale", [1.5, 2.0])
def test_the_cost_plot_text_grows_with_the_presentation_scale_and_stays_on_the_canvas(qtbot, present, scale):
    panel = CostPanel()
    window, presentation = present(panel)
    # The first picture: matplotlib loads meanwhile, off the GUI thread.
    qtbot.waitUntil(lambda: panel.plot_figure is not None and not panel.canvas.pending, timeout=60_000)
    before = _texts_px(panel)
    presentation.set_scale(scale)
    qtbot.waitUntil(lambda: panel.plot_figure.dpi > 100 * (scale - 0.1) and not panel.canvas.pending)
    after = _texts_px(panel)
    common = before.keys() & after.keys()
    assert len(common) >= 5  # the title, axis label, the tick labels, the empty plot's note
    for text in common:
        assert after[text][0] == pytest.approx(scale * before[text][0], rel=0.1), text
    figure = panel.plot_figure.bbox
    for text, (_, box) in after.items():  # nothing cut off by the canvas's edge
        assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= figure.x1 + 1 and box.y1 <= figure.y1 + 1, text
    # The window's text and the plot's are of one size: the axis label about as tall as the panel's lines.
    label = after[panel.plot_figure.axes[0].get_xlabel()][0]
    assert label == pytest.approx(panel.fontMetrics().height(), rel=0.35)


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 and b.x0 < a.x1 and a.y0 < b.y1 and b.y0 < a.y1


def test_a_small_pane_at_double_text_draws_the_plot_at_full_text_and_scrolls_to_all_of_it(qtbot, present):
    # About the room the Cost tab gets in a 1280 x 720 window presenting at x2: before, the plot was
    # squeezed into it, its text drawn at half size and its legends over the curves.
    panel = CostPanel()
    window, presentation = present(panel)
    window.resize(700, 470)
    presentation.set_scale(2.0)
    qtbot.waitUntil(lambda: panel.plot_figure is not None and panel.plot_figure.dpi > 190, timeout=60_000)
    qtbot.waitUntil(lambda: panel.plot_figure.bbox.width >= 1000 and not panel.canvas.pending)
    assert not panel.sheet.side_by_side and panel.sheet.showing_plot()
    shown = _texts_px(panel)
    ax = panel.plot_figure.axes[0]
    renderer = panel.plot_figure.canvas.get_renderer()
    title, ylabel = ax.title.get_window_extent(renderer), ax.yaxis.label.get_window_extent(renderer)
    xlabel = ax.xaxis.label.get_window_extent(renderer)
    assert not _overlap(title, ylabel) and not _overlap(xlabel, ylabel)
    figure = panel.plot_figure.bbox
    for text, (_, box) in shown.items():  # nothing cut off by the canvas's edge
        assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= figure.x1 + 1 and box.y1 <= figure.y1 + 1, text
    # The text at the window's size, as in a large pane (the axis label about a line of the panel's).
    assert shown[ax.get_xlabel()][0] == pytest.approx(panel.fontMetrics().height(), rel=0.35)
    # The whole plot a scroll away, down and across.
    area = panel.canvas.parentWidget().parentWidget().parentWidget()
    for bar, size, seen in ((area.horizontalScrollBar(), panel.canvas.width(), area.viewport().width()),
                            (area.verticalScrollBar(), panel.canvas.height(), area.viewport().height())):
        assert seen < size and bar.maximum() >= size - seen


def test_presenting_at_x2_on_1280x720_the_cost_plots_title_is_whole_in_view(qtbot, monkeypatch):
    # The plot keeps its size that reads (wider than the tab at x2) and scrolls; its title, centred over
    # the whole figure, was cut at the view's right edge ("What accuracy costs ir").  It starts at the
    # axes' left edge now, in view before any scroll.
    from window_helpers import presenting_on_1280x720

    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    window.show_tab("Cost")
    panel = window.tab("cost").widget
    qtbot.waitUntil(lambda: panel.plot_figure is not None and panel.plot_figure.dpi > 190
                    and not panel.canvas.pending, timeout=60_000)
    area = panel.canvas.parentWidget().parentWidget().parentWidget()
    assert area.horizontalScrollBar().value() == 0 and area.verticalScrollBar().value() == 0
    ratio = panel.canvas.devicePixelRatioF()
    renderer = panel.plot_figure.canvas.get_renderer()
    for ax in panel.plot_figure.axes:
        box = ax.title.get_window_extent(renderer)  # figure pixels, y upwards
        top = (panel.plot_figure.bbox.height - box.y1) / ratio
        assert box.x0 >= 0 and box.x1 / ratio <= area.viewport().width(), ax.get_title()
        assert top >= 0 and (panel.plot_figure.bbox.height - box.y0) / ratio <= area.viewport().height()
    window.presentation.set_presenting(False)
