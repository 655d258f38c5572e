"""The Cost panel: a tiny sweep in the background fills the plot point by point; a click shows a point."""

import time
from dataclasses import replace

import numpy as np
import pytest
from PySide6.QtCore import QPoint, Qt, QTimer

from core.accuracy.sweep import KNOBS
from core.presets_trace import mirror_and_glass
from core.srgb import to_srgb8
from views.panels.cost_panel import REPLOT_MS

TIMEOUT_MS = 240_000


@pytest.fixture
def panel(cost_panel):
    return cost_panel


def _pick(panel, name):
    panel.knob.setCurrentIndex(panel.knob.findData(name))


def _plotted_points(panel):
    return sum(len(indices) for indices in panel._lines.values())


def _drawn(qtbot, panel):
    """Wait for the plot's newest picture (drawn off the GUI thread) to be shown."""
    qtbot.waitUntil(lambda: panel.plot_figure is not None and not panel.canvas.pending, timeout=TIMEOUT_MS)


def _images_drawn(qtbot, panel):
    """Wait for the newest picture of the point's images (drawn off the GUI thread) to be shown."""
    qtbot.waitUntil(lambda: panel.image_figure is not None and not panel.image_canvas.pending,
                    timeout=TIMEOUT_MS)


def test_sweep_fills_the_plot_and_a_click_shows_the_point(qtbot, panel):
    _pick(panel, "depth")
    # No progress bar before a sweep (empty, it read as a field to type into), and the status keeps its
    # place when it comes.
    assert not panel.progress.isVisible() and panel.status.isVisible()
    left = panel.status.mapTo(panel, panel.status.rect().topLeft()).x()
    qtbot.mouseClick(panel.run_button, Qt.MouseButton.LeftButton)
    assert panel.running and panel.progress.isVisible()
    assert panel.status.mapTo(panel, panel.status.rect().topLeft()).x() == left
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS) as finished:
        pass
    assert finished.args == [True]
    _drawn(qtbot, panel)
    n = len(KNOBS["depth"].values)
    assert _plotted_points(panel) == n
    rows = panel.rows()
    assert len(rows) == n and sum(r.knee for r in rows) == 1
    assert "Knees: depth" in panel.status.text()

    x, y = panel.point_position(0)
    with qtbot.waitSignal(panel.point_selected, timeout=5000) as picked:
        qtbot.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=QPoint(round(x), round(y)))
    assert picked.args == [0]
    _images_drawn(qtbot, panel)
    setting, reference, error_map = panel.shown_images()
    point = panel._points[0]
    assert np.array_equal(setting, to_srgb8(point.color))  # shown in sRGB
    assert np.array_equal(reference, to_srgb8(panel.sweep.references["raytrace"].color))
    assert error_map.shape == (24, 32)
    assert float(np.mean(error_map)) == pytest.approx(point.row.flip, rel=1e-4)
    assert "ray depth" in panel.explanation.text()
    # A click right on any point shows that point, even where the deepest settings, costing about
    # the same and erring as much, lie within a few pixels of one another; where two lie within a
    # pixel, the click (on whole pixels) shows the one nearer to it.
    where = np.array([panel.point_position(index) for index in range(n)])
    shown = set()
    for index in reversed(range(n)):
        click = QPoint(*np.round(where[index]).astype(int))
        away = np.hypot(*(where - (click.x(), click.y())).T)
        with qtbot.waitSignal(panel.point_selected, timeout=5000) as picked:
            qtbot.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=click)
        assert away[picked.args[0]] <= away.min() + 0.01
        shown.add(picked.args[0])
    assert set(range(4)) <= shown  # depths 0 to 3 err each differently: each is told apart


