"""The Cost pane's sheet: the plot beside the chosen point's pictures and words, or one at a time.

The plot reads only at a size of its own.  Smaller than about 5.6 x 4 inches at its text's resolution
(:func:`views.images.plot_theme.figure_dpi`), its layout shrinks the text to half and more, and puts
legends over the curves: a 1280 x 720 screen presenting at x1.5 or x2 gave it about 3.7 x 2 inches,
with the images beside it as thumbnails.  So the plot is never drawn smaller than :func:`plot_inches`:

- where the sheet has the width for the plot and the point (:data:`POINT_INCHES`), they stand side by
  side, split as the user drags;
- where it has not, they are two pages, "Plot" and "Chosen point", and a click on a point shows its page;
- where even the plot alone does not fit, it scrolls.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, Qt, Signal
from PySide6.QtWidgets import QFrame, QScrollArea, QSplitter, QStackedWidget, QTabWidget, QWidget

from views.images import plot_theme

PLOT_WIDTH = 5.6
"""The least width of the plot, in inches at its text's resolution (see :func:`plot_inches`)."""
POINT_INCHES = 2.4
"""The least width of the chosen point's side: its image and the reference beside each other."""


def plot_inches(scale: float) -> tuple[float, float]:
    """The least size of the plot at text scale ``scale``, in inches at its text's resolution, for a
    sweep of every knob: its legends clear of the curves and its text no smaller than the window's own
    at x1 (70 % of matplotlib's 10 points at 100 dpi).  At x1 that takes 5.6 x 4 inches: narrower, the
    formats' legend has no room beside its panel and the text drops to half; shorter, to 60 %.  From
    x1.4 the text may be drawn at half its size, and 2.6 inches of height do.

    >>> plot_inches(1.0), plot_inches(2.0)
    ((5.6, 4.0), (5.6, 2.6))
    """
    return PLOT_WIDTH, 4.0 if scale < 1.4 else 2.6


class _PlotArea(QScrollArea):
    """The plot at the area's size, never below :func:`plot_inches` (it scrolls then)."""

    def __init__(self, plot: QWidget):
        super().__init__()
        self.setWidget(plot)
        self.setWidgetResizable(True)
        self.setFrameShape(QFrame.Shape.NoFrame)

    def fit(self) -> None:
        """Keep the plot's least size at the size that reads, at the text size now."""
        dpi = plot_theme.figure_dpi(self)
        width, height = plot_inches(dpi / plot_theme.DPI)
        self.widget().setMinimumSize(round(width * dpi), round(height * dpi))


class CostSheet(QStackedWidget):
    """``plot`` and ``point`` side by side where they both fit, else as two pages (see the module).

    Signals
    -------
    shown() : another page, or both sides, came into view (what was not drawn while hidden is due).
    """

    shown = Signal()

    def __init__(self, plot: QWidget, point: QWidget):
        super().__init__()
        self._area, self._point = _PlotArea(plot), point
        self._split = QSplitter(Qt.Orientation.Horizontal)
        self._split.setChildrenCollapsible(False)
        self._pages = QTabWidget()
        self._pages.setDocumentMode(True)
        self._pages.currentChanged.connect(lambda _: self.shown.emit())
        self.addWidget(self._split)
        self.addWidget(self._pages)
        self._arrange(side_by_side=True)
        self._rearrange()

    @property
    def side_by_side(self) -> bool:
        """The plot and the point stand side by side (else they are pages)."""
        return self.currentWidget() is self._split

    def showing_plot(self) -> bool:
        """The plot is in view (side by side, or on its page)."""
        return self.side_by_side or self._pages.currentWidget() is self._area

    def show_point_page(self) -> None:
        """Show the chosen point's page, when they are pages (a click on a point asks to see it)."""
        if not self.side_by_side:
            self._pages.setCurrentWidget(self._point)

    def _arrange(self, side_by_side: bool) -> None:
        if side_by_side:
            self._pages.clear()  # the pages' widgets are kept, and moved into the splitter
            for i, (widget, stretch) in enumerate(((self._area, 3), (self._point, 2))):
                self._split.insertWidget(i, widget)
                self._split.setStretchFactor(i, stretch)
                widget.show()  # a page not shown was hidden by the pages, and stays so in a splitter
            self.setCurrentWidget(self._split)
            self.shown.emit()
        else:
            self._pages.addTab(self._area, "Plot")
            self._pages.addTab(self._point, "Chosen point")
            self._pages.setTabToolTip(0, "Error against time, one curve per knob; click a point to see it")
            self._pages.setTabToolTip(1, "The clicked setting's image, the reference and their FLIP error")
            self.setCurrentWidget(self._pages)

    def _rearrange(self) -> None:
        """Side by side or pages, for the width and the text size now; the least sizes that go with it."""
        dpi = plot_theme.figure_dpi(self)
        side_by_side = self.width() >= round((PLOT_WIDTH + POINT_INCHES) * dpi)
        if side_by_side != self.side_by_side:
            self._arrange(side_by_side)
        if side_by_side:  # a drag of the splitter's handle stops where the plot would scroll sideways
            bar = self._area.verticalScrollBar().sizeHint().width()
            self._area.setMinimumWidth(round(PLOT_WIDTH * dpi) + bar)
            self._point.setMinimumWidth(round(POINT_INCHES * dpi / 2))
        else:  # pages: the sheet may be as narrow as the window makes it, and the plot scrolls
            self._area.setMinimumWidth(0)
            self._point.setMinimumWidth(0)
        self._area.fit()

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._rearrange()

    def changeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:  # the plot's inches are more pixels at larger text
            self._rearrange()
