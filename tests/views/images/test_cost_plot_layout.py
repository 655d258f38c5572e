"""The cost plot with the z-buffer formats' panel: beside the curves on a wide figure, below on a narrow one.

Half a 1280 x 720 window holds a figure about 5.4 x 4.8 inches. With both panels side by side there,
the two titles ran into each other, the legends spilled out of their panels and the curves were a
sliver. Each text of the figure is checked against every other and against the figure's edges.
"""

from __future__ import annotations

import itertools

import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from core.accuracy.sweep import DEPTH_RATIOS, Row
from core.object_order.depth_formats import DEPTH_FORMATS
from views.images.cost_plot import draw_cost_plot, tidy_cost_plot


def _rows() -> list[Row]:
    swept = (("spp", [("1x1", 0.004, 0.03), ("2x2", 0.015, 0.01), ("4x4", 0.06, 0.004)]),
             ("depth", [("0", 0.003, 0.02), ("1", 0.004, 0.01), ("5", 0.005, 0.009)]))
    curves = [Row(knob, value, "raytrace", seconds, 0.0, flip, 0.0, 0.0, flip, 1.0, None, "reference")
              for knob, points in swept for value, seconds, flip in points]
    formats = [Row("depth-format", f"{name}@1:{ratio}", "raster", 0.002, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 4,
                   "float64") for name in DEPTH_FORMATS for ratio in DEPTH_RATIOS]
    return curves + formats


def _texts(figure):
    for ax in figure.axes:
        yield from (t for t in (ax.title, ax.xaxis.label, ax.yaxis.label) if t.get_text())
        yield ax.get_legend()


@pytest.mark.parametrize(("size", "beside"), [((5.4, 4.8), False), ((9.0, 6.0), True)])
def test_the_formats_panel_sits_where_there_is_room_and_no_text_runs_into_another(size, beside):
    figure = Figure(figsize=size, dpi=100, layout="constrained")
    canvas = FigureCanvasAgg(figure)
    draw_cost_plot(figure, _rows())
    canvas.draw()
    tidy_cost_plot(figure)  # the legend under the axis label, laid out again
    canvas.draw()
    curves_ax = figure.axes[0]
    curves, formats = (ax.get_window_extent() for ax in figure.axes)
    if beside:
        assert formats.x0 >= curves.x1
    else:
        assert formats.y1 <= curves.y0  # below (y grows upwards)
        assert curves.height >= 1.5 * formats.height and curves.width == pytest.approx(formats.width, abs=30)
    renderer = canvas.get_renderer()
    boxes = [t.get_window_extent(renderer) for t in _texts(figure)]
    edge = figure.bbox
    for box in boxes:  # inside the figure
        assert box.x0 >= -1 and box.y0 >= -1 and box.x1 <= edge.x1 + 1 and box.y1 <= edge.y1 + 1
    titles_and_labels = [t.get_window_extent(renderer) for ax in figure.axes
                         for t in (ax.title, ax.xaxis.label, ax.yaxis.label)]
    for a, b in itertools.combinations(titles_and_labels, 2):
        assert not (a.x0 < b.x1 - 1 and b.x0 < a.x1 - 1 and a.y0 < b.y1 - 1 and b.y0 < a.y1 - 1)
    legend, panel = curves_ax.get_legend().get_window_extent(renderer), curves  # under its own panel
    assert panel.x0 - 1 <= legend.x0 and legend.x1 <= panel.x1 + 1
    points = [xy for ax in figure.axes for line in ax.get_lines() for xy in ax.transData.transform(
        line.get_xydata())]
    for ax in figure.axes:  # no legend over a point of either panel, nor over the other panel
        legend = ax.get_legend().get_window_extent(renderer)
        assert not any(legend.contains(*p) for p in points)
        for other in figure.axes:
            assert other is ax or not legend.overlaps(other.get_window_extent())


@pytest.mark.parametrize("size", [(5.4, 4.8), (6.4, 3.6), (9.0, 6.0)])
@pytest.mark.parametrize("dpi", [100, 200])  # 200: text twice as large against the panel, as at x2
def test_the_no_fights_note_reads_whole_clear_of_the_formats_legend(size, dpi):
    """Every format shows 0 % wrong pixels here: the note says why, and covers no legend entry (it sat on
    them in the short panel below the curves, half a 1280x720 window)."""
    figure = Figure(figsize=size, dpi=dpi, layout="constrained")
    canvas = FigureCanvasAgg(figure)
    draw_cost_plot(figure, _rows())
    canvas.draw()
    tidy_cost_plot(figure)
    canvas.draw()
    renderer, formats = canvas.get_renderer(), figure.axes[-1]
    legend = formats.get_legend()
    notes = [t for t in [*formats.texts, legend.get_title()] if "fights" in t.get_text()]
    assert len(notes) == 1 and "close enough in depth" in notes[0].get_text().replace("\n", " ")
    note = notes[0].get_window_extent(renderer)
    entries = [t.get_window_extent(renderer) for t in legend.get_texts()]
    entries += [h.get_window_extent(renderer) for h in legend.legend_handles]
    assert len(entries) == 2 * len(DEPTH_FORMATS)
    for entry in entries:
        assert not (note.x0 < entry.x1 and entry.x0 < note.x1 and note.y0 < entry.y1 and entry.y0 < note.y1)
    edge = figure.bbox
    assert note.x0 >= -1 and note.y0 >= -1 and note.x1 <= edge.x1 + 1 and note.y1 <= edge.y1 + 1
