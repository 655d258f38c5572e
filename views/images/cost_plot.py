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
#: The formats' legend title when no format shows a wrong pixel (every curve on 0).
NO_FIGHTS_NOTE = "no format fights here: no two surfaces\nare close enough in depth"
#: One fixed colour per knob, so a knob keeps its colour from plot to plot.
KNOB_COLORS = {name: f"C{i}" for i, name in enumerate(KNOB_NAMES)}


def draw_cost_plot(figure: Figure, rows: list[Row], indices: list[int] | None = None) -> dict:
    """Draw ``rows`` on ``figure`` (cleared first).  The curves' legend goes below their axes; after a
    layout, :func:`tidy_cost_plot` puts it below the axis label and thins the labels that would overlap.

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
        label = knob.title.split(" (")[0].split(",")[0] + (" (time only)" if knob.time_only else "")
        color = KNOB_COLORS[name]
        (line,) = ax.plot(xs, ys, "o-", color=color, markersize=5, label=label, picker=True, pickradius=6)
        lines[line] = [i for i, _ in mine]
        for k, ((_, r), x, y) in enumerate(zip(mine, xs, ys, strict=True)):
            # the methods of a time-only knob share one error: their names go below, slanted, alternating
            offset, rotation = ((0, -10 - 10 * (k % 2)), -30) if knob.time_only else ((4, 4), 0)
            ax.annotate(r.value, (x, y), textcoords="offset points", xytext=offset, fontsize="x-small",
                        color=color, rotation=rotation, ha="left", va="top" if knob.time_only else "bottom")
            if r.knee:
                ax.plot([x], [y], "o", markersize=13, markerfacecolor="none",
                        markeredgecolor=color, markeredgewidth=2)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("render time (s, median)")
    ax.set_ylabel("mean FLIP error\nagainst the reference")  # one line was longer than a short figure
    title = ax.set_title("What accuracy costs in time\n(ringed: each knob's knee)", fontsize="medium")
    _title_from_left(title)
    ax.grid(True, which="both", alpha=0.3)
    if any(line.axes is ax for line in lines):
        ax.legend(fontsize="small", loc="upper center", bbox_to_anchor=(0.5, 0.0), ncols=2)
    return lines


def _title_from_left(title) -> None:
    """Start ``title`` at its axes' left edge: a plot wider than its pane (at text x2 on 1280 x 720)
    scrolls, and a title centred on the whole figure was cut at the view's right edge."""
    title.set_x(0.0)
    title.set_horizontalalignment("left")


def tidy_cost_plot(figure: Figure) -> None:
    """Make a drawn cost plot readable (the figure has been drawn once, so its texts have their extents):
    the curves' legend below the x axis label, in as many columns as the figure's width holds, and the
    z-buffer formats' legend beside or below their panel, never over it; tick labels and point labels
    that would overlap one kept before them hidden.  Draw the figure again after."""
    renderer = figure.canvas.get_renderer()
    ax = figure.axes[0]
    if ax.get_legend() is not None and ax.get_xlabel().startswith("render time"):
        _below_the_axis_label(figure, ax, renderer)
    formats = figure.axes[-1]
    if formats.get_legend() is not None and formats.get_xlabel().startswith("far / near"):
        # Inside the panel, the legend covered the curves of a short one: beside the panel when the
        # figure has the width for it, else under its axis label.
        across = formats.bbox.width >= 0.5 * figure.bbox.width
        if not (across and _in_columns(formats, renderer, 0.4 * figure.bbox.width, loc="center left",
                                       bbox_to_anchor=(1.02, 0.5))):
            _below_the_axis_label(figure, formats, renderer)
    for each in figure.axes:
        for axis in (each.xaxis, each.yaxis):
            _thin(shown_tick_labels(axis), renderer)
    legends = [each.get_legend().get_window_extent(renderer) for each in figure.axes if each.get_legend()]
    from matplotlib.text import Annotation

    _thin([t for t in ax.texts if isinstance(t, Annotation) and t.get_visible()], renderer, avoid=legends,
          inside=figure.bbox)


