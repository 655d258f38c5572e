"""The Cost pane's plot keeps a size that reads: beside the chosen point where the pane is wide, else the
plot and the point are two pages, and a click on a point shows the point's page."""

from dataclasses import replace

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt
from PySide6.QtWidgets import QTabWidget

from core.accuracy.sweep import DEPTH_RATIOS, KNOB_NAMES, KNOBS, Row
from core.object_order.depth_formats import DEPTH_FORMATS
from core.presets_trace import mirror_and_glass
from core.srgb import to_srgb8
from views.images import cost_plot_process, plot_theme
from views.images.cost_plot import point_position
from views.panels.cost_panel import CostPanel
from views.panels.cost_sheet import plot_inches

TIMEOUT_MS = 240_000


def _quick_panel() -> CostPanel:
    """A Cost panel on a small scene, set for a quick sweep of the ray depth."""
    panel = CostPanel()
    scene = mirror_and_glass()
    panel.set_scene(replace(scene, camera=scene.camera.replace(width=320, height=240)))
    panel.width_px.setValue(32)
    panel.reference_spp.setValue(2)
    panel.knob.setCurrentIndex(panel.knob.findData("depth"))
    return panel


def _swept(qtbot, panel) -> None:
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        panel.run()
    qtbot.waitUntil(lambda: panel.plot_figure is not None and not panel.canvas.pending, timeout=TIMEOUT_MS)


def _whole_in_view(widget) -> bool:
    return widget.isVisible() and widget.visibleRegion().boundingRect() == widget.rect()


def _readable(panel) -> bool:
    """The plot is drawn at least at the size that reads, at its text's resolution."""
    dpi = plot_theme.figure_dpi(panel)
    width, height = plot_inches(dpi / plot_theme.DPI)
    return panel.canvas.width() >= width * dpi - 1 and panel.canvas.height() >= height * dpi - 1


def _every_knob() -> tuple[list[Row], list[int]]:
    """A sweep of every knob, as the lecture scene gives it: each knob's values, dearer and closer to the
    reference one after another (the acceleration methods on one error), and the z-buffer formats."""
    rows = []
    for name in KNOB_NAMES:
        if name == "depth-format":
            rows += [Row(name, f"{f}@1:{ratio}", "raster", 0.002, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0, 4, "float64")
                     for f in DEPTH_FORMATS for ratio in DEPTH_RATIOS]
            continue
        for k, value in enumerate(KNOBS[name].values):
            flip = 0.008 if KNOBS[name].time_only else 0.03 / (k + 1)
            rows.append(Row(name, str(value), "raytrace", 0.001 * 3.0 ** k, 0.0, flip, 0.0, 0.0, flip, 1.0,
                            None, "none" if KNOBS[name].time_only else "reference", knee=k == 1))
    return rows, list(range(len(rows)))


@pytest.mark.parametrize("scale", [1.0, 1.5, 2.0])
def test_at_its_least_size_a_sweep_of_every_knob_keeps_its_text_and_its_legends_off_the_curves(scale):
    rows, indices = _every_knob()
    dpi = plot_theme.DPI * scale
    width, height = plot_inches(scale)
    figure, _, _, _ = cost_plot_process.draw(width * dpi, height * dpi, dpi, rows, indices, True, None, None)
    renderer = figure.canvas.get_renderer()
    for ax in figure.axes:  # no smaller on the screen than 70 % of matplotlib's 10 points at x1
        assert ax.xaxis.label.get_fontsize() * scale >= 7.0
    points = [xy for ax in figure.axes for line in ax.get_lines() for xy in ax.transData.transform(
        line.get_xydata())]
    for ax in figure.axes:
        legend = ax.get_legend().get_window_extent(renderer)
        assert not any(legend.contains(*p) for p in points)
        assert all(other is ax or not legend.overlaps(other.get_window_extent()) for other in figure.axes)


def test_a_wide_pane_shows_the_plot_and_the_point_side_by_side(qtbot, present):
    panel = _quick_panel()
    present(panel)  # 1280 x 720, text at x1: the room the Cost tab has beside the docks
    _swept(qtbot, panel)
    assert panel.sheet.side_by_side
    qtbot.waitUntil(lambda: panel.image_figure is not None and not panel.image_canvas.pending,
                    timeout=TIMEOUT_MS)  # the sweep's first point is shown
    assert _whole_in_view(panel.canvas) and _whole_in_view(panel.image_canvas)
    assert _readable(panel)


def test_presenting_at_x2_the_plot_and_the_point_are_pages_and_a_click_shows_the_point(qtbot, present):
    panel = _quick_panel()
    window, presentation = present(panel)
    window.resize(1260, 900)  # about the room of the Cost tab presenting at x2 on 1920 x 1080
    presentation.set_scale(2.0)
    _swept(qtbot, panel)
    qtbot.waitUntil(lambda: panel.plot_figure.dpi > 190 and not panel.canvas.pending, timeout=TIMEOUT_MS)
    assert not panel.sheet.side_by_side and panel.sheet.showing_plot()
    # The plot takes the pane's width, at a size that reads, with nothing to scroll sideways.
    assert _readable(panel) and panel.canvas.width() > 0.9 * panel.width()
    assert panel.canvas.visibleRegion().boundingRect().width() == panel.canvas.width()
    assert not panel.image_canvas.isVisible()

    # The sweep showed its first point; click another, the one farthest on the screen from the rest (the
    # deepest rays of a depth sweep cost about the same and err alike, and may lie under one pixel).
    where = {i: np.array(panel.point_position(i)) for i in panel._points}
    apart = {i: min(np.hypot(*(p - q)) for j, q in where.items() if j != i) for i, p in where.items()}
    other = max((i for i in where if i != panel.selected), key=apart.get)
    assert apart[other] > 3  # a click on it picks it alone
    x, y = where[other]
    with qtbot.waitSignal(panel.point_selected, timeout=5000) as picked:
        qtbot.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=QPoint(round(x), round(y)))
    assert picked.args == [other]
    assert not panel.sheet.showing_plot()
    assert not panel.canvas.pending  # the plot behind its page is not drawn
    qtbot.waitUntil(lambda: _whole_in_view(panel.image_canvas) and not panel.image_canvas.pending,
                    timeout=TIMEOUT_MS)
    setting, reference, _ = panel.shown_images()
    assert np.array_equal(setting, to_srgb8(panel._points[other].color))
    assert setting.shape == reference.shape == (24, 32, 3)
    assert panel.explanation.isVisible() and "ray depth" in panel.explanation.text()

    with qtbot.waitSignal(panel.plot_drawn, timeout=TIMEOUT_MS):  # drawn once its page shows again
        panel.sheet.findChild(QTabWidget).setCurrentIndex(0)
    ax, *at = point_position(panel.plot_figure, panel._points[other].row)
    (mark,) = [line for line in ax.get_lines() if line.get_marker() == "x"]  # the chosen point marked
    assert tuple(mark.get_xydata()[0]) == pytest.approx(tuple(at))

    presentation.set_scale(1.0)  # back at x1 the pane has the width for both again
    qtbot.waitUntil(lambda: panel.sheet.side_by_side)
    assert _whole_in_view(panel.canvas) and _whole_in_view(panel.image_canvas)
