"""Typeset formulas: matplotlib's mathtext drawn into a Qt label, no TeX needed.

:class:`MathView` shows one formula written in mathtext (``"$a t^2 + b t + c = 0$"``;
text outside the dollar signs is set as ordinary text).  It renders at the
label's font size times a scale, in a given colour, at the screen's pixel
density, so a formula stays sharp when presentation mode enlarges it.
mathtext has no matrices, so :class:`MatrixView` draws a bracketed grid of
numbers itself.  Formulas are typeset in a process of their own
(:mod:`views.text.typesetting_process`), started with the first formula that is not in
:mod:`views.text.formula_cache` (formulas at their natural size are kept there), or
earlier when the window asks (:func:`load_typesetting_soon`).

Reading a formula from that cache, or waiting for its typesetting, holds the thread that does
it: a lesson step's formulas held the GUI thread up to a second while other
threads were busy (each file read gives up Python's lock, and getting it back
waits for them).  A ``MathView(..., later=True)`` therefore typesets on a thread
of its own (:func:`_typesetter`) and shows its formula once that is done; until
then it shows nothing, never another formula.
"""

from __future__ import annotations

import atexit
import contextlib
import threading
import weakref
from functools import lru_cache, partial

import numpy as np
from PySide6.QtCore import QRectF, QRunnable, QSize, Qt, QThreadPool, QTimer
from PySide6.QtGui import QColor, QFont, QFontMetricsF, QImage, QPainter, QPalette, QPen, QPixmap
from PySide6.QtWidgets import QLabel, QSizePolicy, QWidget

from core.shown_numbers import shown_number
from views.gui_thread import messenger, tell
from views.text import formula_cache, typesetting_process


