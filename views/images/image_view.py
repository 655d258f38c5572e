"""The image pane: what the observer sees, pixel by pixel.

Pixels are drawn as crisp squares (nearest neighbour) so a student can see
that the image is a grid of samples, scaled to fit the pane with its aspect
ratio kept.  Clicking a pixel reports which one it was; a picked pixel and a
set of highlighted pixels (for example one polygon's fragments) can be
outlined on top, and a polygon's edges drawn; the outline leaves every pixel's
colour true.  When each pixel is shown large (a small image), the pixel grid and
every pixel's centre are drawn too: a fragment is made where a triangle covers a centre.
A picture that picks pixels is reached with Tab too: focused, it wears a frame,
the arrow keys move the picked pixel and Enter chooses it, as a click does
(:data:`PICTURE_KEYS`).  Any picture zooms in and out with the mouse wheel, around the
pointer, and a zoomed one moves with the right or middle button held (:mod:`views.images.zoom`);
pictures of the same pixels shown side by side zoom together (:func:`zoom_together`).  Zoomed onto
what it singles out (:meth:`ImageView.frame_singled_out`: a polygon's highlighted pixels, else the
picked pixel), a small triangle fills the picture for a lecture hall.

Renderers produce *linear* RGB; :func:`core.srgb.to_srgb8` encodes it for
the screen.  That conversion, and the QImage, can be made off the GUI thread
with :func:`display_image` (QImage, unlike QPixmap, may be built in any
thread), so a worker hands over an image ready to paint.  An image marked as
a preview (coarse, shown while the observer moves) carries a visible note.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from PySide6.QtCore import QEvent, QPointF, QRectF, Qt, Signal
from PySide6.QtGui import QColor, QImage, QPainter, QPalette, QPen
from PySide6.QtWidgets import QSizePolicy, QWidget

from core.srgb import to_srgb8
from views.images import zoom

GRID_CELL_PX = 10
"""On-screen size (px) of one pixel from which its square's border and its centre are drawn: the
rasterization lesson's 16 x 12 pixels get 11-12 px each presenting on a 1280 x 720 projector."""
EDGE_COLOR = "#00e5ff"
"""A polygon's edges drawn over the image (cyan: apart from the magenta fragment outline)."""
FOCUS_MARGIN = 3
"""Room (px) kept around a pickable image for its focus frame, which so never covers a pixel."""
NOTE_COLOR = "#ffd34d"
"""The colour of the words a picture writes over itself ("preview", its zoom)."""
PICKED_PAD_PX = 12.0
"""The picked pixel's frame is drawn this far around it at most (zoomed in, a pixel is larger)."""
SHIFT_STEP = 10
"""Pixels a Shift+arrow moves the pick by (an arrow alone: one)."""
PICKED_CONTEXT = 4
"""Framed on a picked pixel (:meth:`ImageView.frame_singled_out`), this many pixels around it show too."""
ARROWS = {Qt.Key.Key_Left: (-1, 0), Qt.Key.Key_Right: (1, 0), Qt.Key.Key_Up: (0, -1), Qt.Key.Key_Down: (0, 1)}
ZOOM_KEYS = {Qt.Key.Key_Plus: zoom.STEP, Qt.Key.Key_Equal: zoom.STEP, Qt.Key.Key_Minus: 1 / zoom.STEP,
             Qt.Key.Key_0: 0.0}
"""The keys that zoom a focused picture, and by what factor (0: whole again)."""
PICTURE_KEYS = [
    ("Arrow keys", "Move the picked pixel of a focused picture (Tab or click to focus it)"),
    ("Shift+arrows", f"Move it by {SHIFT_STEP} pixels"),
    ("Enter", "Answer a click-a-pixel exercise with the pixel picked in a focused picture"),
    ("+ / -", "Zoom a focused picture in or out, around its picked pixel"),
    ("0", "Show a focused picture whole again"),
]
"""(keys, description) of the keys of a focused picture, for Help → Keys."""
PICTURE_GESTURES = [
    ("Click a pixel", "trace it (image order) or list its fragments (object order)"),
    ("Scroll", "zoom in or out around the pointer (pictures of the same pixels side by side zoom together)"),
    ("Ctrl+scroll", "the same over an exercise's or a hard case's pictures (the wheel scrolls their panel)"),
    ("Drag with the right or middle button", "move a zoomed picture"),
]
"""(gesture, what it does) with the mouse over a picture, for Help → Keys."""


