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
    qtbot.waitUntil(lambda: panel.plot_figure is not None)
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
    assert to_rgb(panel.image_figure.get_facecolor()) == (0.0, 0.0, 0.0)  # no point shown yet, black too
    presentation.set_high_contrast(False)
    qtbot.waitUntil(lambda: to_rgb(panel.plot_figure.get_facecolor()) == (1.0, 1.0, 1.0))
    assert to_rgb(panel.plot_figure.axes[0].xaxis.label.get_color()) == (0.0, 0.0, 0.0)
    assert _canvas_mean(panel) > 200


def test_the_dark_plots_curve_colours_read_on_black():
    # WCAG contrast ratio (L1 + 0.05) / (L2 + 0.05) against black: 7 is the "enhanced" level.
    assert min((_luminance(c) + 0.05) / 0.05 for c in DARK_CYCLE) >= 7