def test_of_points_within_reach_of_a_click_the_nearest_is_shown(qtbot, panel, monkeypatch):
    # Three points, the last two 4 pixels apart, both within a click's reach (6 pixels): a click
    # on either shows that one.
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(4, 3), dpi=100)
    FigureCanvasAgg(figure)
    ax = figure.add_axes((0, 0, 1, 1), xlim=(0, 100), ylim=(0, 100))
    (line,) = ax.plot([10, 50, 51], [10, 50, 50], "o-", picker=True, pickradius=6)
    monkeypatch.setattr(type(panel), "plot_figure", property(lambda self: figure))
    monkeypatch.setattr(panel, "_lines", {line: [4, 7, 9]}, raising=False)
    shown = []
    monkeypatch.setattr(panel, "show_point", shown.append)
    for x, index in ((50, 7), (51, 9), (10, 4)):
        panel._on_click(*ax.transData.transform((x, 50 if index != 4 else 10)))
        assert shown[-1] == index
    panel._on_click(*ax.transData.transform((90, 90)))  # far from every point: nothing new
    assert shown == [7, 9, 4]


def test_a_running_sweep_draws_its_plot_seldom_and_the_finished_one_in_full(qtbot, panel):
    # A draw of the plot takes a core half a second; the points of cheap settings come in several a
    # second. Drawn once per point, the window froze for seconds at a time (now: the drawer fell behind).
    _pick(panel, "all")
    panel.resize(900, 720)  # the finished sweep's status (its knees) takes two lines
    qtbot.waitUntil(lambda: panel.canvas.width() < 600)
    draws, sizes = [], set()

    def drawn():
        draws.append(time.perf_counter())
        sizes.add(panel.canvas.shown.rgba.shape)

    panel.plot_drawn.connect(drawn)
    started = time.perf_counter()
    panel.run()
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS) as finished:
        pass
    assert finished.args == [True]
    done = time.perf_counter()
    qtbot.waitUntil(lambda: bool(draws) and draws[-1] > done, timeout=TIMEOUT_MS)  # the finished sweep's
    _drawn(qtbot, panel)
    points = len(panel.rows())
    # The first point (shown with its images), one draw per interval, a new panel's layout, the last.
    allowed = 3 + (done - started) / (REPLOT_MS / 1000) + 1
    assert points > allowed  # more points than draws: drawn once per point, this would fail
    assert len(draws) <= allowed
    assert panel.canvas.shown.extra["layout"] is not None  # the last: laid out in full
    assert _plotted_points(panel) == points
    assert len(sizes) == 1  # the plot keeps its size (the knees' two status lines do not shrink it)


def test_depth_formats_get_their_own_panel_and_a_click_there_shows_the_point(qtbot, panel):
    _pick(panel, "depth-format")
    panel.run()
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        pass
    _drawn(qtbot, panel)
    n = len(KNOBS["depth-format"].values)
    assert _plotted_points(panel) == n and len(panel.rows()) == n
    (ax,) = panel.plot_figure.axes
    assert "near ratio" in ax.get_xlabel() and "wrong object" in ax.get_ylabel()
    last = n - 1  # int16 at the largest ratio
    x, y = panel.point_position(last)
    with qtbot.waitSignal(panel.point_selected, timeout=5000) as picked:
        qtbot.mouseClick(panel.canvas, Qt.MouseButton.LeftButton, pos=QPoint(round(x), round(y)))
    # no format fights on this scene, so every curve lies on 0 and the click finds the ratio, any format
    assert panel._points[picked.args[0]].row.value.endswith("@1:10000")
    assert "16-bit" in panel.explanation.text()


def test_cancel_stops_between_renders_and_run_resumes(qtbot, panel):
    _pick(panel, "spp")
    # Stop as the first point is shown (as a user pressing Stop then would): the points the worker
    # finished meanwhile are not shown, however fast it runs ahead of a busy GUI thread.
    panel.point_selected.connect(lambda _: panel.cancel())
    panel.run()
    qtbot.waitUntil(lambda: len(panel._points) >= 1, timeout=TIMEOUT_MS)
    panel.point_selected.disconnect()
    assert not panel.running and panel.run_button.text() == "Resume"
    stopped_at = len(panel._points)
    assert stopped_at == 1 < len(KNOBS["spp"].values)
    panel.run()
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        pass
    _drawn(qtbot, panel)
    assert panel.finished and _plotted_points(panel) == len(KNOBS["spp"].values)
    assert sorted(panel._points) == list(range(len(KNOBS["spp"].values)))


