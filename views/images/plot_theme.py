"""matplotlib figures in the window's colours: light as usual, or dark in the high-contrast theme.

A widget that draws with matplotlib asks :func:`is_dark` of its own palette
(the high-contrast style sheet turns it black, see :mod:`views.presentation`)
and draws inside ``matplotlib.rc_context(plot_style(dark))``: the figure,
axes, text, ticks, grid and legend take the theme's colours, and the colour
cycle (``"C0"``, ``"C1"``, ...) becomes one that reads on black.

Its figures follow the window's text size too (presentation mode's ×1.5,
×2): made at :func:`figure_dpi` dots per inch, every text, line and marker
(all sized in points) is drawn that many times larger on the same pixels.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:  # Qt loads with the widgets that ask; the Cost plot's own process loads none
    from PySide6.QtWidgets import QWidget

DPI = 100.0
"""matplotlib's own figure resolution, dots per inch: a figure's size at text scale 1."""

DARK_BACKGROUND = "#000000"
DARK_FOREGROUND = "#ffffff"
LIGHT_BACKGROUND = "#ffffff"
LIGHT_FOREGROUND = "#000000"
DARK_CYCLE = ["#4fc3ff", "#ffb000", "#5cff7a", "#ff6b6b", "#d29bff", "#ffd400", "#ff8ad8", "#e0e0e0",
              "#c6ff3d", "#3dfff2"]
"""Colours that read on black (each at least 7:1 against it), for the figures' colour cycle."""


def is_dark(widget: QWidget) -> bool:
    """Whether ``widget`` is drawn on a dark background now."""
    from PySide6.QtGui import QPalette

    return widget.palette().color(QPalette.ColorRole.Window).lightness() < 128


def figure_dpi(widget: QWidget) -> float:
    """The resolution a figure in ``widget`` is made at, so that its text follows the widget's."""
    from views.text.text_scale import text_scale

    return DPI * text_scale(widget)


FULL_SIZE_PX = (300.0, 240.0)
"""Width and height, in pixels per unit of text scale, a figure needs for its text at full size."""
LEAST_TEXT = 0.6
"""The least share of the full text size a crowded figure is drawn with."""


def fitted_style(figure) -> dict:
    """matplotlib's base font size for ``figure``, smaller when its text would crowd it.

    A figure made for large text (:func:`figure_dpi`) in a small pane (a small
    screen at ×2) would have its title, axis labels and ticks run into each
    other; below :data:`FULL_SIZE_PX` the text shrinks with the figure, down to
    :data:`LEAST_TEXT` of its size, in steps of 5 %.
    """
    import matplotlib

    scale = figure.dpi / DPI
    room = min(figure.bbox.width / (FULL_SIZE_PX[0] * scale), figure.bbox.height / (FULL_SIZE_PX[1] * scale))
    base = matplotlib.rcParamsDefault["font.size"]
    share = round(min(1.0, max(LEAST_TEXT, room)) * 20) / 20  # in steps of 5 %: a drag redraws seldom
    return {"font.size": base * share}


def foreground(dark: bool) -> str:
    """The colour of text and marks on the theme's background."""
    return DARK_FOREGROUND if dark else LIGHT_FOREGROUND


def plot_style(dark: bool) -> dict:
    """matplotlib settings for the theme (empty for the light one: matplotlib's own)."""
    if not dark:
        return {}
    from cycler import cycler

    fg = DARK_FOREGROUND
    return {"figure.facecolor": DARK_BACKGROUND, "axes.facecolor": DARK_BACKGROUND,
            "savefig.facecolor": DARK_BACKGROUND, "axes.edgecolor": fg, "axes.labelcolor": fg,
            "axes.titlecolor": fg, "text.color": fg, "xtick.color": fg, "ytick.color": fg,
            "grid.color": "#bbbbbb", "legend.facecolor": "#1a1a1a", "legend.edgecolor": fg,
            "legend.labelcolor": fg, "axes.prop_cycle": cycler(color=DARK_CYCLE)}


def background(dark: bool) -> str:
    return DARK_BACKGROUND if dark else LIGHT_BACKGROUND


def fit_axis_labels(figure) -> None:
    """Break an axis label nearly as long as its axes' share of the figure (large text, small pane, or
    panels stacked) into two lines."""
    renderer = figure.canvas.get_renderer()
    box = figure.bbox
    for ax in figure.axes:
        across, down = _share(ax)
        for label, room in ((ax.xaxis.label, 0.9 * across * box.width),
                            (ax.yaxis.label, 0.9 * down * box.height)):
            text = label.get_text()
            extent = label.get_window_extent(renderer)
            if "\n" in text or " " not in text or max(extent.width, extent.height) <= room:
                continue
            spaces = [i for i, c in enumerate(text) if c == " "]
            cut = min(spaces, key=lambda i: abs(i - len(text) / 2))
            label.set_text(text[:cut] + "\n" + text[cut + 1:])


def _share(ax) -> tuple[float, float]:
    """The share of its figure's width and height that ``ax``'s cell of the grid takes (1, 1 alone)."""
    spec = ax.get_subplotspec()
    if spec is None:
        return 1.0, 1.0
    grid = spec.get_gridspec()
    widths = grid.get_width_ratios() or [1] * grid.ncols
    heights = grid.get_height_ratios() or [1] * grid.nrows
    return (sum(widths[i] for i in spec.colspan) / sum(widths),
            sum(heights[i] for i in spec.rowspan) / sum(heights))