@dataclass(frozen=True)
class DisplayImage:
    """An image ready to paint.

    Attributes
    ----------
    rgb : (H, W, 3) float array, the values the image stands for (linear RGB,
        or display levels such as a depth grey scale); row 0 at the top.
    qimage : the 8-bit picture painted on screen.
    note : shown over the image when not empty (``"preview"`` for a coarse image).
    """

    rgb: np.ndarray
    qimage: QImage
    note: str = ""


def to_qimage(rgb: np.ndarray, linear: bool = True) -> QImage:
    """An (H, W, 3) float image in [0, 1] as a QImage that owns its pixels.

    ``linear`` values are encoded to sRGB (:func:`core.srgb.to_srgb8`); others
    (already display levels, e.g. a grey scale) are only rounded to 8 bits.
    """
    rgb = np.asarray(rgb)
    levels = to_srgb8(rgb) if linear else np.round(np.clip(rgb, 0.0, 1.0) * 255.0).astype(np.uint8)
    data = np.ascontiguousarray(levels)
    h, w, _ = data.shape
    return QImage(data.data, w, h, 3 * w, QImage.Format.Format_RGB888).copy()


def display_image(rgb: np.ndarray, note: str = "", linear: bool = True) -> DisplayImage:
    """Prepare ``rgb`` for :meth:`ImageView.set_image`; safe to call in a worker thread."""
    return DisplayImage(rgb, to_qimage(rgb, linear), note)


