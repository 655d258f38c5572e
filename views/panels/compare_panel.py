"""The Compare panel: two outputs of one scene, their difference image, one pixel read in both.

Two selectors choose any two of the four outputs (orthographic and
perspective z-buffer, ray cast, ray traced; see :mod:`core.compare`).  The
panel shows them side by side with the difference image, the absolute
difference of their linear RGB colour-mapped with its scale.  A click on a
pixel of any of the three images marks the same pixel in all of them and
reads it in both outputs: its colour, what decided it in each, in one sentence
(:mod:`core.pixel_verdict`; hover for the fragments of the z-buffer or the ray
tree of the tracer), A and B side by side, and under them the difference with
why the two differ there.
Under the images, a few sentences say what differs and why for this scene.
"""

from __future__ import annotations

from dataclasses import dataclass

from PySide6.QtCore import QEvent, Qt, QTimer, Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QComboBox,
    QFrame,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QScrollArea,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from core.compare import DIFFERENCE_UNITS, OUTPUTS, Comparison, Output, PixelReport, why_here
from core.srgb import linear_to_srgb
from views.images.color_scale import ColorScale
from views.images.image_view import DisplayImage, ImageView, zoom_together
from views.panels.image_order_panel import accel_words

PANES = ("a", "b", "difference")
DEFAULT_PAIR = ("perspective", "raytrace")
PICK_HINT = "Click a pixel in any image to read it in both outputs."
IMAGE_SHARE = 0.35
"""The share of the panel's height the images keep when the sentences under them ask for room (0.45 left
the sentences 50 px short at x2 on 1920x1080)."""


@dataclass(frozen=True, eq=False)
class ComparisonImages:
    """A comparison ready to show, its images made off the GUI thread.

    Attributes
    ----------
    comparison : the two outputs, their difference and the explanation (core).
    images : :class:`DisplayImage` per pane of :data:`PANES`, at the observer's
        image size (a preview's coarse images upscaled to it).
    bar : the difference's colour scale as a strip, lowest difference on the left.
    preview : a coarse comparison shown while the observer moves; no pixel is read in it.
    pixel : the pixel read with the render, ``(x, y)``, or ``None``.
    reports : that pixel in both outputs.
    """

    comparison: Comparison
    images: dict[str, DisplayImage]
    bar: DisplayImage
    preview: bool = False
    pixel: tuple[int, int] | None = None
    reports: tuple[PixelReport, PixelReport] | None = None


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms"


def cost(output: Output) -> str:
    """What rendering ``output`` counted and how long it took."""
    if output.raster is not None:
        stats = output.raster.stats
        drawn = stats["polygons_drawn"]
        return f"z-buffer: {drawn:,} polygon{'s' * (drawn != 1)}, {_ms(sum(stats['times'].values()))}"
    stats = output.trace.stats
    return f"{stats['rays']['total']:,} rays, {accel_words(stats['accel']['method'])}, " \
           f"{_ms(stats['times']['total'])}"


class ReadoutRow(QWidget):
    """One line of the picked pixel's readout: a swatch, a title, the linear RGB, what was found.

    Attributes
    ----------
    rgb : (r, g, b) floats shown, linear RGB, or ``None`` while nothing is read.
    """

    def __init__(self):
        super().__init__()
        self.rgb: tuple[float, float, float] | None = None
        self.swatch, self.title, self.numbers, self.found = QLabel(), QLabel(), QLabel(), QLabel()
        self.swatch.setFixedSize(14, 14)
        self.numbers.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        for label in (self.title, self.numbers, self.found):  # numbers too: a column is narrow at x2
            label.setWordWrap(True)
        grid = QGridLayout(self)
        grid.setContentsMargins(0, 0, 0, 4)
        grid.setVerticalSpacing(0)
        grid.addWidget(self.swatch, 0, 0)
        grid.addWidget(self.title, 0, 1)
        grid.addWidget(self.numbers, 1, 1)
        grid.addWidget(self.found, 2, 1)
        grid.setColumnStretch(1, 1)

    def set_row(self, title: str, rgb=None, shown=None, found: str = "", tip: str = "") -> None:
        """Show ``rgb`` (linear) on a swatch of ``shown`` (the colour on screen; ``rgb`` by default).
        Without a title the row shows only ``found`` (a hint), and nothing without either."""
        self.rgb = None if rgb is None else tuple(float(c) for c in rgb)
        self.title.setText(f"<b>{title}</b>")
        self.title.setVisible(bool(title))
        self.swatch.setVisible(bool(title))
        self.setVisible(bool(title or found))
        # The box's title says "linear RGB": with it, the numbers took two lines of a column at x2.
        self.numbers.setText("" if rgb is None else " ".join(f"{c:.3f}" for c in self.rgb))
        self.numbers.setVisible(rgb is not None)  # empty, it kept a line's height above a hint
        if rgb is None:
            self.swatch.setStyleSheet("")
        else:
            color = QColor.fromRgbF(*linear_to_srgb(self.rgb if shown is None else shown))
            self.swatch.setStyleSheet(f"background: {color.name()}; border: 1px solid #888")
        self.found.setText(found)
        self.setToolTip(tip)


