"""The Cost plot is laid out and drawn in a process of its own (:mod:`core.helper_process`).

A full layout of a sweep's plot (constrained layout, tried at smaller text until the curves have room;
the legends placed; the labels that would overlap thinned) is a second of matplotlib, most of it in
Python.  On a thread of the window's process it held the interpreter's lock in turns with the GUI
thread: lesson steps taken just after a sweep of every knob stalled the window 120-190 ms, while the
finished sweep's plot was laid out (``bench gui``; the steps alone stayed under 90 ms).  In a process
of its own it takes the other core, as the formulas' typesetting does
(:mod:`views.text.typesetting_process`).

The figure comes back pickled with its pixels and its lines (a click on the plot finds its point among
them); unpickling it takes the window's drawing thread a few tens of milliseconds.

The process loads no Qt: matplotlib, numpy and the theme's colours and sizes only.
"""

from __future__ import annotations

import warnings

from core import helper_process
from views.images import plot_theme
from views.images.agg_figure import Drawn, agg_figure, pixels
from views.images.cost_plot import draw_cost_plot, point_position, tidy_cost_plot
from views.matplotlib_lock import MATPLOTLIB

TEXT_SHARES = (1.0, 0.85, 0.7, 0.6, 0.5)
"""The shares of its text size the plot tries, largest first, until the curves get :data:`ROOM`."""
ROOM = (0.5, 0.3)
"""The least share of the figure's width and height the curves' axes keep (else the text shrinks)."""


def _places(figure) -> tuple[list, list]:
    """The places of ``figure``'s axes, and the entries of the legends they were laid out with.  While a
    sweep runs the plot is drawn in the places of its last full layout, for speed, but only while the
    legends are the same: a knob's curve added makes the legend under the curves taller, and drawn in
    the old places it ran off the figure's bottom."""
    return ([ax.get_position().frozen() for ax in figure.axes],
            [_entries(ax.get_legend()) for ax in figure.axes])


def _entries(legend) -> tuple:
    """A legend's title and labels (nothing for no legend)."""
    if legend is None:
        return ()
    return (legend.get_title().get_text(), *(text.get_text() for text in legend.get_texts()))


def lay_out_plot(figure, rows, indices, dark, selected, layout) -> dict:
    """Draw ``rows`` on ``figure``, laid out and tidied (:func:`tidy_cost_plot`); its lines.  When
    the text leaves the curves too little room or a legend outside the figure (a small pane, large
    text), the text is drawn smaller, down to the last of :data:`TEXT_SHARES` of matplotlib's
    ``font.size`` of the caller; a legend still outside then goes inside its panel."""
    import matplotlib

    size = matplotlib.rcParams["font.size"]
    for share in TEXT_SHARES:  # the last is drawn however little room the curves get
        with matplotlib.rc_context({"font.size": share * size}), warnings.catch_warnings():
            # Text too large for the pane is what this loop measures and makes smaller.
            warnings.filterwarnings("ignore", "constrained_layout not applied", UserWarning)
            lines, kept = _first_layout(figure, rows, indices, dark, selected, layout)
        curves = figure.axes[0].bbox
        if kept or (curves.height >= ROOM[1] * figure.bbox.height
                    and curves.width >= ROOM[0] * figure.bbox.width and _legends_inside(figure)):
            break
    with matplotlib.rc_context({"font.size": share * size}):
        figure.set_layout_engine("none")  # the tick labels thinned stay where they were measured
        tidy_cost_plot(figure)
        if not _legends_inside(figure):  # no room around the panels: the legends go inside them
            for ax in figure.axes:
                legend = ax.get_legend()
                if legend is not None and not _legends_inside_box(legend, figure):
                    ax.legend(fontsize="small", loc="best", title=legend.get_title().get_text() or None,
                              title_fontsize="small")
        figure.canvas.draw()
    return lines


def _legends_inside(figure) -> bool:
    """Whether every legend of ``figure`` lies inside it: presenting at x2 in a narrow pane, the
    z-buffer formats' legend under its axis label was laid out below the figure's bottom, unseen."""
    return all(_legends_inside_box(ax.get_legend(), figure) for ax in figure.axes if ax.get_legend())


def _legends_inside_box(legend, figure) -> bool:
    """Whether ``legend`` lies inside ``figure``."""
    box, edge = legend.get_window_extent(figure.canvas.get_renderer()), figure.bbox
    return edge.x0 - 1 <= box.x0 and box.x1 <= edge.x1 + 1 and edge.y0 - 1 <= box.y0 and box.y1 <= edge.y1 + 1


def _first_layout(figure, rows, indices, dark, selected, layout) -> tuple[dict, bool]:
    """Draw ``rows`` on ``figure`` and lay it out, the curves' legend under their axis label, or in
    the places of ``layout`` (:func:`_places`) if they were made for the same axes and legends; its
    lines, and whether those places were kept."""
    figure.set_facecolor(plot_theme.background(dark))
    figure.set_layout_engine("constrained")
    lines = draw_cost_plot(figure, rows, indices)
    kept = layout is not None and layout[1] == _places(figure)[1]
    if kept:
        figure.set_layout_engine("none")
        for ax, box in zip(figure.axes, layout[0], strict=True):
            ax.set_position(box)
    ax = figure.axes[0]
    if selected is not None:
        at, x, y = point_position(figure, selected)
        at.plot([x], [y], "x", color=plot_theme.foreground(dark), markersize=10, markeredgewidth=2)
    if not rows:
        ax.text(0.5, 0.5, "the curves fill in here,\npoint by point", transform=ax.transAxes,
                ha="center", va="center", color="gray")
    figure.canvas.draw()
    plot_theme.fit_axis_labels(figure)
    tidy_cost_plot(figure)  # the legend under the axis label: laid out again to make room for it
    figure.canvas.draw()
    return lines, kept


def drawn(width: float, height: float, dpi: float, rows, indices, dark: bool, selected, layout) -> Drawn:
    """The plot of ``rows`` (:func:`draw`), drawn in the plot's process (started on first use)."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    figure, rgba, lines, places = helper_process.call(__name__, "draw", width, height, dpi, rows, indices,
                                                      dark, selected, layout)
    FigureCanvasAgg(figure)  # a figure unpickled has a bare canvas: this one measures text, as Agg drew it
    return Drawn(figure, rgba, {"lines": lines, "layout": places})


def draw(width: float, height: float, dpi: float, rows, indices, dark: bool, selected, layout):
    """A new figure of ``width`` x ``height`` pixels at ``dpi`` with the plot of ``rows`` (each its
    setting's index of ``indices``), in the theme (``dark``), the ``selected`` row marked, laid out in
    ``layout``'s places if they fit (:func:`lay_out_plot`), drawn by the process that calls this.

    Returns the figure, its RGBA pixels, its lines (each to its points' setting indices) and, when laid
    out in full (no ``layout``), its places (:func:`_places`)."""
    import matplotlib

    with MATPLOTLIB:  # in the window's process (no helper), the fonts are shared with the formulas
        figure = agg_figure(width, height, dpi)
        style = {**plot_theme.plot_style(dark), **plot_theme.fitted_style(figure)}
        with matplotlib.rc_context(style):
            lines = lay_out_plot(figure, rows, indices, dark, selected, layout)
        return figure, pixels(figure), lines, _places(figure) if layout is None else None