def render_mathtext(text: str, size_pt: float, color: str, dpi: float, keep: bool = False) -> QImage:
    """``text`` typeset by mathtext as an image with a transparent background.

    Parameters
    ----------
    text : mathtext, math between ``$`` signs.
    size_pt : font size in points.
    color : any matplotlib colour, e.g. ``"#202020"``.
    dpi : output pixels per inch (72 makes one point one pixel).
    keep : keep the image in :mod:`views.text.formula_cache` for later processes
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
    rgba = typesetting_process.typeset(text, size_pt, color, dpi)
    rgba.setflags(write=False)
    if keep:
        formula_cache.store(text, size_pt, color, dpi, rgba)
    return rgba


MIN_SHRINK = 0.75
"""A formula is never drawn smaller than this share of its size: beyond that it wraps into lines
(at its spaces) and, if a part is still too wide, its pane scrolls sideways."""
SHRINKS = (1.0, 0.9, 0.8, MIN_SHRINK)
"""The shares of its size a formula of several parts is tried at, largest first, when it must wrap."""
BREAKS = (r"\qquad", r"\quad", r"\ \ ", r"\ ")
"""The spaces of mathtext a formula may wrap at (between its parts, never inside braces)."""


def _command_at(text: str, i: int, name: str) -> bool:
    r"""Whether the command ``name`` (``r"\quad"``) starts at ``text[i]`` (and not a longer one)."""
    after = text[i + len(name):i + len(name) + 1]
    return text.startswith(name, i) and not (name[-1].isalpha() and after.isalpha())


def split_formula(text: str) -> list[tuple[str, str]]:
    r"""A formula's parts, each with the space that follows it: ``[(part, space), ..., (last, "")]``.

    Only a formula that is one stretch of math between ``$`` signs splits,
    and only at the spaces of :data:`BREAKS` outside braces and
    ``\left … \right``; otherwise it is one part.  :func:`join_parts` of
    all the parts gives the formula back (up to spaces before a break).

    >>> split_formula(r"$a = 1,\quad b = \frac{2}{3}$")
    [('a = 1,', '\\quad '), ('b = \\frac{2}{3}', '')]
    """
    return list(_split(text))


@lru_cache(maxsize=1024)
def _split(text: str) -> tuple[tuple[str, str], ...]:  # asked at every typesetting and size of a formula
    body = text.strip()
    if len(body) < 2 or body[0] != "$" or body[-1] != "$" or "$" in body[1:-1].replace(r"\$", ""):
        return ((text, ""),)
    body = body[1:-1]
    parts, start, depth, i = [], 0, 0, 0
    while i < len(body):
        if body[i] == "\\" and i + 1 < len(body) and body[i + 1] in "{}$\\":
            i += 2
            continue
        if body[i] == "{" or _command_at(body, i, r"\left"):
            depth += 1
        elif body[i] == "}" or _command_at(body, i, r"\right"):
            depth -= 1
        elif depth == 0:
            space = next((b for b in BREAKS if _command_at(body, i, b)), None)
            if space is not None:
                end = i + len(space)
                while end < len(body) and body[end] == " ":
                    end += 1
                if body[start:i].strip():
                    parts.append((body[start:i].strip(), body[i:end]))
                start = i = end
                continue
        i += 1
    if not parts:
        return ((text, ""),)
    parts.append((body[start:].strip(), ""))
    return tuple(parts)


def join_parts(parts) -> str:
    """The mathtext of consecutive parts of :func:`split_formula` on one line."""
    if len(parts) == 1 and parts[0][0].startswith("$"):
        return parts[0][0]
    return "$" + "".join(p + space for p, space in parts[:-1]) + parts[-1][0] + "$"


loader: threading.Thread | None = None
"""The thread :func:`load_typesetting_soon` started, once it has."""


def load_typesetting_soon() -> threading.Thread:
    """Start the typesetting process and have it load matplotlib's typesetting, from a thread of its
    own (once; returns that thread).

    The first formula not in the cache otherwise waits for the process to start and for mathtext and
    its fonts to load and its grammar to be built: about 0.4 s the first time a pixel is picked.
    """
    global loader
    if loader is None:
        loader = threading.Thread(target=_warm_up, name="load typesetting", daemon=True)
        loader.start()
    return loader


def _warm_up() -> None:
    typesetting_process.typeset("$x^2$", 10.0, "#000000", 72.0)


@lru_cache(maxsize=1)
def _typesetter() -> QThreadPool:
    """The one thread that typesets (or reads from the cache) the formulas of ``later`` views, in the
    order they were asked for."""
    pool = QThreadPool()
    pool.setMaxThreadCount(1)
    # Registered after PySide's own clean-up, so it runs before it: that deletes the Qt objects a
    # formula being typeset reports to, and a process that ended mid-typesetting printed a traceback
    # for each formula still queued (or crashed).
    atexit.register(stop_typesetting, EXIT_WAIT_MS)
    return pool


EXIT_WAIT_MS = 10_000
"""How long a process that ends waits for the formula being typeset (typesetting one takes at most a
second or so; the rest of its sizes and parts are dropped)."""
_stopping = threading.Event()


def stop_typesetting(wait_ms: int) -> bool:
    """Drop the formulas still waiting to be typeset, stop the one being typeset after its current text,
    and wait up to ``wait_ms`` for it (False if it took longer).  Called as the application quits and
    as the process ends: a formula typeset while the interpreter shut down crashed it."""
    if _typesetter.cache_info().currsize == 0:  # nothing was ever typeset off the GUI thread
        return True
    _stopping.set()
    _typesetter().clear()
    if not _typesetter().waitForDone(wait_ms):
        return False
    _stopping.clear()  # typesetting asked for from now on goes ahead (a test's next window)
    return True


class _Wanted:
    """The newest typesetting one view asked for: all the typesetter's thread reads of the view, as plain
    Python (a Qt object of a view deleted meanwhile, touched from that thread, crashed the program)."""

    def __init__(self, view: MathView):
        self.newest = 0
        self.view = weakref.ref(view)

    def drop(self) -> None:
        """The view is gone: nothing it asked for is typeset."""
        self.newest = -1


class _TypesetJob(QRunnable):
    """Typesets ``(text, size_pt)`` pairs in ``color`` at ``dpi`` into :func:`_typeset`'s memory (and the
    disk cache), then says so; a text that is not mathtext is left to the view to report."""

    def __init__(self, request: int, texts: list[tuple[str, float]], color: str, dpi: float,
                 wanted: _Wanted):
        super().__init__()
        self.request, self.texts, self.color, self.dpi, self.wanted = request, texts, color, dpi, wanted
        messenger()  # made on the GUI thread

    def run(self):
        for text, size_pt in self.texts:
            if self.wanted.newest != self.request or _stopping.is_set():  # a newer formula (the next lesson
                return  # step, a new pixel) waits behind it, or the view is gone, or the program ends
            with contextlib.suppress(ValueError):
                _typeset(text, size_pt, self.color, self.dpi, True)
        if not _stopping.is_set():
            tell(self.wanted.view, partial(MathView._typeset_done, request=self.request))


def _ink(widget: QWidget) -> QColor:
    """``widget``'s text colour in the palette's active group: a formula typeset while its pane was
    disabled (covered by an exercise) kept the disabled grey once the pane came back."""
    return widget.palette().color(QPalette.ColorGroup.Active, widget.foregroundRole())


class MathView(QLabel):
    """A label showing one mathtext formula, typeset.

    The formula is drawn at ``font size x scale`` points in the label's text
    colour unless :meth:`set_color` gave another.  Given less width than
    that, it is drawn a little smaller, down to :data:`MIN_SHRINK` of its
    size, and wrapped into lines at its spaces (``\\quad``, ``\\ ``), the
    later lines indented, so that it stays readable from the back of a room;
    a part still too wide makes a scroll area around it scroll sideways.
    An invalid formula is shown as its plain text, with the parser's
    complaint in the tooltip.

    With ``later``, it is typeset off the GUI thread (:func:`_typesetter`) whenever
    its formula, size or colour changes: :attr:`pending` meanwhile, showing nothing
    (a new formula) or the formula at its previous size or colour.  A hidden one
    (a tab, dock or page not shown) waits until it is shown: a new text size asked
    the typesetter for some 150 formulas of hidden panes after every lesson, and the
    GUI thread then laid each one out again as it came back.
    """

    def __init__(self, formula: str = "", parent: QWidget | None = None, *, size_pt: float | None = None,
                 scale: float = 1.0, later: bool = False):
        super().__init__(parent)
        self._later = later
        self._request = 0  # the newest typesetting asked of the typesetter's thread
        self._done = 0  # the newest typesetting it finished
        self._asked: tuple | None = None  # what it was asked for: formula, size, colour, resolution
        self._asking = False  # asking it soon, once this turn's changes are in
        self._when_shown = False  # changed while hidden: typeset once shown
        self._wanted: _Wanted | None = None
        self.pending = False
        """Typesetting on the typesetter's thread (``later`` views only)."""
        self._formula = formula
        self._size_pt = size_pt
        self._scale = float(scale)
        self._color: QColor | None = None
        self._natural: QSize | None = None
        self._parts: list[tuple[str, str]] = [(formula, "")]
        self.error: str | None = None
        # Wrapped into lines the formula grows taller than its one-line size hint: a fixed
        # height would clip it, so the height is at least the hint and as tall as the lines.
        policy = QSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.Minimum)
        policy.setHeightForWidth(True)
        self.setSizePolicy(policy)
        self.ensurePolished()  # the window's style sheet (its text size) before the first typesetting
        self._render()

    def formula(self) -> str:
        """The mathtext shown."""
        return self._formula

    def set_formula(self, formula: str) -> None:
        self._formula = formula
        if self._later:  # the former formula is not shown while this one is typeset
            self._natural, self._asked = None, None
            self.clear()
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
        """The font size the formula is drawn at when it fits, in points (scale included)."""
        base = self._size_pt or QFont(self.font()).pointSizeF() or 10.0
        return base * 1.15 * self._scale

    def shown_lines(self) -> tuple[list[str], float]:
        """The lines the formula is drawn in at the label's width, and their size in points (no lines
        before it is typeset)."""
        if self._natural is None:
            return [], self.size_pt()
        return self._layout(self.width())

    def changeEvent(self, event) -> None:  # a new font or palette (theme, scale) re-renders
        super().changeEvent(event)
        if event.type() in (event.Type.FontChange, event.Type.PaletteChange, event.Type.StyleChange):
            self._render()

    def sizeHint(self) -> QSize:
        """The formula's full size on one line (a narrower label breaks or shrinks it)."""
        return self._natural if self._natural is not None else super().sizeHint()

    def minimumSizeHint(self) -> QSize:
        if self._natural is None:
            return super().minimumSizeHint()
        if self.pending:  # measured at the new size once typeset, not on the GUI thread now
            return QSize(0, self.height())
        least = self.size_pt() * MIN_SHRINK
        indent = self._indent(least) if len(self._parts) > 1 else 0.0
        widest = max(self._width(join_parts([part]), least) for part in self._parts) + indent
        return QSize(int(min(widest, self._natural.width()) + 0.999), self._natural.height())

    def hasHeightForWidth(self) -> bool:
        return self._natural is not None

    def heightForWidth(self, width: int) -> int:
        if self._natural is None:
            return super().heightForWidth(width)
        if self.pending:  # the height shown until the new size is typeset
            return self.height()
        lines, size = self._layout(width)
        return int(sum(self._image_of(line, size).height() for line in lines) / self._ratio() + 0.999)

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._show()

    def _out_of_sight(self) -> bool:
        """Whether the view is in a pane not shown: a hidden tab, dock or page, or a window not shown (a
        view just made in a shown pane is not: Qt shows it at the next turn of the event loop)."""
        widget = self
        while not widget.isWindow():
            if widget.isHidden() and widget.testAttribute(Qt.WidgetAttribute.WA_WState_ExplicitShowHide):
                return True
            widget = widget.parentWidget()
        return not widget.isVisible()

    def showEvent(self, event) -> None:
        super().showEvent(event)
        if self._when_shown:
            self._when_shown = False
            self._render()

    def _render(self) -> None:
        if not self._later or not self._formula:
            self._render_now()
            return
        if self._asking:  # a restyle sends a font, a palette and a style change: asked once
            return
        if self._out_of_sight():
            self._when_shown = True
            return
        self.pending = True
        self._asking = True
        QTimer.singleShot(0, self, self._ask)

    def _ask(self) -> None:
        """Ask the typesetter's thread for what the formula now needs, unless that was asked already."""
        self._asking = False
        if self._asked == self._needs():
            self.pending = self._done != self._request  # what it shows, or will show, is up to date
            return
        self._asked = self._needs()
        _, size, color, dpi = self._asked
        # What _render_now needs first, the sizes the formula and its parts may be shrunk to, and the
        # lines _wrap may try (runs of two parts or more): typeset on the GUI thread, a lesson
        # step's wrapped formulas held it a quarter of a second.
        texts = [(self._formula, size)]
        with contextlib.suppress(ValueError):
            split = split_formula(self._formula)
            parts = [join_parts([part]) for part in split]
            texts += [(part, size) for part in parts if part != self._formula]
            texts += [(text, size * s) for s in SHRINKS[1:] for text in [self._formula, *parts]]
            n = len(split)
            runs = [join_parts(split[i:j]) for i in range(n) for j in range(i + 2, n + 1) if j - i < n]
            texts += [(run, size * s) for s in SHRINKS for run in runs]
        if self._wanted is None:
            self._wanted = _Wanted(self)
            # A plain callable holding it, not its method: PySide ties a method's connection to its object
            # and cleans up on the thread that frees it, here the typesetter's, when a deleted view's last
            # job lets go of it last (334 times in tests/app + tests/views).
            self.destroyed.connect(partial(_Wanted.drop, self._wanted))
        self._request += 1
        self._wanted.newest = self._request
        self.pending = True
        _typesetter().start(_TypesetJob(self._request, texts, color, dpi, self._wanted))

    def _typeset_done(self, request: int) -> None:
        self._done = request
        # Else a newer typesetting is on its way, or is about to be asked for (a new text size since):
        # shown now, the formula at that size would be typeset here, on the GUI thread.
        if request == self._request and self._asked == self._needs():
            self.pending = False
            self._render_now()

    def _needs(self) -> tuple:
        """What the formula needs typeset now: formula, size, colour, resolution."""
        return self._formula, self.size_pt(), self._color_name(), self._dpi()

    def _render_now(self) -> None:
        self.error = None
        self._natural = None
        if not self._formula:
            self.clear()
            return
        try:
            image = self._image_of(self._formula, self.size_pt())
        except ValueError as exc:
            self.error = str(exc).strip().splitlines()[-1] if str(exc).strip() else "invalid mathtext"
            self.setToolTip(f"cannot typeset: {self.error}")
            self.setText(self._formula)
            return
        ratio = self._ratio()
        self._natural = QSize(int(image.width() / ratio + 0.999), int(image.height() / ratio + 0.999))
        try:
            self._parts = split_formula(self._formula)
            for part in self._parts:
                self._image_of(join_parts([part]), self.size_pt())
        except ValueError:  # a part that is not mathtext on its own: the formula stays whole
            self._parts = [(self._formula, "")]
        self.setToolTip("")
        self.updateGeometry()
        self._show()

    def _ratio(self) -> float:
        return max(1.0, self.devicePixelRatioF())

    def _color_name(self) -> str:
        return (self._color or _ink(self)).name()

    def _dpi(self) -> float:
        return 96.0 * self._ratio()

    def _image_of(self, text: str, size_pt: float) -> QImage:
        """``text`` typeset at ``size_pt``; kept on disk too at the few sizes that do not depend on the
        label's width (those of :data:`SHRINKS`), which are all a window needs to open."""
        natural = self.size_pt()
        return render_mathtext(text, size_pt, self._color_name(), self._dpi(),
                               keep=any(size_pt == natural * s for s in SHRINKS))

    def _width(self, text: str, size_pt: float) -> float:
        return self._image_of(text, size_pt).width() / self._ratio()

    def _indent(self, size_pt: float) -> float:
        """How far lines after the first are indented (two ems), in pixels."""
        return 2.0 * size_pt * 96.0 / 72.0

    def _layout(self, width: int) -> tuple[list[str], float]:
        """The lines and their size for a label ``width`` pixels wide."""
        size = self.size_pt()
        full = self._natural.width()
        if width <= 0 or full <= width:
            return [self._formula], size
        least = size * MIN_SHRINK
        if len(self._parts) == 1:
            return [self._formula], max(least, size * width / full * 0.98)
        for shrink in SHRINKS:  # as large as possible, then the fewest lines
            lines = self._wrap(width, size * shrink)
            if all(self._width(line, size * shrink) + (k > 0) * self._indent(size * shrink) <= width
                   for k, line in enumerate(lines)):
                return lines, size * shrink
        return lines, least

    def _wrap(self, width: int, size: float) -> list[str]:
        """The parts filled into lines of at most ``width`` pixels at ``size`` (a part too wide alone
        gets a line of its own)."""
        lines, line = [], [self._parts[0]]
        for part in self._parts[1:]:
            indent = self._indent(size) if lines else 0.0
            if self._width(join_parts(line + [part]), size) + indent <= width:
                line.append(part)
            else:
                lines.append(join_parts(line))
                line = [part]
        return lines + [join_parts(line)]

    def _show(self) -> None:
        """Draw the formula in the lines :meth:`_layout` chose for the label's width (the former
        picture stays while the new size is typeset)."""
        if self._natural is None or self.pending:
            return
        # Until a layout gives the label its width, one line (not wrapped to fit Qt's default size).
        lines, size = self._layout(self.width() if self.testAttribute(Qt.WidgetAttribute.WA_Resized) else 0)
        images = [self._image_of(line, size) for line in lines]
        if len(images) == 1:
            image = images[0]
        else:
            indent = int(self._indent(size) * self._ratio())
            image = QImage(max(im.width() + (k > 0) * indent for k, im in enumerate(images)),
                           sum(im.height() for im in images), QImage.Format.Format_ARGB32_Premultiplied)
            image.fill(Qt.GlobalColor.transparent)
            painter = QPainter(image)
            y = 0
            for k, im in enumerate(images):
                painter.drawImage(indent if k else 0, y, im)
                y += im.height()
            painter.end()
        pixmap = QPixmap.fromImage(image)
        pixmap.setDevicePixelRatio(self._ratio())
        self.setPixmap(pixmap)
        if len(images) > 1 and self.height() * self._ratio() < image.height():
            self.updateGeometry()  # taller now: ask the layout for the room


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
        self._cells = [[shown_number(v) for v in row] for row in m]
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
        painter.setPen(QPen(_ink(self), max(1.0, self._scale)))
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