def _details(report: PixelReport, names: list[str]) -> str:
    """The evidence behind ``report.found``: every fragment, or the colours of the ray tree."""
    if report.ray_tree is not None:
        return "Ray tree, colours from the last hits back to the first:\n" + "\n".join(
            report.ray_tree.explain())
    lines = [f"step {e.polygon + 1}: {names[e.object_index]} triangle {e.triangle_index} at distance "
             f"{e.distance:.4g} against stored {e.stored_distance:.4g}: "
             f"{'passed' if e.passed else 'failed'} the z-test" for e in report.events]
    return "Fragments in drawing order:\n" + "\n".join(lines) if lines else report.found


def _needed_height(widget: QWidget) -> int:
    """The height ``widget`` needs at its width (its words wrapped to it), at least its minimum."""
    height = widget.minimumSizeHint().height()
    if widget.hasHeightForWidth():
        height = max(height, widget.heightForWidth(widget.width()))
    return height


class ComparePanel(QWidget):
    """Two output selectors, the two images and their difference, the picked pixel, the explanation.

    Signals
    -------
    pair_changed() : a selector chose another output; the comparison is out of date.
    pixel_picked(int x, int y) : a pixel was clicked in one of the images (marked in all).
    """

    pair_changed = Signal()
    pixel_picked = Signal(int, int)

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.shown: ComparisonImages | None = None
        self.picked: tuple[int, int] | None = None
        self.selectors: list[QComboBox] = []
        top = QHBoxLayout()
        for side, default in zip("AB", DEFAULT_PAIR, strict=True):
            combo = QComboBox()
            for key, title in OUTPUTS.items():
                combo.addItem(title, key)
            combo.setCurrentIndex(list(OUTPUTS).index(default))
            combo.setToolTip(f"Output {side} (Alt+{side}): z-buffer (object order) with either projection, "
                             "or ray casting / ray tracing (image order) from the observer; the "
                             "difference image shows |A − B|")
            combo.currentIndexChanged.connect(self.pair_changed)
            label = QLabel(f"&{side}")
            label.setBuddy(combo)
            top.addWidget(label)
            top.addWidget(combo)
            self.selectors.append(combo)
        top.addStretch(1)

        self.views: dict[str, ImageView] = {}
        self.boxes: dict[str, QGroupBox] = {}
        self.captions: dict[str, QLabel] = {}
        grid = QGridLayout()
        grid.setContentsMargins(0, 0, 0, 0)
        for i, key in enumerate(PANES):
            box = QGroupBox()
            layout = QVBoxLayout(box)
            layout.setContentsMargins(4, 4, 4, 4)
            view = self.views[key] = ImageView(placeholder="rendering…")
            view.setToolTip("Click a pixel: it is marked in all three images and read in both outputs; "
                            "scroll to zoom all three together")
            view.pixel_clicked.connect(self.pick)
            layout.addWidget(view, 1)
            if key == "difference":
                # Its units in three lines at most: at text x2 on 1280 x 720 they took four, more than
                # the image above them, and were cut at their top and bottom.
                self.scale = ColorScale("Difference colour scale: the map's darkest colour means no "
                                        "difference, its brightest the largest one in this image",
                                        units_lines=3)
                layout.addWidget(self.scale)
            else:
                caption = self.captions[key] = QLabel()
                caption.setWordWrap(True)
                layout.addWidget(caption)
            self.boxes[key] = box
            grid.addWidget(box, 0, i)
        zoom_together(list(self.views.values()))
        self.boxes["difference"].setTitle("Difference |A − B|")
        self.readout = [ReadoutRow() for _ in range(3)]
        self.pixel_box = QGroupBox("Picked pixel")
        self.pixel_box.setToolTip("The picked pixel in both outputs; hover a line for every fragment "
                                  "(z-buffer) or the colours of the ray tree (tracer)")
        rows = QWidget()
        rows_layout = QGridLayout(rows)  # A and B side by side, why they differ under both
        rows_layout.setContentsMargins(0, 0, 0, 0)
        rows_layout.addWidget(self.readout[0], 0, 0, Qt.AlignmentFlag.AlignTop)
        rows_layout.addWidget(self.readout[1], 0, 1, Qt.AlignmentFlag.AlignTop)
        rows_layout.addWidget(self.readout[2], 1, 0, 1, 2)
        rows_layout.setColumnStretch(0, 1)
        rows_layout.setColumnStretch(1, 1)
        rows_layout.setRowStretch(2, 1)
        rows_scroll = self.rows_scroll = QScrollArea()
        rows_scroll.setWidgetResizable(True)
        rows_scroll.setFrameShape(QFrame.Shape.NoFrame)
        rows_scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        rows_scroll.setWidget(rows)
        pixel_layout = QVBoxLayout(self.pixel_box)
        pixel_layout.setContentsMargins(4, 4, 4, 4)
        pixel_layout.addWidget(rows_scroll)
        for column in range(len(PANES)):
            grid.setColumnStretch(column, 1)
        images = QWidget()
        images.setLayout(grid)

        self.explanation = QLabel()
        self.explanation.setWordWrap(True)
        self.explanation.setTextFormat(Qt.TextFormat.RichText)
        self.explanation.setAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        scroll = self.explanation_scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setWidget(self.explanation)
        scroll.setToolTip("What differs between A and B for this scene, and why")
        splitter = self.split = QSplitter(Qt.Orientation.Vertical)
        splitter.addWidget(images)
        splitter.addWidget(self.pixel_box)  # under the images, the whole width: A and B in two columns
        splitter.addWidget(scroll)
        splitter.setStretchFactor(0, 1)
        splitter.setStretchFactor(1, 1)
        splitter.setSizes([260, 200, 90])  # the images keep the larger share; drag to read more
        splitter.setChildrenCollapsible(False)
        self._room_as_dragged = False  # the user dragged a divider: their sizes stand
        splitter.splitterMoved.connect(self._leave_room_as_dragged)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(6, 6, 6, 6)
        layout.addLayout(top)
        layout.addWidget(splitter, 1)
        self._clear_readout(PICK_HINT)

    def _leave_room_as_dragged(self) -> None:
        self._room_as_dragged = True

    def _make_room_for_explanation(self) -> None:
        """Give the sentences under the images the height they need to read whole, taken from the
        images down to :data:`IMAGE_SHARE` of the height (or what their captions need, if more),
        then from the picked pixel down to what its rows need (at text x2 they scrolled, three lines
        shown of eight); they give it back when the images' captions need it.  Not after a drag."""
        scroll = self.explanation_scroll
        width = scroll.width() - 2 * scroll.frameWidth()
        if self._room_as_dragged or width <= 0 or not self.explanation.text():
            return
        need = self.explanation.heightForWidth(width) + 2 * scroll.frameWidth()
        images, pixel, words = sizes = self.split.sizes()
        total, least = sum(sizes), self._readout_height()
        # For the images: their share, or more where their captions need it (at 1280 x 720 and text
        # x1.5 the difference's units were cut to a line and a half).
        kept = max(round(IMAGE_SHARE * total), _needed_height(self.split.widget(0)))
        words = max(0, min(max(words, need), total - kept - least))
        pixel = max(least, min(pixel, total - words - kept))  # a resize shares out to images and pixel
        if [total - words - pixel, pixel, words] != sizes:
            self.split.setSizes([total - words - pixel, pixel, words])

    def _readout_height(self) -> int:
        """The height the picked pixel's box needs to show its rows whole at its width (at text x2 on
        1280 x 720 it kept the hint's two lines, and a pick's numbers showed a line and a half)."""
        view = self.rows_scroll.viewport()
        rows = self.rows_scroll.widget().heightForWidth(view.width())
        return max(_needed_height(self.pixel_box), self.pixel_box.height() - view.height() + rows)

    def resizeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        super().resizeEvent(event)
        self._make_room_for_explanation()

    def changeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:  # the sentences grow with the text
            QTimer.singleShot(0, self, self._make_room_for_explanation)

    def pair(self) -> tuple[str, str]:
        """The keys (of :data:`core.compare.OUTPUTS`) of outputs A and B."""
        return tuple(combo.currentData() for combo in self.selectors)

    def pick(self, x: int, y: int) -> None:
        """Mark pixel ``(x, y)`` in every image and ask for it to be read (``pixel_picked``)."""
        self.picked = (x, y)
        for view in self.views.values():
            view.set_picked(self.picked)
        self._clear_readout(f"reading pixel ({x}, {y})…")
        self.pixel_picked.emit(x, y)

    def show_comparison(self, shown: ComparisonImages) -> None:
        """Show a finished (or preview) comparison; a picked pixel outside the new image is let go."""
        comparison = shown.comparison
        self.shown = shown
        for key, output in (("a", comparison.a), ("b", comparison.b)):
            self.boxes[key].setTitle(f"{'A' if key == 'a' else 'B'}: {output.title}")
            self.captions[key].setText(cost(output) + (" (preview)" if shown.preview else ""))
        for key, view in self.views.items():
            view.set_image(shown.images[key])
        diff = comparison.difference
        self.scale.set_scale(shown.bar, "0", f"{diff.scale:.3g}", DIFFERENCE_UNITS)
        self.explanation.setText("<b>Why they differ</b><br>"
                                 + "<br>".join(f"• {s}" for s in comparison.explanation))
        self._make_room_for_explanation()
        h, w = shown.images["a"].rgb.shape[:2]
        if self.picked is not None and not (self.picked[0] < w and self.picked[1] < h):
            self.picked = None
            for view in self.views.values():
                view.set_picked(None)
            self._clear_readout(PICK_HINT)
        elif shown.preview and self.picked is not None:
            self._clear_readout("the pixel is read again when the observer stops")
        elif shown.reports is not None:
            self.show_pixel((shown.pixel, shown.reports))

    def show_pixel(self, read: tuple[tuple[int, int], tuple[PixelReport, PixelReport]]) -> None:
        """Show pixel ``read[0]`` as both outputs report it (``read[1]``) and their difference."""
        pixel, reports = read
        if pixel != self.picked or self.shown is None or self.shown.preview:
            return  # an older pick, or a comparison no longer on screen
        comparison = self.shown.comparison
        names = [o.name for o in comparison.a.scene.objects]
        x, y = pixel
        self.pixel_box.setTitle(f"Picked pixel ({x}, {y}), linear RGB")
        for row, (side, output, report) in enumerate(zip("AB", (comparison.a, comparison.b), reports,
                                                         strict=True)):
            self.readout[row].set_row(f"{side}: {output.title}", report.color, found=report.found,
                                      tip=_details(report, names))
        diff = comparison.difference
        magnitude = float(diff.magnitude[y, x])
        found = (f"largest channel difference {magnitude:.3f} (linear RGB units). "
                 + why_here(comparison.a, comparison.b, *reports) if magnitude > 0
                 else "no difference: both outputs give this pixel the same colour")
        self.readout[2].set_row("|A − B|", diff.delta[y, x], diff.colored[y, x], found,
                                "The swatch shows the difference image's colour at this pixel")
        QTimer.singleShot(0, self, self._make_room_for_explanation)  # once the rows have their lines

    def _clear_readout(self, message: str) -> None:
        self.pixel_box.setTitle("Picked pixel")
        for k, row in enumerate(self.readout):  # the message alone: at 1280 x 720 and text x1.5 the
            row.set_row("", found=message if k == 0 else "")  # empty A, B and |A − B| rows cut it
