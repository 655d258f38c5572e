"""The cost plot: error against time, log-log, one curve per knob, the knee marked.

Drawn on a plain :class:`matplotlib.figure.Figure`, so the same code serves
the app (inside a Qt canvas) and the command line (saved as PNG and SVG).
The error axis is FLIP against the reference: acceleration methods, which are
exactly equal to each other, sit on one horizontal line at the error of the
default render.
"""

from __future__ import annotations

from matplotlib.figure import Figure

from core.accuracy.sweep import KNOB_NAMES, KNOBS, Row

#: Smallest error drawn: log axes cannot show 0.
ERROR_FLOOR = 1e-5
#: One fixed colour per knob, so a knob keeps its colour from plot to plot.
KNOB_COLORS = {name: f"C{i}" for i, name in enumerate(KNOB_NAMES)}


def draw_cost_plot(figure: Figure, rows: list[Row], indices: list[int] | None = None) -> dict:
    """Draw ``rows`` on ``figure`` (cleared first).

    Parameters
    ----------
    rows : the sweep's rows, knees marked.
    indices : each row's setting index (for picking), default ``0 .. len(rows) - 1``.

    Returns
    -------
    dict, matplotlib line -> list of setting indices of its points, in order.
    """
    indices = list(range(len(rows))) if indices is None else indices
    figure.clear()
    ax = figure.add_subplot(1, 1, 1)
    lines = {}
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
    ax.set_title("What accuracy costs in time\n(ringed: the knee of each knob)")  # fits a narrow pane
    ax.grid(True, which="both", alpha=0.3)
    if lines:
        ax.legend(fontsize=8, loc="best")
    return lines
