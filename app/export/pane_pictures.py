"""The pictures a tab offers File → Export: every image pane in it, at the image's full resolution.

A tab offers, unless it says otherwise, what its widget shows (each pane
named by its accessible name, else by the title of the group box around it):

- each image pane (:class:`views.images.image_view.ImageView`), pixel for pixel as
  it is painted (one file pixel per image pixel, however large the pane);
- a z-buffer pane (:class:`views.images.depth_view.DepthView`) with its grey scale
  in scene units under it;
- a grid of panes (:class:`views.images.image_grid.ImageGrid`, such as the four
  views) also as one picture, each pane under its title.

A tab with other pictures to offer defines ``pictures() -> list[PanePicture]``
(see :mod:`app.window.tabs`).  A pane not rendered yet, or showing a preview or a
render under way, or hidden in its tab, has nothing to export; its picture
says why.
"""

from __future__ import annotations

from collections.abc import Callable
from dataclasses import dataclass

import numpy as np
from PySide6.QtGui import QImage
from PySide6.QtWidgets import QGroupBox, QWidget

from app.export.picture_sheet import Panel, compose, zbuffer_sheet
from core.srgb import srgb_to_linear
from views.images.depth_view import DepthView
from views.images.image_grid import ImageGrid
from views.images.image_view import ImageView
from views.panels.pane_cover import covered_with


@dataclass(frozen=True)
class PanePicture:
    """One picture File → Export can write.

    Attributes
    ----------
    tab : the title of the tab it belongs to.
    pane : what it shows, e.g. ``"z-buffer with its scale"``.
    make : returns the picture, (H, W, 3) float64 linear RGB; ``None`` when
        there is nothing to export yet.
    why_not : why ``make`` is ``None``, for the disabled menu entry's tooltip.
    """

    tab: str
    pane: str
    make: Callable[[], np.ndarray] | None
    why_not: str = ""


def tab_pictures(tab) -> list[PanePicture]:
    """The pictures ``tab`` offers: its own ``pictures()``, else those of its widget's panes; none of
    them while the tab is covered (what it shows is not of the current scene: a render refused or
    failed), each then with the cover's reason."""
    offered = getattr(tab, "pictures", None)
    pictures = offered() if offered is not None else widget_pictures(tab.title, tab.widget)
    covered = covered_with(tab.widget)
    if covered is None:
        return pictures
    why = covered.split("\n")[0]
    return [PanePicture(p.tab, p.pane, None, why) for p in pictures]


def shown_rgb(view: ImageView) -> np.ndarray:
    """The image ``view`` paints, pixel for pixel, as (H, W, 3) linear RGB."""
    image = view.qimage.convertToFormat(QImage.Format.Format_RGB888)
    h, w = image.height(), image.width()
    rows = np.frombuffer(image.constBits(), np.uint8).reshape(h, image.bytesPerLine())
    return srgb_to_linear(rows[:, :3 * w].reshape(h, w, 3) / 255.0)


def _why_not(view: ImageView, top: QWidget) -> str:
    if not view.isVisibleTo(top):
        return "Not part of what the tab shows now"
    if view.qimage is None:
        return "Nothing shown yet: show the tab and let it render"
    if view.note:
        return f"The pane shows a “{view.note}” image: wait for the full render"
    return ""


def _pane_title(view: QWidget, top: QWidget) -> str:
    """The title of the group box around ``view`` inside ``top`` ("" when there is none)."""
    widget = view.parentWidget()
    while widget is not None and widget is not top:
        if isinstance(widget, QGroupBox) and widget.title():
            return widget.title()
        widget = widget.parentWidget()
    return ""


def _picture(tab: str, pane: str, views: list[ImageView], top: QWidget, make) -> PanePicture:
    why = next((why for why in (_why_not(view, top) for view in views) if why), "")
    return PanePicture(tab, pane, None if why else make, why)


def _panes(widget: QWidget):
    """The image panes, z-buffer panes and grids inside ``widget``, in the order they were laid out."""
    for child in widget.children():
        if isinstance(child, (ImageView, DepthView)):
            yield child
        elif isinstance(child, QWidget):
            yield from _panes(child)
            if isinstance(child, ImageGrid):
                yield child


def widget_pictures(tab: str, widget: QWidget) -> list[PanePicture]:
    """The pictures of the panes in ``widget``, the page of the tab titled ``tab``."""
    pictures = []
    for pane in [*_panes(widget), *([widget] if isinstance(widget, ImageGrid) else [])]:
        if isinstance(pane, ImageGrid):
            views = list(pane.views.values())

            def sheet(grid=pane):
                panels = [Panel(grid.titles[key], shown_rgb(v)) for key, v in grid.views.items()]
                return compose(panels, grid.layout().columnCount())

            pictures.append(_picture(tab, f"All {len(views)} panes as one picture", views, widget, sheet))
        elif isinstance(pane, DepthView):
            title = _pane_title(pane, widget) or "z-buffer"
            pictures.append(_picture(tab, f"{title} with its scale", [pane.image], widget,
                                     lambda d=pane: zbuffer_sheet(d.depth, d.near, d.far)))
        else:
            name = pane.accessibleName() or _pane_title(pane, widget) or "Image"
            pictures.append(_picture(tab, name, [pane], widget, lambda v=pane: shown_rgb(v)))
    return pictures
