"""The Cost tab's plot follows the window's theme: dark in high contrast, light again after."""

import numpy as np
import pytest
from matplotlib.colors import to_rgb

from views.images.plot_theme import DARK_CYCLE
from views.panels.cost_panel import CostPanel


def _luminance(color) -> float:
    """WCAG relative luminance of an sRGB colour."""
    c = np.asarray(to_rgb(color))
    linear = np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)
    return float(linear @ [0.2126, 0.7152, 0.0722])


@pytest.fixture
def themed(present):
    panel = CostPanel()
    window, presentation = present(panel)
    return window, panel, presentation


def _canvas_mean(panel) -> float:
    return float(panel.canvas.shown.rgba[..., :3].mean())


def test_the_cost_plot_turns_dark_in_high_contrast_and_light_again(qtbot, themed):
    _, panel, presentation = themed
    # The first picture: matplotlib loads meanwhile, off the GUI thread.
    qtbot.waitUntil(lambda: panel.plot_figure is not None, timeout=60_000)
    assert to_rgb(panel.plot_figure.get_facecolor()) == (1.0, 1.0, 1.0)
    assert _canvas_mean(panel) > 200
    presentation.set_high_contrast(True)
    qtbot.waitUntil(lambda: to_rgb(panel.plot_figure.get_facecolor()) == (0.0, 0.0, 0.0))
    ax = panel.plot_figure.axes[0]
    assert to_rgb(ax.get_facecolor()) == (0.0, 0.0, 0.0)
    assert to_rgb(ax.xaxis.label.get_color()) == (1.0, 1.0, 1.0)
    assert to_rgb(ax.title.get_color()) == (1.0, 1.0, 1.0)
    assert all(to_rgb(t.get_color()) == (1.0, 1.0, 1.0) for t in ax.get_yticklabels())
    assert _canvas_mean(panel) < 40  # a black picture with light text, not a white one
    # no point shown yet: no images drawn, the pane shows the window's background, black too
    assert panel.image_figure is None
    shown = panel.image_canvas.grab().toImage()
    assert shown.pixelColor(shown.width() // 2, shown.height() // 2).getRgb()[:3] == (0, 0, 0)
    presentation.set_high_contrast(False)
    qtbot.waitUntil(lambda: to_rgb(panel.plot_figure.get_facecolor()) == (1.0, 1.0, 1.0))
    assert to_rgb(panel.plot_figure.axes[0].xaxis.label.get_color()) == (0.0, 0.0, 0.0)
    assert _canvas_mean(panel) > 200


def test_the_dark_plots_curve_colours_read_on_black():
    # WCAG contrast ratio (L1 + 0.05) / (L2 + 0.05) against black: 7 is the "enhanced" level.
    assert min((_luminance(c) + 0.05) / 0.05 for c in DARK_CYCLE) >= 7
