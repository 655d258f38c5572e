"""A matplotlib figure on an Agg canvas, drawn into pixels: what a figure's drawing gives the window.

No Qt here: a figure is drawn on a thread of the window's process
(:mod:`views.images.figure_image`) or in a process of its own that loads no Qt
(:mod:`views.images.cost_plot_process`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


@dataclass
class Drawn:
    """A figure drawn off the GUI thread.

    Attributes
    ----------
    figure : the matplotlib figure (on an Agg canvas); read it, do not draw it again.
    rgba : its pixels, (height, width, 4) uint8, row 0 at the top.
    extra : whatever the drawing function returned besides (e.g. its lines, for picking).
    """

    figure: object
    rgba: np.ndarray
    extra: object = None


def agg_figure(width_px: float, height_px: float, dpi: float):
    """A new figure of ``width_px`` x ``height_px`` pixels at ``dpi``, on an Agg canvas, laid out by
    constrained layout."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    figure = Figure(figsize=(max(width_px, 1) / dpi, max(height_px, 1) / dpi), dpi=dpi, layout="constrained")
    FigureCanvasAgg(figure)
    return figure


def pixels(figure) -> np.ndarray:
    """The figure's last drawn pixels, a copy, (height, width, 4) uint8."""
    return np.array(figure.canvas.buffer_rgba(), copy=True)
