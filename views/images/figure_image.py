"""A matplotlib figure drawn off the GUI thread into an image that the window only paints.

Laying out and drawing a figure (constrained layout, legend placement, text
extents) held the GUI thread a quarter of a second or more.  A
:class:`FigureImage` asks its drawer for a picture: the drawer runs the given
function on a thread pool of its own (one thread), which makes a new figure,
draws it with matplotlib's Agg backend and returns it with its RGBA pixels.
The widget paints those pixels scaled to its size.  A newer request supersedes
an older one: a request made while another is drawn waits, replacing any
waiting before it, and the picture of a superseded request is not shown.

A drawing function holds :data:`views.matplotlib_lock.MATPLOTLIB`
while it uses matplotlib, and returns a :class:`views.images.agg_figure.Drawn`.
"""

from __future__ import annotations

from collections.abc import Callable

from PySide6.QtCore import QPointF, QRectF, QThreadPool, Signal
from PySide6.QtGui import QImage, QPainter
from PySide6.QtWidgets import QWidget

from views.images.agg_figure import Drawn
from views.jobs import JobRun, JobSignals


class FigureImage(QWidget):
    """Paints the newest figure drawn for it, scaled to its size.

    Signals
    -------
    drawn(object) : a new picture is shown (its :class:`Drawn`).
    failed(str) : drawing the newest request raised; the message.
    clicked(float, float) : a press, in the shown figure's pixels (x right, y up, matplotlib's).
    resized() : the widget took another size (its owner asks for a picture of that size).
    """

    drawn = Signal(object)
    failed = Signal(str)
    clicked = Signal(float, float)
    resized = Signal()

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.shown: Drawn | None = None
        self._image: QImage | None = None
        self._pool = QThreadPool(self)
        self._pool.setMaxThreadCount(1)
        self._signals = JobSignals(self)
        self._signals.finished.connect(self._on_drawn)
        self._signals.failed.connect(self._on_drawn)  # the message, shown instead of a picture
        self._request = 0  # the newest request's id
        self._busy = False  # a request is being drawn
        self._waiting: Callable[[], Drawn] | None = None

    @property
    def pending(self) -> bool:
        """A request is being drawn or waits."""
        return self._busy or self._waiting is not None

    def request(self, draw: Callable[[], Drawn]) -> None:
        """Draw with ``draw`` (called on the drawer's thread), superseding every earlier request."""
        self._request += 1
        self._waiting = draw
        self._start()

    def clear(self) -> None:
        """Show no picture (the window's background shows through), superseding every request."""
        self._request += 1
        self._waiting = None
        self.shown, self._image = None, None
        self.update()

    def _start(self) -> None:
        if self._busy or self._waiting is None:
            return
        self._busy = True
        draw, self._waiting = self._waiting, None
        self._pool.start(JobRun(self._request, lambda _cancelled, _progress: draw(), self._signals))

    def _on_drawn(self, request: int, result) -> None:
        self._busy = False
        newest = request == self._request
        self._start()
        if not newest:
            return  # superseded: a newer request is drawn next
        if isinstance(result, str):
            self.failed.emit(result)
            return
        self.shown = result
        height, width, _ = result.rgba.shape
        self._image = QImage(result.rgba.data, width, height, 4 * width, QImage.Format.Format_RGBA8888).copy()
        self.update()
        self.drawn.emit(result)

    def to_figure(self, x: float, y: float) -> tuple[float, float]:
        """Widget pixels (y down) -> the shown figure's pixels (y up)."""
        height, width, _ = self.shown.rgba.shape
        return x * width / max(self.width(), 1), (self.height() - y) * height / max(self.height(), 1)

    def to_widget(self, x: float, y: float) -> tuple[float, float]:
        """The shown figure's pixels (y up) -> widget pixels (y down)."""
        height, width, _ = self.shown.rgba.shape
        return x * self.width() / width, self.height() - y * self.height() / height

    def paintEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        if self._image is None:
            return
        painter = QPainter(self)
        painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform)
        painter.drawImage(QRectF(0, 0, self.width(), self.height()), self._image)
        painter.end()

    def resizeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        super().resizeEvent(event)
        self.resized.emit()

    def mousePressEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        if self.shown is not None:
            at: QPointF = event.position()
            self.clicked.emit(*self.to_figure(at.x(), at.y()))
        super().mousePressEvent(event)

    def closeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        self._waiting = None
        super().closeEvent(event)