def test_adaptive_point_shows_its_samples_heat_map_and_exports(qtbot, panel, tmp_path):
    _pick(panel, "adaptive")
    panel.run()
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        pass
    panel.show_point(len(KNOBS["adaptive"].values) - 1)
    _images_drawn(qtbot, panel)
    images = panel.shown_images()
    assert len(images) == 4
    heat = images[3]
    assert heat.shape == (24, 32) and heat.min() == 1 and heat.max() == 17
    panel.export_csv(tmp_path / "cost.csv")
    panel.export_plot(tmp_path / "cost.png")
    lines = (tmp_path / "cost.csv").read_text().splitlines()
    assert lines[0].startswith("knob,value,mode,seconds,rmse,flip,wrong_pixel_fraction")
    assert len(lines) == 1 + len(KNOBS["adaptive"].values)
    assert (tmp_path / "cost.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"


def test_knobs_the_scene_cannot_use_are_disabled(panel):
    from core.presets import lecture_scene

    panel.set_scene(lecture_scene())
    item = panel.knob.model().item(panel.knob.findData("tessellation"))
    assert not item.isEnabled() and "no analytic spheres" in item.toolTip()


def test_a_hidden_cost_pane_draws_its_plot_only_when_shown(qtbot, panel, monkeypatch):
    # A lesson step (a new scene) reset the plot of the hidden Cost tab and drew it in full on
    # the GUI thread, a quarter of a second for a pane nobody saw.
    from views.images import cost_plot_process

    _pick(panel, "depth")
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        panel.run()
    _drawn(qtbot, panel)
    assert _plotted_points(panel) > 0
    drawn = []
    original = cost_plot_process.drawn
    monkeypatch.setattr(cost_plot_process, "drawn", lambda *a, **k: (drawn.append(1), original(*a, **k))[1])
    panel.hide()
    scene = mirror_and_glass()
    panel.set_scene(replace(scene, camera=scene.camera.replace(width=160, height=120)))
    assert drawn == []  # hidden: not drawn
    panel.show()
    qtbot.waitUntil(lambda: drawn == [1], timeout=5000)  # shown: drawn once, the new scene's empty plot
    _drawn(qtbot, panel)
    assert _plotted_points(panel) == 0


def test_a_new_scene_then_another_tab_in_the_same_turn_draws_no_plot_until_the_pane_is_back(
        qtbot, panel, monkeypatch):
    # A lesson step sets its scene while the Cost tab still shows, then shows its own tab. The Cost
    # plot was laid out for the new scene in that moment: 1.5 s of matplotlib on a worker thread, which
    # held Python's lock and the window with it for the step's first 100-120 ms stalls.
    from views.images import cost_plot_process

    _pick(panel, "depth")
    with qtbot.waitSignal(panel.sweep_finished, timeout=TIMEOUT_MS):
        panel.run()
    _drawn(qtbot, panel)
    drawn = []
    original = cost_plot_process.drawn
    monkeypatch.setattr(cost_plot_process, "drawn", lambda *a, **k: (drawn.append(1), original(*a, **k))[1])
    scene = mirror_and_glass()
    panel.set_scene(replace(scene, camera=scene.camera.replace(width=160, height=120)))
    panel.hide()  # the same turn: a lesson step's own tab is shown
    later = []
    QTimer.singleShot(0, lambda: later.append(1))  # fires after what the panel deferred to a turn later
    qtbot.waitUntil(lambda: later == [1])
    assert drawn == [] and not panel.canvas.pending
    panel.show()
    qtbot.waitUntil(lambda: drawn == [1], timeout=5000)  # shown: the new scene's empty plot, once
    _drawn(qtbot, panel)
    assert _plotted_points(panel) == 0
