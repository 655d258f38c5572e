"""Typeset formulas: matplotlib's mathtext drawn into a Qt label, no TeX needed.

:class:`MathView` shows one formula written in mathtext (``"$a t^2 + b t + c = 0$"``;
text outside the dollar signs is set as ordinary text).  It renders at the
label's font size times a scale, in a given colour, at the screen's pixel
density, so a formula stays sharp when presentation mode enlarges it.
mathtext has no matrices, so :class:`MatrixView` draws a bracketed grid of
numbers itself.  matplotlib loads with the first formula that is not in
:mod:`views.formula_cache` (formulas at their natural size are kept there).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
from PySide6.QtCore import QRectF, QSize, Qt
from PySide6.QtGui import QColor, QFont, QFontMetricsF, QImage, QPainter, QPen, QPixmap
from PySide6.QtWidgets import QLabel, QSizePolicy, QWidget

from views import formula_cache


def render_mathtext(text: str, size_pt: float, color: str, dpi: float, keep: bool = False) -> QImage:
    """``text`` typeset by mathtext as an image with a transparent background.

    Parameters
    ----------
    text : mathtext, math between ``$`` signs.
    size_pt : font size in points.
    color : any matplotlib colour, e.g. ``"#202020"``.
    dpi : output pixels per inch (72 makes one point one pixel).
    keep : keep the image in :mod:`views.formula_cache` for later processes
        (and look there first).

    Raises
    ------
    ValueError
        ``text`` is not valid mathtext (the message says where).
    """
    rgba = _typeset(text, float(size_pt), color, float(dpi), keep)
    h, w, _ = rgba.shape
    return QImage(rgba.data, w, h, 4 * w, QImage.Format.Format_RGBA8888).copy()


@lru_cache(maxsize=512)
def _typeset(text: str, size_pt: float, color: str, dpi: float, keep: bool) -> np.ndarray:
    """(H, W, 4) uint8 RGBA of the typeset ``text`` (cached: plain arrays, no Qt objects)."""
    if keep and (kept := formula_cache.load(text, size_pt, color, dpi)) is not None:
        kept.setflags(write=False)
        return kept
    from matplotlib.colors import to_rgb
    from matplotlib.font_manager import FontProperties

    ink = np.asarray(_parser().parse(text, dpi=dpi, prop=FontProperties(size=size_pt)).image)
    pad = max(2, int(round(0.15 * size_pt * dpi / 72.0)))  # room for glyphs at the box's edge
    alpha = np.pad(ink, pad)
    rgba = np.empty((*alpha.shape, 4), np.uint8)
    rgba[..., :3] = np.round(np.array(to_rgb(color)) * 255).astype(np.uint8)
    rgba[..., 3] = alpha
    rgba.setflags(write=False)
    if keep:
        formula_cache.store(text, size_pt, color, dpi, rgba)
    return rgba


@lru_cache(maxsize=1)
def _parser():
    from matplotlib.mathtext import MathTextParser

    return MathTextParser("agg")  # typesets straight into an 8-bit coverage image


class MathView(QLabel):
    """A label showing one mathtext formula, typeset.

    The formula is drawn at ``font size x scale`` points in the label's text
    colour unless :meth:`set_color` gave another, and smaller when the label
    is given less width than that, so a long formula never widens the window.
    An invalid formula is shown as its plain text, with the parser's complaint
    in the tooltip.
    """

    def __init__(self, formula: str = "", parent: QWidget | None = None, *, size_pt: float | None = None):
        super().__init__(parent)
        self._formula = formula
        self._size_pt = size_pt
        self._scale = 1.0
        self._color: QColor | None = None
        self._natural: QSize | None = None
        self.error: str | None = None
        self.setSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.Fixed)
        self._render()

    def formula(self) -> str:
        """The mathtext shown."""
        return self._formula

    def set_formula(self, formula: str) -> None:
        self._formula = formula
        self._render()

    def set_scale(self, scale: float) -> None:
        """Enlarge the formula by ``scale`` (presentation mode)."""
        self._scale = float(scale)
        self._render()

    def set_color(self, color) -> None:
        """Draw in ``color`` (a QColor or a colour name) instead of the text colour."""
        self._color = QColor(color)
        self._render()

    def size_pt(self) -> float:
        """The font size the formula is drawn at, in points (scale included)."""
        base = self._size_pt or QFont(self.font()).pointSizeF() or 10.0
        return base * 1.15 * self._scale

    def changeEvent(self, event) -> None:  # a new font or palette (theme, scale) re-renders
        super().changeEvent(event)
        if event.type() in (event.Type.FontChange, event.Type.PaletteChange, event.Type.StyleChange):
            self._render()

    def sizeHint(self) -> QSize:
        """The formula's full size (a narrower label shrinks it to fit)."""
        return self._natural if self._natural is not None else super().sizeHint()

    def minimumSizeHint(self) -> QSize:
        hint = self.sizeHint()
        return QSize(min(hint.width(), 40), hint.height() // 2)

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._show(fit=True)

    def _render(self) -> None:
        self.error = None
        self._natural = None
        if not self._formula:
            self.clear()
            return
        try:
            image = self._image(self.size_pt())
        except ValueError as exc:
            self.error = str(exc).strip().splitlines()[-1] if str(exc).strip() else "invalid mathtext"
            self.setToolTip(f"cannot typeset: {self.error}")
            self.setText(self._formula)
            return
        ratio = self._ratio()
        self._natural = QSize(int(image.width() / ratio + 0.999), int(image.height() / ratio + 0.999))
        self.setToolTip("")
        self.updateGeometry()
        self._show(fit=False, image=image)

    def _ratio(self) -> float:
        return max(1.0, self.devicePixelRatioF())

    def _image(self, size_pt: float) -> QImage:
        """The formula typeset at ``size_pt``; at its natural size it is kept on disk too."""
        color = self._color or self.palette().color(self.foregroundRole())
        return render_mathtext(self._formula, size_pt, color.name(), 96.0 * self._ratio(),
                               keep=size_pt == self.size_pt())

    def _show(self, fit: bool, image: QImage | None = None) -> None:
        """Show the formula at full size, or smaller when the label is narrower than that."""
        if self._natural is None:
            return
        size = self.size_pt()
        if fit and 0 < self.width() < self._natural.width():
            size = max(1.0, size * self.width() / self._natural.width() * 0.98)
            image = self._image(size)
        elif image is None:
            image = self._image(size)
        pixmap = QPixmap.fromImage(image)
        pixmap.setDevicePixelRatio(self._ratio())
        self.setPixmap(pixmap)


def _number(x: float) -> str:
    text = f"{x:.6g}"
    return "0" if text == "-0" else text


class MatrixView(QWidget):
    """A matrix of numbers between square brackets, drawn at the widget's font size times a scale."""

    def __init__(self, matrix=None, parent: QWidget | None = None):
        super().__init__(parent)
        self._cells: list[list[str]] = []
        self._scale = 1.0
        self.setSizePolicy(QSizePolicy.Policy.Fixed, QSizePolicy.Policy.Fixed)
        if matrix is not None:
            self.set_matrix(matrix)

    def set_matrix(self, matrix) -> None:
        """Show ``matrix`` (2D array-like of numbers), each to 6 significant digits.

        Entries below 1e-12 of the largest are rounding noise (a rotation's
        ``-2.2e-16``) and are shown as 0.
        """
        m = np.atleast_2d(np.asarray(matrix, dtype=float))
        m = np.where(np.abs(m) < 1e-12 * np.abs(m).max(initial=0.0), 0.0, m)  # rounding noise reads 0
        self._cells = [[_number(v) for v in row] for row in m]
        self.updateGeometry()
        self.update()

    def cells(self) -> list[list[str]]:
        """The entries as shown, row by row."""
        return [list(r) for r in self._cells]

    def set_scale(self, scale: float) -> None:
        self._scale = float(scale)
        self.updateGeometry()
        self.update()

    def _font(self) -> QFont:
        font = QFont(self.font())
        font.setPointSizeF((font.pointSizeF() or 10.0) * self._scale)
        return font

    def _geometry(self):
        metrics = QFontMetricsF(self._font())
        columns = max((len(r) for r in self._cells), default=0)
        widths = [max((metrics.horizontalAdvance(r[c]) for r in self._cells), default=0.0)
                  for c in range(columns)]
        gap, row_h, pad = metrics.horizontalAdvance("  "), metrics.height(), metrics.horizontalAdvance(" ")
        return metrics, widths, gap, row_h, pad

    def sizeHint(self) -> QSize:
        if not self._cells:
            return QSize(0, 0)
        _, widths, gap, row_h, pad = self._geometry()
        w = sum(widths) + gap * (len(widths) - 1) + 4 * pad
        return QSize(int(w + 2), int(row_h * len(self._cells) + 4))

    def paintEvent(self, event) -> None:
        if not self._cells:
            return
        metrics, widths, gap, row_h, pad = self._geometry()
        painter = QPainter(self)
        painter.setFont(self._font())
        color = self.palette().color(self.foregroundRole())
        painter.setPen(QPen(color, max(1.0, self._scale)))
        h = row_h * len(self._cells) + 2
        w = self.sizeHint().width() - 2
        tick = pad * 0.8
        for x, sign in ((1.0, 1), (w, -1)):
            painter.drawLine(int(x), 1, int(x), int(h))
            painter.drawLine(int(x), 1, int(x + sign * tick), 1)
            painter.drawLine(int(x), int(h), int(x + sign * tick), int(h))
        for i, row in enumerate(self._cells):
            x = 2 * pad
            for c, text in enumerate(row):
                rect = QRectF(x, 1 + i * row_h, widths[c], row_h)
                painter.drawText(rect, int(Qt.AlignmentFlag.AlignRight | Qt.AlignmentFlag.AlignVCenter), text)
                x += widths[c] + gap
        painter.end()