def _runs(edges: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Runs of True along each row of ``edges``: (row, first column, one past the last)."""
    padded = np.pad(edges, ((0, 0), (1, 1)))
    starts = np.nonzero(padded[:, 1:-1] & ~padded[:, :-2])
    ends = np.nonzero(padded[:, 1:-1] & ~padded[:, 2:])  # row-major: each end follows its start
    return starts[0], starts[1], ends[1] + 1


def mask_outline(mask: np.ndarray) -> np.ndarray:
    """The boundary of a set of pixels as segments between pixel corners.

    Parameters
    ----------
    mask : (H, W) bool, the pixels (for example one polygon's fragments).

    Returns
    -------
    (S, 4) float64, segments ``(x0, y0, x1, y1)`` in pixel-corner coordinates (x to
    the right, y down), horizontal or vertical, covering every side a masked pixel
    shares with an unmasked one or with the image border exactly once; sides in a
    straight row are joined into one segment, so a large polygon's outline draws
    quickly.  Drawn on top, they mark the set while every pixel inside keeps its
    true colour.
    """
    padded = np.pad(np.asarray(mask, bool), 1)
    horizontal = padded[1:, 1:-1] != padded[:-1, 1:-1]  # (H+1, W): edge above row y
    vertical = padded[1:-1, 1:] != padded[1:-1, :-1]  # (H, W+1): edge left of column x
    hy, hx0, hx1 = _runs(horizontal)
    vx, vy0, vy1 = _runs(vertical.T)
    return np.concatenate([np.column_stack([hx0, hy, hx1, hy]),
                           np.column_stack([vx, vy0, vx, vy1])]).astype(float)


class ImageView(QWidget):
    """Shows an RGB image scaled to fit, with its pixels kept square and sharp.

    A ``pickable`` view (the default) picks a pixel by a click, or from the keyboard:
    it takes the focus by Tab or a click, and an arrow key moves the picked pixel by
    one (Shift+arrow by :data:`SHIFT_STEP`, kept inside the image; with none picked,
    the first arrow picks the centre pixel).  Other keys, Enter too, go on to the
    view's parents (the Exercises panel checks its answer on Enter).  A view that is
    only looked at (``pickable=False``) takes neither clicks nor the focus.

    Signals
    -------
    pixel_clicked(int x, int y) : column and row of the pixel picked by a click or an arrow key.
    pixel_chosen(int x, int y) : the pixel given as an answer: clicked, or picked by the user (a
        click, the arrow keys) when Enter was pressed; the arrow keys walk through pixels on the way
        and only show them, and a pixel the owner picked (:meth:`set_picked`) is not the user's.
    """

    pixel_clicked = Signal(int, int)
    pixel_chosen = Signal(int, int)
    zoomed = Signal(float, object)  # the user zoomed or moved the picture: zoom, focus (zoom.py)

    def __init__(self, parent: QWidget | None = None, placeholder: str = "rendering…",
                 pickable: bool = True):
        super().__init__(parent)
        self.pickable = pickable
        self._margin = FOCUS_MARGIN if pickable else 0
        if pickable:
            self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)
            self.setAccessibleDescription(f"Click a pixel to pick it; arrow keys move the picked pixel, "
                                          f"Shift+arrows by {SHIFT_STEP}; + and - zoom, 0 shows it whole")
        self.setToolTip("Scroll to zoom in or out; drag with the right or middle button to move a zoomed "
                        "picture; Z zooms the pictures onto the highlight")
        self.zoom = 1.0  # 1: the picture whole (views.images.zoom)
        self.zoom_modifier = Qt.KeyboardModifier.NoModifier  # what the wheel needs held to zoom
        self.focus: tuple[float, float] | None = None  # the picture's point at the pane's centre
        self._panning: tuple[QPointF, tuple[float, float]] | None = None  # (press position, focus then)
        self._image: QImage | None = None
        self._highlight: np.ndarray | None = None
        self._highlight_shape: tuple[int, int] | None = None
        self._highlight_color = QColor("#ff2bd6")
        self.rgb: np.ndarray | None = None
        self.note = ""
        self.picked: tuple[int, int] | None = None
        self._users = False  # the picked pixel was picked by the user (a click, an arrow), not set
        self.edges: np.ndarray | None = None  # (N, 2) polygon corners in pixel coordinates, or None
        self.edges_coming = False  # those of a polygon not drawn yet (dashed)
        self._placeholder = placeholder
        self.setMinimumSize(120, 90)
        self.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Expanding)

    def set_image(self, image: np.ndarray | DisplayImage) -> None:
        """Show ``image``: a :class:`DisplayImage`, or an (H, W, 3) linear RGB array in [0, 1]."""
        if not isinstance(image, DisplayImage):
            image = display_image(image)
        if self._image is None or self._image.size() != image.qimage.size():
            self.zoom, self.focus = 1.0, None  # other pixels: shown whole
        self.rgb, self._image, self.note = image.rgb, image.qimage, image.note
        self.update()

    def set_zoom(self, zoom_: float, focus: tuple[float, float] | None) -> None:
        """Show the picture at ``zoom_`` around ``focus`` (kept where the picture covers the pane)."""
        if self._image is not None:
            focus = zoom.kept_focus(self._room_size(), self._picture_size(), zoom_, focus)
        if (zoom_, focus) != (self.zoom, self.focus):  # (a lesson step sets every picture whole)
            self.zoom, self.focus = zoom_, focus
            self.update()

    def _zoom_by(self, factor: float, anchor: QPointF) -> None:
        """The user zooms by ``factor`` (0: whole again) about the widget position ``anchor``."""
        room = self._room()
        if factor == 0:
            new, focus = 1.0, None
        else:
            new, focus = zoom.zoomed_about(self._room_size(), self._picture_size(), self.zoom, self.focus,
                                           factor, (anchor - room.topLeft()).toTuple())
        if (new, focus) != (self.zoom, self.focus):
            self.set_zoom(new, focus)
            self.zoomed.emit(self.zoom, self.focus)

    def zoom_with_ctrl(self) -> None:
        """Zoom with Ctrl+wheel, leaving the plain wheel to a panel around the picture that scrolls (an
        exercise's, the hard cases')."""
        self.zoom_modifier = Qt.KeyboardModifier.ControlModifier
        self.setToolTip("Ctrl+scroll to zoom in or out; drag with the right or middle button to move a "
                        "zoomed picture; Z zooms the pictures onto the highlight")

    def _picture_size(self) -> tuple[float, float]:
        return float(self._image.width()), float(self._image.height())

    def _room_size(self) -> tuple[float, float]:
        room = self._room()
        return max(1.0, room.width()), max(1.0, room.height())

    def _room(self) -> QRectF:
        """The part of the widget pixels are drawn in (inside the focus frame's margin)."""
        return QRectF(self.rect()).adjusted(self._margin, self._margin, -self._margin, -self._margin)

    @property
    def qimage(self) -> QImage | None:
        """The 8-bit picture shown, at the image's own resolution (``None`` before the first)."""
        return self._image

    def set_highlight(self, mask: np.ndarray | None, color: str = "#ff2bd6",
                      outline: np.ndarray | None = None) -> None:
        """Outline the pixels where ``mask`` (H, W) is true, keeping their colours; ``None`` clears it.

        ``outline``: ``mask_outline(mask)`` when the caller has it already (a worker made it).
        """
        self._highlight = None if mask is None else mask_outline(mask) if outline is None else outline
        self._highlight_shape = None if mask is None else mask.shape
        self._highlight_color = QColor(color)
        self.update()

    def singled_out(self) -> tuple[float, float, float, float] | None:
        """The box around what the picture singles out, ``(x0, y0, x1, y1)`` in picture pixels
        (corners): its highlighted pixels, else its picked pixel and :data:`PICKED_CONTEXT` pixels
        around; None where it singles out nothing."""
        if self._image is None:
            return None
        if (self._highlight is not None and len(self._highlight)
                and self._highlight_shape == (self._image.height(), self._image.width())):
            xs, ys = self._highlight[:, [0, 2]], self._highlight[:, [1, 3]]
            return float(xs.min()), float(ys.min()), float(xs.max()), float(ys.max())
        if self.picked is not None:
            x, y = self.picked
            return x - PICKED_CONTEXT, y - PICKED_CONTEXT, x + 1 + PICKED_CONTEXT, y + 1 + PICKED_CONTEXT
        return None

    def frame_singled_out(self) -> bool:
        """Zoom onto what the picture singles out (:meth:`singled_out`, :func:`zoom.framing`);
        whether it singles out anything."""
        box = self.singled_out()
        if box is not None:
            self.set_zoom(*zoom.framing(self._room_size(), self._picture_size(), box))
        return box is not None

    def set_edges(self, corners: np.ndarray | None, coming: bool = False) -> None:
        """A polygon's edges to draw over the grid (when :meth:`grid_shown`): ``corners`` (N, 2) in pixel
        coordinates (x right, y down, pixel ``(i, j)``'s centre at ``(i + 0.5, j + 0.5)``); None clears.
        ``coming``: the polygon is not drawn yet, its edges dashed."""
        self.edges = None if corners is None else np.asarray(corners, dtype=float)
        self.edges_coming = coming and corners is not None
        self.update()

    def grid_shown(self) -> bool:
        """Each pixel is drawn large enough (:data:`GRID_CELL_PX`) to show its square and centre."""
        rect = self.image_rect()
        return self._image is not None and rect.width() / self._image.width() >= GRID_CELL_PX

    def set_picked(self, pixel: tuple[int, int] | None) -> None:
        """Outline one pixel ``(x, y)``; ``None`` clears it.  Picked so, by the view's owner (a lesson
        step's pixel, another picture's), it is not the user's: Enter does not give it as an answer
        (the user's own pick, echoed back by the owner, stays the user's)."""
        if pixel != self.picked:
            self.picked, self._users = pixel, False
        self.update()

    def _pick(self, pixel: tuple[int, int]) -> None:
        """The user picks ``pixel`` (a click or an arrow key)."""
        self.set_picked(pixel)
        self._users = True
        self.pixel_clicked.emit(*pixel)

    def image_rect(self) -> QRectF:
        """Where the whole image is drawn in the widget (aspect kept; zoomed in, beyond the widget)."""
        if self._image is None:
            return QRectF()
        room = self._room()
        x, y, w, h = zoom.shown_rect(self._room_size(), self._picture_size(), self.zoom, self.focus)
        return QRectF(room.x() + x, room.y() + y, w, h)

    def pixel_at(self, pos: QPointF) -> tuple[int, int] | None:
        """The image pixel ``(x, y)`` under a widget position, or ``None`` where no pixel is shown."""
        rect = self.image_rect()
        if self._image is None or not rect.intersected(self._room()).contains(pos):
            return None
        x = int((pos.x() - rect.x()) / rect.width() * self._image.width())
        y = int((pos.y() - rect.y()) / rect.height() * self._image.height())
        return min(x, self._image.width() - 1), min(y, self._image.height() - 1)

    def widget_pos(self, x: int, y: int) -> QPointF:
        """Widget position of the centre of pixel ``(x, y)``."""
        rect = self.image_rect()
        return QPointF(rect.x() + (x + 0.5) * rect.width() / self._image.width(),
                       rect.y() + (y + 0.5) * rect.height() / self._image.height())

    def mousePressEvent(self, event):
        pixel = self.pixel_at(event.position())
        if self.pickable and pixel is not None and event.button() == Qt.MouseButton.LeftButton:
            self._pick(pixel)
            self.pixel_chosen.emit(*pixel)
        elif self._image is not None and event.button() in (Qt.MouseButton.RightButton,
                                                               Qt.MouseButton.MiddleButton):
            self._panning = event.position(), zoom.kept_focus(self._room_size(),
                                                              self._picture_size(), self.zoom, self.focus)
            self.setCursor(Qt.CursorShape.ClosedHandCursor)

    def mouseMoveEvent(self, event):
        if self._panning is None or self._image is None:
            return super().mouseMoveEvent(event)
        start, (fx, fy) = self._panning
        scale = self.image_rect().width() / self._image.width()
        moved = (event.position() - start) / scale
        focus = zoom.kept_focus(self._room_size(), self._picture_size(), self.zoom,
                                (fx - moved.x(), fy - moved.y()))
        if focus != self.focus:
            self.set_zoom(self.zoom, focus)
            self.zoomed.emit(self.zoom, self.focus)

    def mouseReleaseEvent(self, event):
        if self._panning is not None and not event.buttons() & (Qt.MouseButton.RightButton
                                                                  | Qt.MouseButton.MiddleButton):
            self._panning = None
            self.unsetCursor()
        super().mouseReleaseEvent(event)

    def wheelEvent(self, event):
        notches = event.angleDelta().y() / 120
        held = event.modifiers() & ~Qt.KeyboardModifier.KeypadModifier
        if (self._image is None or not notches or held != self.zoom_modifier
                or (notches < 0 and self.zoom <= 1)):  # nothing to do: a panel around it may scroll
            return super().wheelEvent(event)
        self._zoom_by(zoom.STEP ** notches, event.position())
        event.accept()

    def _zoom_key(self, event) -> float | None:
        """The factor a key asks of this focused view's zoom (:data:`ZOOM_KEYS`), or None."""
        ignored = Qt.KeyboardModifier.KeypadModifier | Qt.KeyboardModifier.ShiftModifier  # + takes Shift
        modifiers = event.modifiers() & ~ignored
        if self._image is None or modifiers != Qt.KeyboardModifier.NoModifier:
            return None
        return ZOOM_KEYS.get(event.key())

    def _arrow_step(self, event) -> tuple[int, int] | None:
        """The move ``event`` (a key) asks of the picked pixel, or None when it is not an arrow
        or Shift+arrow for this view (no image shown, or not pickable)."""
        if not self.pickable or self._image is None or event.key() not in ARROWS:
            return None
        modifiers = event.modifiers() & ~Qt.KeyboardModifier.KeypadModifier
        if modifiers not in (Qt.KeyboardModifier.NoModifier, Qt.KeyboardModifier.ShiftModifier):
            return None
        n = SHIFT_STEP if modifiers == Qt.KeyboardModifier.ShiftModifier else 1
        dx, dy = ARROWS[event.key()]
        return dx * n, dy * n

    def event(self, event):
        # The arrow keys are also the window's shortcuts (they orbit the observer): Qt asks the
        # focused widget first whether it wants the key; a focused picture keeps them.
        if event.type() == QEvent.Type.ShortcutOverride and (self._arrow_step(event) is not None
                                                             or self._zoom_key(event) is not None):
            event.accept()
            return True
        return super().event(event)

    def keyPressEvent(self, event):
        factor = self._zoom_key(event)
        if factor is not None:  # about the picked pixel, or the pane's centre
            anchor = self.widget_pos(*self.picked) if self.picked is not None else self._room().center()
            self._zoom_by(factor, anchor if self._room().contains(anchor) else self._room().center())
            event.accept()
            return
        step = self._arrow_step(event)
        if step is None:
            if (self.pickable and self._image is not None and self.picked is not None and self._users
                    and event.key() in (Qt.Key.Key_Return, Qt.Key.Key_Enter)):
                self.pixel_chosen.emit(*self.picked)
            event.ignore()  # on to the parents: Enter checks an exercise's answer
            return
        w, h = self._image.width(), self._image.height()
        if self.picked is None:
            pixel = (w // 2, h // 2)  # the first arrow picks the centre
        else:
            x, y = self.picked[0] + step[0], self.picked[1] + step[1]
            pixel = (min(max(x, 0), w - 1), min(max(y, 0), h - 1))  # kept inside the image
        event.accept()
        if pixel != self.picked:  # at the border, a press further out does nothing
            self._pick(pixel)
            if not self._room().contains(self.widget_pos(*pixel)):  # zoomed in: the view follows it
                self.set_zoom(self.zoom, (pixel[0] + 0.5, pixel[1] + 0.5))
                self.zoomed.emit(self.zoom, self.focus)

    def _paint_grid(self, painter: QPainter, rect: QRectF) -> None:
        """The pixel squares' borders and a dot at each pixel's centre, where fragments are sampled
        (of the pixels in view: zoomed into a large picture, the others are many)."""
        w, h = self._image.width(), self._image.height()
        sx, sy = rect.width() / w, rect.height() / h
        room = self._room()
        i0, i1 = max(0, int((room.left() - rect.x()) / sx)), min(w, int((room.right() - rect.x()) / sx) + 1)
        j0, j1 = max(0, int((room.top() - rect.y()) / sy)), min(h, int((room.bottom() - rect.y()) / sy) + 1)
        painter.setPen(QPen(QColor(0, 0, 0, 90), 1))
        for i in range(i0, i1 + 1):
            painter.drawLine(QPointF(rect.x() + i * sx, rect.y()), QPointF(rect.x() + i * sx, rect.bottom()))
        for j in range(j0, j1 + 1):
            painter.drawLine(QPointF(rect.x(), rect.y() + j * sy), QPointF(rect.right(), rect.y() + j * sy))
        radius = max(1.5, min(sx, sy) / 12)
        painter.setPen(QPen(QColor(0, 0, 0, 200), 1))
        painter.setBrush(QColor("#ffffff"))
        for j in range(j0, j1):
            for i in range(i0, i1):
                centre = QPointF(rect.x() + (i + 0.5) * sx, rect.y() + (j + 0.5) * sy)
                painter.drawEllipse(centre, radius, radius)
        painter.setBrush(Qt.BrushStyle.NoBrush)

    def paintEvent(self, event):
        painter = QPainter(self)
        painter.fillRect(self.rect(), QColor("#15181f"))
        if self._image is None:
            painter.setPen(QColor("#8a93a6"))
            painter.drawText(self.rect(), Qt.AlignmentFlag.AlignCenter, self._placeholder)
            painter.end()
            return
        rect = self.image_rect()
        shown = rect.intersected(self._room())  # all of the picture in view, or the part zoomed into
        painter.setClipRect(shown)
        painter.setRenderHint(QPainter.RenderHint.SmoothPixmapTransform, False)
        painter.drawImage(rect, self._image)
        if self._highlight is not None and self._highlight_shape == (self._image.height(),
                                                                     self._image.width()):
            sx = rect.width() / self._image.width()
            sy = rect.height() / self._image.height()
            seg = self._highlight * (sx, sy, sx, sy) + (rect.x(), rect.y(), rect.x(), rect.y())
            width = max(2.0, min(0.25 * min(sx, sy), 6.0))  # (zoomed in, a line, not a band)
            # Each segment is axis-aligned: filled as a thin rectangle, far quicker than a wide stroke.
            painter.setPen(Qt.PenStyle.NoPen)
            for colour, w in ((QColor(0, 0, 0, 170), width + 2), (self._highlight_color, width)):
                corner = np.minimum(seg[:, :2], seg[:, 2:]) - w / 2  # a dark rim, visible on light colours
                size = np.abs(seg[:, 2:] - seg[:, :2]) + w
                painter.setBrush(colour)
                painter.drawRects([QRectF(*r) for r in np.hstack([corner, size]).tolist()])
        if self.grid_shown():
            self._paint_grid(painter, rect)
        if self.grid_shown() and self.edges is not None and len(self.edges) >= 2:
            sx = rect.width() / self._image.width()
            sy = rect.height() / self._image.height()
            points = [QPointF(rect.x() + x * sx, rect.y() + y * sy) for x, y in self.edges.tolist()]
            for colour, w in ((QColor(0, 0, 0, 200), 4.0), (QColor(EDGE_COLOR), 2.0)):
                pen = QPen(colour, w)
                if self.edges_coming:
                    pen.setStyle(Qt.PenStyle.DashLine)
                painter.setPen(pen)
                painter.drawPolygon(points)
        painter.setClipping(False)
        if self.hasFocus() and self._margin:
            # In the room kept around the image, so it covers no pixel; the palette's focus colour.
            painter.setPen(QPen(self.palette().color(QPalette.ColorRole.Highlight), 2))
            painter.setBrush(Qt.BrushStyle.NoBrush)
            painter.drawRect(shown.adjusted(-self._margin + 1, -self._margin + 1,
                                            self._margin - 1, self._margin - 1))
        if self.picked is not None and shown.contains(self.widget_pos(*self.picked)):
            sx = rect.width() / self._image.width()
            sy = rect.height() / self._image.height()
            x, y = self.picked
            cell = QRectF(rect.x() + x * sx, rect.y() + y * sy, sx, sy)
            pad = min(max(3.0, sx), PICKED_PAD_PX)
            painter.setBrush(Qt.BrushStyle.NoBrush)  # an outline: the highlight's fill hid the pixel
            painter.setPen(QPen(QColor("#ffffff"), 2))
            painter.drawRect(cell.adjusted(-pad, -pad, pad, pad))
            painter.setPen(QPen(QColor("#000000"), 1))
            painter.drawRect(cell.adjusted(-pad - 2, -pad - 2, pad + 2, pad + 2))
        if self.note:
            self._paint_note(painter, self.note, shown, Qt.Corner.TopLeftCorner)
        if self.zoom > 1:  # part of the picture is hidden: say so, and how to see it whole
            self._paint_note(painter, self.zoom_note(), shown, Qt.Corner.BottomRightCorner)
        painter.end()

    def zoom_note(self) -> str:
        """What the picture says in its corner while zoomed in (``""`` when shown whole): its zoom, in
        few words (presenting, the picture may be small; its tooltip and Help → Keys say the rest)."""
        return f"×{self.zoom:.3g}" if self.zoom > 1 else ""

    @staticmethod
    def _paint_note(painter: QPainter, text: str, shown: QRectF, corner: Qt.Corner) -> None:
        """``text`` in a dark box in ``corner`` of the part of the picture shown."""
        painter.setOpacity(0.8)
        label = QRectF(painter.fontMetrics().boundingRect(text).adjusted(-6, -3, 6, 3))
        if corner == Qt.Corner.TopLeftCorner:
            label.moveTopLeft(shown.topLeft() + QPointF(6, 6))
        else:
            label.moveBottomRight(shown.bottomRight() - QPointF(6, 6))
        painter.fillRect(label, QColor("#15181f"))
        painter.setOpacity(1.0)
        painter.setPen(QColor(NOTE_COLOR))
        painter.drawText(label, Qt.AlignmentFlag.AlignCenter, text)


def zoom_together(views: list[ImageView]) -> None:
    """``views`` (pictures of the same pixels, side by side) zoom and move together: as one is zoomed
    or moved, the others show the same part of their pictures (those of the same size)."""
    for view in views:
        for other in views:
            if other is not view:
                view.zoomed.connect(lambda zoom_, focus, other=other, view=view:
                                    other.qimage is not None and view.qimage is not None
                                    and other.qimage.size() == view.qimage.size()
                                    and other.set_zoom(zoom_, focus))
