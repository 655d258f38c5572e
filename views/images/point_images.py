"""A swept setting's picture beside the reference and the FLIP error map, drawn off the GUI thread.

Clicking a point of the Cost plot shows what that setting renders, the
reference it is compared with and the per-pixel FLIP error between them
(and, for adaptive supersampling, the samples each pixel took), side by
side on one matplotlib figure.  Drawing that figure (four images, two colour
bars, constrained layout) held the GUI thread for up to a second, so
:func:`point_images_drawing` returns a function that draws it on the
drawer's thread of a :class:`views.images.figure_image.FigureImage`; the
window only paints the picture.  Images are encoded to sRGB
(:mod:`core.srgb`) before they are shown; error and samples are shown in
false colour with their scale.
"""

from __future__ import annotations

import textwrap
from collections.abc import Callable

from core.srgb import to_srgb8
from views.images import plot_theme
from views.images.agg_figure import Drawn, agg_figure, pixels
from views.images.cost_plot import boxes_overlap
from views.matplotlib_lock import MATPLOTLIB


def _panels(point, reference) -> list:
    """``(image, title, colour map or None)`` for each image shown for ``point`` against ``reference``."""
    row = point.row
    panels = [(to_srgb8(point.color), f"{row.knob} = {row.value}\n{row.seconds * 1000:.1f} ms", None),
              (to_srgb8(reference.color), f"reference\n{reference.spp}x{reference.spp} per pixel", None),
              (point.error_map, f"FLIP against {row.compared_with}\nmean {row.flip:.4f}", "magma")]
    if point.samples is not None:
        panels.append((point.samples, f"samples per pixel\n{row.samples_per_pixel:.2f} on average",
                       "viridis"))
    return panels


def draw_point_images(figure, point, reference) -> None:
    """Draw ``point``'s image, ``reference``'s and the FLIP error map (and the samples per pixel) on
    ``figure``, two to a row or all in one (:func:`_columns`), inside the caller's
    ``matplotlib.rc_context``, and draw it.  The error map's scale is FLIP's own, 0 to 1.  Alone on its
    row (no samples), the error map takes the whole row: in half of it, beside an empty cell, it was
    drawn a third as large as the images above, under its title broken into four lines (presenting
    at x2)."""
    panels = _panels(point, reference)
    columns = _columns(figure, len(panels), panels[0][0].shape)
    rows = -(-len(panels) // columns)
    cells = figure.add_gridspec(rows, columns)  # one grid, so that the layout makes room for every title
    for k, (image, title, cmap) in enumerate(panels):
        alone = k == len(panels) - 1 and k % columns == 0 and columns > 1
        ax = figure.add_subplot(cells[k // columns, :] if alone else cells[k // columns, k % columns])
        limits = {"vmin": 0.0, "vmax": 1.0} if cmap == "magma" else {}
        shown = ax.imshow(image, cmap=cmap, interpolation="nearest", **limits)
        if cmap:  # the scale's two ends only: a bar beside a small image had room for no more
            bar = figure.colorbar(shown, ax=ax, shrink=0.8)
            bar.set_ticks([shown.norm.vmin, shown.norm.vmax])
        ax.set_title(title, fontsize=9)
        ax.set_xticks([])
        ax.set_yticks([])
    _fit_titles(figure)


def _columns(figure, count: int, shape: tuple) -> int:
    """Two images to a row, or all ``count`` in one where that draws them larger: a pane much wider than
    tall (the chosen point's own page, presenting at x2) held two rows of small images beside an empty
    half.  Each image (``shape``, rows by columns) is fitted into its cell under a two-line title."""
    title = 2 * 1.4 * 9 / 72 * figure.dpi  # two lines of the 9-point titles, in pixels
    width, height = figure.bbox.width, figure.bbox.height

    def scale(columns: int) -> float:
        rows = -(-count // columns)
        return min(width / columns / shape[1], (height / rows - title) / shape[0])

    return count if scale(count) > scale(2) else 2


def _fit_titles(figure) -> None:
    """Break each title wider than its room over its words, its lines halved, until it fits: over an
    image a fifth of a narrow figure wide ("FLIP against reference", presenting at x2), a title ran past
    the figure's edge and into its neighbour's."""
    for _ in range(3):
        figure.canvas.draw()  # measures the titles where the layout put them
        renderer, edge = figure.canvas.get_renderer(), figure.bbox
        boxes = {ax: ax.title.get_window_extent(renderer) for ax in figure.axes if ax.get_title()}
        wide = [ax for ax, box in boxes.items()
                if box.x0 < edge.x0 or box.x1 > edge.x1
                or any(other is not ax and boxes_overlap(box, boxes[other], 0.0) for other in boxes)]
        if not wide:
            return
        for ax in wide:
            halved = [textwrap.fill(line, max(6, (len(line) + 1) // 2), break_long_words=False)
                      for line in ax.get_title().splitlines()]
            ax.set_title("\n".join(halved), fontsize=9)
    figure.canvas.draw()


def point_images_drawing(point, reference, width: float, height: float, dpi: float,
                         dark: bool) -> Callable[[], Drawn]:
    """A function, for any thread, that draws :func:`draw_point_images` on a new ``width`` x ``height``
    pixel figure at ``dpi``, in the dark or light theme."""

    def draw() -> Drawn:
        import matplotlib

        with MATPLOTLIB:
            figure = agg_figure(width, height, dpi)
            figure.set_facecolor(plot_theme.background(dark))
            with matplotlib.rc_context(plot_theme.plot_style(dark)):
                draw_point_images(figure, point, reference)
            return Drawn(figure, pixels(figure))

    return draw
