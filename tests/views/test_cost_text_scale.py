"""Presentation mode's text scale reaches the Cost tab's plot: its text grows on the screen with the rest."""

import pytest

from views.cost_panel import CostPanel


def _texts_px(panel) -> dict[str, tuple[float, object]]:
    """Every shown text of the plot: its height on the canvas (logical pixels) and its box."""
    panel.canvas.draw()
    renderer = panel.canvas.get_renderer()
    ratio = panel.canvas.device_pixel_ratio or 1.0
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
    qtbot.waitUntil(lambda: panel.canvas is not None)
    before = _texts_px(panel)
    presentation.set_scale(scale)
    qtbot.waitUntil(lambda: panel.canvas is not None and panel.canvas.figure.dpi > 100 * (scale - 0.1))
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
