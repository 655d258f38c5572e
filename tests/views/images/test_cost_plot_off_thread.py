"""The Cost plot is laid out and drawn off the GUI thread, and the finished 'all knobs' plot reads at
1280 x 720 and presenting at x2: no legend over a data point, no two tick labels over each other, no
point label over another, every title and label inside the figure."""

from __future__ import annotations

import itertools
import threading

import pytest

from core.accuracy.sweep import KNOB_NAMES, KNOBS, Row
from views.images import cost_plot_process, plot_theme
from views.images.agg_figure import agg_figure
from views.images.cost_plot import shown_tick_labels
from views.panels.cost_panel import CostPanel

TIMEOUT_MS = 240_000


def _all_knob_rows() -> list[Row]:
    """A sweep of every knob shaped like a real one: each knob's settings cost more and err less, from a
    millisecond to a second and from 0.2 to 0.002 (crowding the cheap corner, as the real ones do); the
    acceleration methods share one error; no z-buffer format fights; one knee per knob."""
    rows = []
    for k, name in enumerate(KNOB_NAMES):
        values = KNOBS[name].values
        for i, value in enumerate(values):
            text = f"{value[0]}@1:{value[1]}" if name == "depth-format" else str(value)
            seconds = 0.001 * (1.0 + 0.3 * k) * 2.5 ** i
            flip = 0.01 if KNOBS[name].time_only else 0.2 / (1.0 + 0.2 * k) / 2.2 ** i
            rows.append(Row(name, text, "raytrace", seconds, 0.0, flip, 0.0, 0.0, flip, 1.0, None,
                            "reference", knee=i == len(values) // 2))
    return rows


def _overlap(a, b) -> bool:
    return a.x0 < b.x1 - 0.5 and b.x0 < a.x1 - 0.5 and a.y0 < b.y1 - 0.5 and b.y0 < a.y1 - 0.5


@pytest.mark.parametrize("scale", [1.0, 2.0])
def test_the_finished_all_knobs_plot_reads_at_1280x720(qtbot, present, scale):
    panel = CostPanel()
    window, presentation = present(panel)  # a 1280 x 720 window
    presentation.set_scale(scale)
    qtbot.waitUntil(lambda: panel.plot_figure is not None and panel.plot_figure.dpi >= 100 * scale - 1,
                    timeout=60_000)  # the first picture: matplotlib loads meanwhile, off the GUI thread
    # The figure the pane would show of a finished sweep of every knob, drawn as the panel draws it.
    figure = agg_figure(panel.canvas.width(), panel.canvas.height(), plot_theme.figure_dpi(panel))
    rows = _all_knob_rows()
    import matplotlib

    with matplotlib.rc_context(plot_theme.fitted_style(figure)):
        cost_plot_process.lay_out_plot(figure, rows, list(range(len(rows))), False, None, None)
    renderer = figure.canvas.get_renderer()
    edge = figure.bbox
    curves = figure.axes[0]
    points = [xy for line in curves.get_lines() for xy in curves.transData.transform(line.get_xydata())]
    legend = curves.get_legend().get_window_extent(renderer)
    inside = [p for p in points if curves.bbox.contains(*p)]
    assert len(inside) == len(points)  # every point of the curves shows
    formats = figure.axes[-1]  # and of the z-buffer formats' curves
    points += [xy for line in formats.get_lines() for xy in formats.transData.transform(line.get_xydata())]
    for ax in figure.axes:  # no legend covers a point
        assert not any(ax.get_legend().get_window_extent(renderer).contains(*p) for p in points)
    for ax in figure.axes:
        for axis in (ax.xaxis, ax.yaxis):
            labels = [t.get_window_extent(renderer) for t in shown_tick_labels(axis)]
            assert len(labels) >= 2  # the axis still reads: at least two values
            for a, b in itertools.combinations(labels, 2):
                assert not _overlap(a, b)
        for text in (ax.title, ax.xaxis.label, ax.yaxis.label, ax.get_legend()):
            box = text.get_window_extent(renderer)
            assert edge.x0 - 1 <= box.x0 and box.x1 <= edge.x1 + 1
            assert edge.y0 - 1 <= box.y0 and box.y1 <= edge.y1 + 1
    shown = [t.get_window_extent(renderer) for t in curves.texts if t.get_visible()]
    assert len(shown) >= len(KNOB_NAMES)  # thinned, but not all gone
    for a, b in itertools.combinations(shown, 2):  # the point labels do not pile up
        assert not _overlap(a, b)
    assert not any(_overlap(a, legend) for a in shown)


def test_a_sweep_never_draws_the_plot_or_a_points_images_on_the_gui_thread(qtbot, monkeypatch, cost_panel):
    # A Cost sweep of every knob held the GUI thread up to 850 ms drawing the plot with matplotlib, and up
    # to a second drawing the images beside it (the setting, the reference, the FLIP map with its colour
    # bar) as the sweep's first point came in.
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    panel = cost_panel
    panel.knob.setCurrentIndex(panel.knob.findData("depth"))
    draws = []
    original = FigureCanvasAgg.draw

    def draw(canvas, *args, **kwargs):
        draws.append((threading.current_thread(), canvas.figure))
        return original(canvas, *args, **kwargs)

    monkeypatch.setattr(FigureCanvasAgg, "draw", draw)
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        panel.run()
    qtbot.waitUntil(lambda: not panel.canvas.pending and len(panel._lines) > 0, timeout=TIMEOUT_MS)
    assert sum(len(i) for i in panel._lines.values()) == len(KNOBS["depth"].values)
    last = len(KNOBS["depth"].values) - 1
    panel.show_point(last)  # a click on the last point
    qtbot.waitUntil(lambda: not panel.image_canvas.pending and not panel.canvas.pending, timeout=TIMEOUT_MS)
    shown = panel.image_figure
    assert any(figure is shown for _, figure in draws)  # the images shown were drawn here, ...
    assert all(thread is not threading.main_thread() for thread, _ in draws)  # ... never on the GUI thread
    # The plot was drawn in a process of its own (its Python holds no lock of the window's process).
    from core import helper_process

    plots = helper_process._helpers.get(cost_plot_process.__name__)
    assert plots is not None and plots.process.poll() is None
    assert not any(figure is panel.plot_figure for _, figure in draws)
    assert panel.plot_figure.axes[0].get_xlabel().startswith("render time")
    titles = [ax.get_title() for ax in shown.axes if ax.images]
    assert titles[0].startswith(f"depth = {panel._points[last].row.value}")
    assert titles[1].startswith("reference")


def test_while_a_sweep_runs_a_new_knobs_curve_never_pushes_the_legend_off_the_plot():
    # While a sweep runs the plot is drawn quickly, in the places of its last full layout. Presenting at
    # x2 at 1920 x 1080, that layout was made for the first knob's one-line legend; with every knob's
    # curve in, the legend under the curves ran off the figure's bottom until the sweep ended.
    import matplotlib


    rows = [r for r in _all_knob_rows() if r.knob != "depth-format"]
    first = [r for r in rows if r.knob == rows[0].knob]
    size = (741, 644, 200.0)  # the pane's figure presenting at x2 at 1920 x 1080
    full = agg_figure(*size)
    with matplotlib.rc_context(plot_theme.fitted_style(full)):
        cost_plot_process.lay_out_plot(full, first, list(range(len(first))), False, None, None)
    quick = agg_figure(*size)
    with matplotlib.rc_context(plot_theme.fitted_style(quick)):
        cost_plot_process.lay_out_plot(quick, rows, list(range(len(rows))), False, None,
                                       cost_plot_process._places(full))
    renderer = quick.canvas.get_renderer()
    legend = quick.axes[0].get_legend()
    assert len(legend.get_texts()) == len({r.knob for r in rows})  # every knob's curve is named
    box, edge = legend.get_window_extent(renderer), quick.bbox
    assert edge.y0 - 1 <= box.y0 and box.y1 <= edge.y1 + 1  # and the names show whole


@pytest.mark.parametrize("size", [(530, 630), (755, 512)])  # x2 on 1920 x 1080; x2 at 1280 x 720
def test_every_legend_of_the_all_knobs_plot_stays_inside_the_figure_presenting_at_x2(size):
    # In the Cost pane presenting at x2 on a 1920 x 1080 screen (530 x 630 pixels at 200 dpi), the
    # z-buffer formats' legend, laid out under its axis label, fell below the figure's bottom: unseen.
    import matplotlib

    figure = agg_figure(*size, 200.0)
    rows = _all_knob_rows()
    with matplotlib.rc_context(plot_theme.fitted_style(figure)):
        cost_plot_process.lay_out_plot(figure, rows, list(range(len(rows))), False, None, None)
    renderer, edge = figure.canvas.get_renderer(), figure.bbox
    legends = [ax.get_legend() for ax in figure.axes]
    assert len(legends) == 2 and all(legend is not None and legend.get_visible() for legend in legends)
    for legend in legends:
        box = legend.get_window_extent(renderer)
        assert edge.x0 - 1 <= box.x0 and box.x1 <= edge.x1 + 1
        assert edge.y0 - 1 <= box.y0 and box.y1 <= edge.y1 + 1
