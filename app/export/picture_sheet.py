"""A sheet of pictures: titled panels in a grid, a scale under a panel, caption lines below.

What ``python -m app export`` and the window's File → Export write when one
image is not enough: the z-buffer with its scale in scene units, the four
views in one picture, a comparison, each frame of the z-buffer steps.  Images
stay pixel for pixel (a panel is never scaled); only the text is drawn, with
matplotlib's Agg canvas, so this module imports neither Qt nor VTK.  Colours
are linear RGB throughout, written as sRGB by :mod:`app.export.image_files`.
"""

from __future__ import annotations

import textwrap
from dataclasses import dataclass, replace

import numpy as np

from views.matplotlib_lock import MATPLOTLIB

#: Sheet layout, in pixels: the gap around panels, a panel title's row, a line of text.
MARGIN, TITLE_ROW, TEXT_ROW = 8, 20, 16
SHEET = (1.0, 1.0, 1.0)  # the sheet's background, linear RGB


def depth_grey(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """Distances along the viewing axis (H, W) as grey (H, W, 3): near black, the far plane and +inf white.

    The grey is linear RGB that a file shows as the sRGB level ``(d - near) / (far - near)``.
    """
    from core.srgb import srgb_to_linear

    level = np.clip((np.asarray(depth, dtype=float) - near) / (far - near), 0.0, 1.0)
    return srgb_to_linear(np.repeat(level[..., None], 3, axis=2))


def depth_ramp(near: float, far: float, width: int, rows: int) -> np.ndarray:
    """The grey scale of :func:`depth_grey` from ``near`` (left) to ``far`` (right), ``rows`` high."""
    return depth_grey(np.linspace(near, far, width)[None].repeat(rows, 0), near, far)


@dataclass
class Panel:
    """One image of a sheet, with its title and, optionally, a scale bar under it.

    Attributes
    ----------
    title : str, drawn above the image.
    image : (H, W, 3) float64, linear RGB.
    bar : (h, W, 3) float64 or None, a scale strip under the image (linear RGB).
    bar_labels : (left, right) labels under the bar's ends.
    """

    title: str
    image: np.ndarray
    bar: np.ndarray | None = None
    bar_labels: tuple[str, str] = ("", "")


def _panel_height(panel: Panel) -> int:
    h = TITLE_ROW + panel.image.shape[0]
    if panel.bar is not None:
        h += 4 + panel.bar.shape[0] + TEXT_ROW
    return h


def panel_origins(panels: list[Panel], columns: int) -> list[tuple[int, int]]:
    """The top-left pixel (column, row) of every panel's image on the sheet."""
    rows = [panels[i:i + columns] for i in range(0, len(panels), columns)]
    widths = [max(p.image.shape[1] for p in panels[c::columns]) for c in range(min(columns, len(panels)))]
    origins, top = [], MARGIN
    for row in rows:
        left = MARGIN
        for c in range(len(row)):
            origins.append((left, top + TITLE_ROW))
            left += widths[c] + MARGIN
        top += max(_panel_height(p) for p in row) + MARGIN
    return origins


def _layout(panels, columns, caption, lines):
    """Panel origins, the sheet's width and height, the row under the panels and the caption lines."""
    origins = panel_origins(panels, columns)
    right = max(x + p.image.shape[1] for (x, _), p in zip(origins, panels, strict=True)) + MARGIN
    bottom = max(y - TITLE_ROW + _panel_height(p) for (_, y), p in zip(origins, panels, strict=True))
    width = max(right, 2 * MARGIN + 40)
    chars = max(20, int((width - 2 * MARGIN) / 6.9))
    wrapped = [line for sentence in caption for line in textwrap.wrap(sentence, chars)]
    if lines is not None:
        wrapped = (wrapped + [""] * lines)[:lines]
    height = bottom + MARGIN + TEXT_ROW * len(wrapped) + (MARGIN if wrapped else 0)
    return origins, width, height, bottom, wrapped


def sheet_shape(panels: list[Panel], columns: int, lines: int) -> tuple[int, int]:
    """Height and width in pixels of the sheet :func:`compose` makes with ``lines`` caption lines."""
    _, width, height, _, _ = _layout(panels, columns, (), lines)
    return height, width


def compose(panels: list[Panel], columns: int, caption: list[str] = (),
            lines: int | None = None) -> np.ndarray:
    """Panels in a grid with their titles and scales, and caption lines under them.

    ``lines`` fixes the number of caption lines (cut or padded), so that the
    frames of an animation all have one size.

    Returns
    -------
    (H, W, 3) float64
        Linear RGB, to be written with :func:`app.export.image_files.encode_image`.
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    from core.srgb import srgb_to_linear, to_srgb8

    origins, width, height, bottom, lines = _layout(panels, columns, caption, lines)
    sheet = np.empty((height, width, 3))
    sheet[:] = SHEET
    texts = []
    for (x, y), panel in zip(origins, panels, strict=True):
        h, w = panel.image.shape[:2]
        sheet[y:y + h, x:x + w] = panel.image
        texts.append((x, y - TITLE_ROW + 3, panel.title, 10, "left"))
        if panel.bar is not None:
            top = y + h + 4
            sheet[top:top + panel.bar.shape[0], x:x + panel.bar.shape[1]] = panel.bar
            below = top + panel.bar.shape[0] + 1
            texts.append((x, below, panel.bar_labels[0], 8.5, "left"))
            texts.append((x + panel.bar.shape[1], below, panel.bar_labels[1], 8.5, "right"))
    for i, line in enumerate(lines):
        texts.append((MARGIN, bottom + MARGIN + i * TEXT_ROW, line, 9, "left"))
    with MATPLOTLIB:  # exports compose on worker threads, beside the window's plots and formulas
        fig = Figure(figsize=(width / 100, height / 100), dpi=100)
        canvas = FigureCanvasAgg(fig)
        fig.figimage(to_srgb8(sheet), 0, 0, origin="upper", resize=False)
        for x, y, text, size, align in texts:
            fig.text(x / width, 1 - y / height, text, fontsize=size, ha=align, va="top", color="#202020")
        canvas.draw()
        pixels = np.asarray(canvas.buffer_rgba())[:height, :width, :3].copy()
    return srgb_to_linear(pixels / 255.0)


def zbuffer_sheet(depth: np.ndarray, near: float, far: float) -> np.ndarray:
    """The z-buffer (distances along the viewing axis, +inf where nothing was drawn) with its scale.

    Returns
    -------
    (H, W, 3) float64, linear RGB: the grey image at full resolution, the ramp
    from ``near`` to ``far`` under it, and a sentence on what the greys mean.
    """
    seen = depth[np.isfinite(depth)]
    span = (f"the surfaces seen lie between {seen.min():.3g} and {seen.max():.3g}" if seen.size
            else "no surface is seen")
    panel = Panel("z-buffer", depth_grey(depth, near, far), depth_ramp(near, far, depth.shape[1], 10),
                  (f"near {near:g}", f"far {far:g}"))
    return compose([panel], 1, [f"Grey: distance along the viewing axis in scene units, from the near "
                                f"plane (black) to the far plane (white); {span}."])


def four_views(scene, pipeline: str = "raster", render=None) -> np.ndarray:
    """The front, side and top orthographic views and the observer's view of ``scene`` in one sheet.

    By the ``"raster"`` pipeline each view is drawn as the window's Four views
    tab draws it (:func:`core.object_order.four_views.inked_view`), under the
    tab's titles; another pipeline needs ``render(scene) -> (H, W, 3)`` linear
    RGB.  The caption names the pipeline.
    """
    from core.object_order.four_views import PANES, four_cameras, inked_view

    if render is None:
        def render(view):
            return inked_view(view, view.camera)[0]

    cameras = four_cameras(scene)
    panels = [Panel(title, render(replace(scene, camera=cameras[key]))) for key, title in PANES]
    return compose(panels, 2, [f"Pipeline: {pipeline}."])
