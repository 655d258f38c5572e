"""The cost plot: error against time, log-log, one curve per knob, the knee marked.

Drawn on a plain :class:`matplotlib.figure.Figure`, so the same code serves
the app (inside a Qt canvas) and the command line (saved as PNG and SVG).
The error axis is FLIP against the reference: acceleration methods, which are
exactly equal to each other, sit on one horizontal line at the error of the
default render.

The z-buffer's number formats save memory, not time, so they get a panel of
their own on the right: the share of pixels showing the wrong object
(z-fighting, against float64 at the same ratio) against the far/near ratio,
one curve per format.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from core.accuracy.sweep import KNOB_NAMES, KNOBS, Row, split_depth_label
from core.object_order.depth_formats import BYTES_PER_PIXEL, DEPTH_FORMATS

if TYPE_CHECKING:  # matplotlib loads with the first figure, not with this module
    from matplotlib.figure import Figure

#: Smallest error drawn: log axes cannot show 0.
ERROR_FLOOR = 1e-5
#: A figure at least this wide (points: its text keeps its size whatever the resolution) has the z-buffer
#: formats' panel beside the cost curves; a narrower one has it below them (side by side in a pane half a
#: window wide, the two panels' titles and legends ran into each other and the curves were squeezed flat).
SIDE_BY_SIDE_PT = 576
#: One fixed colour per knob, so a knob keeps its colour from plot to plot.
KNOB_COLORS = {name: f"C{i}" for i, name in enumerate(KNOB_NAMES)}


def draw_cost_plot(figure: Figure, rows: list[Row], indices: list[int] | None = None,
                   legend_loc: str = "best") -> dict:
    """Draw ``rows`` on ``figure`` (cleared first).

    Parameters
    ----------
    rows : the sweep's rows, knees marked.
    indices : each row's setting index (for picking), default ``0 .. len(rows) - 1``.
    legend_loc : where the curves' legend goes (matplotlib's ``loc``); ``"best"`` looks for the
        emptiest corner, which costs a sixth of a draw.

    Returns
    -------
    dict, matplotlib line -> list of setting indices of its points, in order.
    """
    indices = list(range(len(rows))) if indices is None else indices
    figure.clear()
    formats = [(i, r) for i, r in zip(indices, rows, strict=True) if r.knob == "depth-format"]
    others = [(i, r) for i, r in zip(indices, rows, strict=True) if r.knob != "depth-format"]
    if formats and not others:
        return _draw_depth_formats(figure.add_subplot(1, 1, 1), formats, wide=True)
    if formats:  # the cost curves keep two thirds of the room: beside the formats' panel, or above it
        beside = figure.get_figwidth() * 72 >= SIDE_BY_SIDE_PT
        if beside:
            grid = figure.add_gridspec(1, 2, width_ratios=(2, 1))
            ax, formats_ax = figure.add_subplot(grid[0, 0]), figure.add_subplot(grid[0, 1])
        else:
            grid = figure.add_gridspec(2, 1, height_ratios=(2, 1))
            ax, formats_ax = figure.add_subplot(grid[0, 0]), figure.add_subplot(grid[1, 0])
        lines = _draw_depth_formats(formats_ax, formats, wide=not beside)
    else:
        ax, lines = figure.add_subplot(1, 1, 1), {}
    indices, rows = [i for i, _ in others], [r for _, r in others]
    for name in KNOB_NAMES:
        mine = [(i, r) for i, r in zip(indices, rows, strict=True) if r.knob == name]
        if not mine:
            continue
        xs = [max(r.seconds, 1e-6) for _, r in mine]
        ys = [max(r.reference_flip, ERROR_FLOOR) for _, r in mine]
        knob = KNOBS[name]
        label = knob.title + (" (time only)" if knob.time_only else "")
        color = KNOB_COLORS[name]
        (line,) = ax.plot(xs, ys, "o-", color=color, markersize=5, label=label, picker=True, pickradius=6)
        lines[line] = [i for i, _ in mine]
        for k, ((_, r), x, y) in enumerate(zip(mine, xs, ys, strict=True)):
            # the methods of a time-only knob share one error: their names go below, slanted, alternating
            offset, rotation = ((0, -10 - 10 * (k % 2)), -30) if knob.time_only else ((4, 4), 0)
            ax.annotate(r.value, (x, y), textcoords="offset points", xytext=offset, fontsize=7,
                        color=color, rotation=rotation, ha="left", va="top" if knob.time_only else "bottom")
            if r.knee:
                ax.plot([x], [y], "o", markersize=13, markerfacecolor="none",
                        markeredgecolor=color, markeredgewidth=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time (s, median)")
    ax.set_ylabel("mean FLIP error against the reference")
    ax.set_title("What accuracy costs in time\n(ringed: each knob's knee)", fontsize="medium")
    ax.grid(True, which="both", alpha=0.3)
    if lines:
        ax.legend(fontsize=8, loc=legend_loc, framealpha=0.6)  # curves show through where it covers them
    return lines


def point_position(figure: Figure, row: Row):
    """Where ``row`` is drawn by :func:`draw_cost_plot`: (axes, x, y) in its data coordinates."""
    if row.knob == "depth-format":
        return figure.axes[-1], split_depth_label(row.value)[1], 100 * row.wrong_pixel_fraction
    return figure.axes[0], max(row.seconds, 1e-6), max(row.reference_flip, ERROR_FLOOR)


def _draw_depth_formats(ax, formats: list[tuple[int, Row]], wide: bool) -> dict:
    """The z-fighting panel: wrong-object share (%) against the far/near ratio, a curve per format.
    ``wide``: the panel has the figure's width (its title takes two lines, not three)."""
    lines = {}
    for k, name in enumerate(DEPTH_FORMATS):
        mine = sorted(((split_depth_label(r.value)[1], i, r) for i, r in formats
                       if split_depth_label(r.value)[0] == name), key=lambda t: t[0])
        if not mine:
            continue
        xs = [ratio for ratio, _, _ in mine]
        ys = [100 * r.wrong_pixel_fraction for _, _, r in mine]
        color = f"C{k}"
        (line,) = ax.plot(xs, ys, "o-", color=color, markersize=5, picker=True, pickradius=6,
                          label=f"{name} ({BYTES_PER_PIXEL[name]} B/pixel)")
        lines[line] = [i for _, i, _ in mine]
        for x, y, (_, _, r) in zip(xs, ys, mine, strict=True):
            if r.knee:
                ax.plot([x], [y], "o", markersize=13, markerfacecolor="none", markeredgecolor=color,
                        markeredgewidth=2)
    highest = max(100 * r.wrong_pixel_fraction for _, r in formats)
    ax.set_ylim(-0.02 * max(highest, 1.0), 1.1 * max(highest, 1.0))
    if highest == 0:
        ax.text(0.7 if wide else 0.5, 0.4,  # wide: clear of the legend
                "no format fights here:\nno two surfaces are\nclose enough in depth",
                transform=ax.transAxes, ha="center", va="center", color="gray")
    ax.set_xscale("log")
    ax.set_xlabel("far / near ratio (near plane moved)")
    ax.set_ylabel("pixels showing\nthe wrong object (%)" if wide else "pixels showing the wrong object (%)")
    title = "z-buffer formats: z-fighting against float64\n(ringed: fewest bytes within the tolerance)"
    ax.set_title(title if wide else "z-buffer formats: z-fighting\nagainst float64 (ringed: fewest bytes\n"
                 "within the tolerance)", fontsize=10)
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8, loc="upper left")
    return lines