def shown_tick_labels(axis) -> list:
    """The tick labels ``axis`` shows: visible, with text, at a tick within its view."""
    low, high = sorted(axis.get_view_interval())
    return [label for ticks in (axis.get_major_ticks(), axis.get_minor_ticks())
            for tick, label in ((t, t.label1) for t in ticks)
            if label.get_visible() and label.get_text().strip() and low <= tick.get_loc() <= high]


def boxes_overlap(a, b, pad: float = 1.0) -> bool:
    """Whether two boxes (display pixels) come within ``pad`` of each other."""
    return a.x0 < b.x1 + pad and b.x0 < a.x1 + pad and a.y0 < b.y1 + pad and b.y0 < a.y1 + pad


def _thin(texts: list, renderer, avoid: list | None = None, inside=None) -> None:
    """Hide each text that overlaps one kept before it, or a box of ``avoid``, or leaves ``inside``."""
    kept = list(avoid or [])
    for text in texts:
        box = text.get_window_extent(renderer)
        outside = inside is not None and not (inside.x0 <= box.x0 and box.x1 <= inside.x1
                                               and inside.y0 <= box.y0 and box.y1 <= inside.y1)
        if outside or any(boxes_overlap(box, other) for other in kept):
            text.set_visible(False)
        else:
            kept.append(box)


def _below_the_axis_label(figure: Figure, ax, renderer) -> None:
    """Anchor ``ax``'s legend under its x axis label (constrained layout then makes room for it), in as
    many columns (at most 3) as the width of ``ax``'s cell of the figure holds."""
    from matplotlib.transforms import offset_copy

    label = ax.xaxis.label.get_window_extent(renderer)
    below = ax.get_window_extent(renderer).y0 - label.y0 + 4  # pixels from the axes' bottom
    cell = ax.get_subplotspec().get_position(figure).width * figure.bbox.width
    _in_columns(ax, renderer, 0.98 * cell, loc="upper center", bbox_to_anchor=(0.5, 0.0),
                bbox_transform=offset_copy(ax.transAxes, figure, 0, -below, units="dots"))


def _in_columns(ax, renderer, room: float, **where) -> bool:
    """Lay ``ax``'s legend out again at ``where``, in the most columns (at most 3) that fit ``room``
    pixels wide; whether one did (else it has one column)."""
    handles, labels = ax.get_legend_handles_labels()
    title = ax.get_legend().get_title().get_text() or None  # laid out again, it says the same
    for ncols in (3, 2, 1):
        legend = ax.legend(handles, labels, fontsize="small", ncols=ncols, title=title,
                           title_fontsize="small", **where)
        if legend.get_window_extent(renderer).width <= room:
            return True
    return False


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
    ax.set_xscale("log")
    ax.set_xlabel("far / near ratio (near plane moved)")
    ax.set_ylabel("pixels showing\nthe wrong object (%)" if wide else "pixels showing the wrong object (%)")
    title = "z-buffer formats: z-fighting against float64\n(ringed: fewest bytes within the tolerance)"
    _title_from_left(ax.set_title(title if wide else "z-buffer formats:\nz-fighting against float64\n"
                                  "(ringed: fewest bytes\nwithin the tolerance)", fontsize="medium"))
    ax.grid(True, which="both", alpha=0.3)
    # With no fights every curve lies on 0; the legend says so in its title, so the note can never
    # sit on the legend's entries (drawn apart, it covered them in a short panel).
    note = NO_FIGHTS_NOTE if wide else NO_FIGHTS_NOTE.replace(" no two surfaces", "\nno two surfaces")
    ax.legend(fontsize="small", loc="upper left", title=note if highest == 0 else None,
              title_fontsize="small")
    return lines
