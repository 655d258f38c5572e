"""The object-order panel: the pipeline's stages, step by step, and one pixel's history.

Polygons are processed one after another.  The scrubber moves through them:
at step k the image memory and the z-buffer are shown exactly as they stand
after the first k polygons, the polygon drawn at that step has its fragments
outlined in both buffers, and a click on a pixel lists every fragment that
reached it: which polygon, its depth against the stored depth, whether it
passed, and for transparent polygons the blend; above them one sentence says
what decided the pixel (:mod:`core.pixel_verdict`).

A step's picture (the buffers replayed to it, encoded for the screen, the overdraw
heat map) is made on a worker thread; the window only paints it.  Making it on the
GUI thread held the window at every lesson step and scrubber move, and it was made
even while the panel was hidden: a hidden panel now makes it once it is shown.
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QEvent, Qt, Signal
from PySide6.QtGui import QColor, QFont
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QGroupBox,
    QHBoxLayout,
    QHeaderView,
    QLabel,
    QPlainTextEdit,
    QSplitter,
    QTableWidget,
    QTableWidgetItem,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from core.in_words import counted
from core.object_order.depth_formats import BYTES_PER_PIXEL, DEPTH_FORMATS
from core.object_order.pipeline import STAGES, RasterResult, RasterSettings
from core.pixel_verdict import dropped_fragments, raster_verdict
from core.projection import project_point
from core.scene import Scene
from core.srgb import linear_to_srgb
from views.images.color_scale import ColorScale, heat_over
from views.images.depth_view import DepthView
from views.images.image_view import ImageView, zoom_together
from views.images.step_picture import StepPicture, polygon_name, step_picture
from views.jobs import JobRunner, own_thread
from views.panels.panel_layout import pictures_over_details
from views.panels.side_column import SideColumn
from views.panels.step_scrubber import StepScrubber
from views.text.verdict_label import VerdictLabel
from views.text.worked_math import WorkedMath
from views.whole_rows import ROWS_SHOWN, WholeLinesLabel, WholeRowsTable

#: Each stage's check box: its text and tooltip, by :data:`core.object_order.pipeline.STAGES`.
STAGE_WORDS = {
    "back_face_culling": ("Back-face culling",
                          "Skip faces whose normal points away from the eye (the sign of Nz).\n"
                          "Off: every face is rasterized; the z-buffer still hides the back ones, "
                          "at a cost."),
    "frustum_culling": ("Frustum culling",
                        "Skip whole objects whose bounding sphere lies outside the viewing pyramid."),
    "clipping": ("Clipping",
                 "Cut polygons at the six frustum planes before the perspective divide.\n"
                 "Off: polygons reaching behind the eye are dropped whole, so geometry near the observer "
                 "vanishes."),
    "sort_transparent": ("Sort transparent\nfar → near",
                         "Blend transparent polygons from the farthest to the nearest, after all "
                         "opaque ones.\n"
                         "Off: they are blended in scene order, and the colours come out wrong."),
    "z_test": ("z-test",
               "Keep a fragment only if it is nearer than the depth already stored at its pixel.\n"
               "Off: every fragment overwrites the pixel, so the polygon drawn last wins, near or far."),
}

DEPTH_FORMAT_TIP = (
    "The z-buffer's number format.  Window depth crowds toward the far plane, so two surfaces "
    "closer together than one step of the format get the same stored depth and the drawing "
    "order decides between them, pixel by pixel (z-fighting).\n"
    "float64: our reference.  float32: 24 significant bits.  float32-reversed: stores 1 − depth, "
    "so the float's fine steps meet the crowded far end.  int24, int16: equal steps over [0, 1].")

HISTORY_PROMPT = "Click a pixel in either buffer to see its history."
DEPTH_TIP = ("Depths are distances along the viewing axis; a fragment passes when it is nearer than the "
             "depth stored so far")
HISTORY_COLUMNS = ["step", "polygon", "depth", "stored depth", "z-test", "before", "after", "blend αs"]


def _swatch(rgb) -> QTableWidgetItem:
    item = QTableWidgetItem(" ".join(f"{c:.2f}" for c in rgb))
    color = QColor.fromRgbF(*linear_to_srgb(rgb))
    item.setBackground(color)
    item.setForeground(QColor("black" if color.lightnessF() > 0.5 else "white"))
    return item


def _text_box() -> QPlainTextEdit:
    """A read-only, scrollable, monospaced text area for numbers."""
    box = QPlainTextEdit()
    box.setReadOnly(True)
    font = QFont("monospace")
    font.setStyleHint(QFont.StyleHint.Monospace)
    box.setFont(font)
    box.setLineWrapMode(QPlainTextEdit.LineWrapMode.NoWrap)
    return box


def _step_shown(result: RasterResult, scene: Scene, k: int, overdraw: bool) -> tuple:
    """What the panel paints at step ``k`` (made on a worker): its picture, and the overdraw heat map
    when that is on (else ``None``)."""
    picture = step_picture(result, scene, k)
    if not overdraw:
        return picture, None
    return picture, heat_over(result.history.fragments_per_pixel(k), "fragments", picture.image.rgb,
                              "overdraw")


VERTEX_PROMPT = ("Click a pixel in either buffer: the corner of its visible polygon "
                 "nearest to it is followed from world space to the pixel.")

class ObjectOrderPanel(QWidget):
    """Stage switches, step scrubber, image memory and z-buffer, pixel history.

    The stage switches, the scrubber and a click in the buffers write to the
    model (``set_raster_settings``, ``set_step``, ``set_buffer_pixel``); the
    panel shows what the model holds.

    Signals
    -------
    polygon_shown(object) : world-space vertices (N, 3) of the polygon drawn at
        the current step, or ``None`` at step 0, for the 3D pane to highlight.
    clipped_shown(object) : list of (N, 3) world-space polygons the frustum cut,
        for the 3D pane to outline.
    """

    polygon_shown = Signal(object)
    clipped_shown = Signal(object)

    def __init__(self, model, parent: QWidget | None = None):
        super().__init__(parent)
        self.model = model
        self.result: RasterResult | None = None
        self.scene: Scene | None = None
        self._dropped = (None, ())  # ((result, pixel), its fragments culling and clipping dropped)
        self._pictures = JobRunner(self, own_thread(self))  # makes the step's picture off the GUI thread
        self._pictures.finished.connect(self._paint_step)
        self._stale = False  # a step was chosen while hidden: its picture is made once shown
        self.switches: dict[str, QCheckBox] = {}
        stages = QWidget()
        switches = QVBoxLayout(stages)
        switches.setContentsMargins(0, 0, 0, 0)
        switches.addWidget(QLabel("<b>Stages</b>"))
        for key in STAGES:
            text, tip = STAGE_WORDS[key]
            box = QCheckBox(text)
            box.setChecked(True)
            box.setToolTip(tip)
            box.toggled.connect(self._settings_edited)
            switches.addWidget(box)
            self.switches[key] = box
        self.depth_format = QComboBox()
        for name in DEPTH_FORMATS:
            self.depth_format.addItem(f"{name} ({BYTES_PER_PIXEL[name]} bytes)", name)
        self.depth_format.setToolTip(DEPTH_FORMAT_TIP)
        # As wide as the stage switches above it, a longer choice cut short (its list shows it whole):
        # as wide as its longest ("float32-reversed (4 bytes)"), the column took so much of a small
        # screen, presenting, that the dock tabs beside the pane lost their names' ends.
        self.depth_format.setSizeAdjustPolicy(QComboBox.SizeAdjustPolicy.AdjustToMinimumContentsLengthWithIcon)
        self.depth_format.setMinimumContentsLength(12)
        self.depth_format.currentIndexChanged.connect(self._settings_edited)
        depth_label = QLabel("z-buffer format")
        depth_label.setToolTip(DEPTH_FORMAT_TIP)
        switches.addWidget(depth_label)
        switches.addWidget(self.depth_format)
        self.overdraw = QCheckBox("Overdraw heat map")
        self.overdraw.setToolTip("Colour each pixel by the fragments that reached it so far (passed or "
                                 "failed), over the image memory: where the z-buffer did its work")
        self.overdraw.toggled.connect(lambda _: self.show_step(self.scrubber.step))
        self.overdraw_scale = ColorScale("Overdraw colour scale: the map's darkest colour means no "
                                         "fragment, its brightest the most any pixel received so far")
        self.overdraw_scale.hide()
        switches.addWidget(self.overdraw)
        switches.addWidget(self.overdraw_scale)

        self.scrubber = StepScrubber()
        self.image = ImageView(placeholder="image memory")
        self.depth = DepthView()
        zoom_together([self.image, self.depth.image])
        buffers = QSplitter(Qt.Orientation.Horizontal)
        for title, widget in (("Image memory", self.image), ("z-buffer", self.depth)):
            box = QGroupBox(title)
            QVBoxLayout(box).addWidget(widget)
            buffers.addWidget(box)
        self.step_caption = QLabel()
        self.step_caption.setWordWrap(True)

        self.history = WholeRowsTable(0, len(HISTORY_COLUMNS))  # the pane gives its first rows room
        self.history.setHorizontalHeaderLabels(HISTORY_COLUMNS)
        self.history.verticalHeader().setVisible(False)
        # Columns as wide as their header or their widest entry, rows as tall as the text,
        # at every text scale (presentation mode enlarges both).
        self.history.horizontalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        self.history.verticalHeader().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        self.history.setEditTriggers(QTableWidget.EditTrigger.NoEditTriggers)
        for column in (2, 3, 4):  # depth, stored depth, z-test
            self.history.horizontalHeaderItem(column).setToolTip(DEPTH_TIP)
        self.history.setToolTip(DEPTH_TIP)
        self.history_caption = WholeLinesLabel(HISTORY_PROMPT)
        self.verdict = VerdictLabel()
        self.history.viewport().installEventFilter(self)  # its height shared with the verdict
        history_page = QWidget()
        hl = QVBoxLayout(history_page)
        hl.addWidget(self.verdict)
        hl.addWidget(self.history_caption)
        hl.addWidget(self.history, 1)
        self.numbers = _text_box()
        self.counts = _text_box()
        self.details = QTabWidget()
        self.details.addTab(history_page, "Pixel history")
        self.details.addTab(self.numbers, "Numbers")
        self.details.addTab(self.counts, "Counts and times")
        self.vertex_math = WorkedMath()
        self.vertex_math.clear(VERTEX_PROMPT)
        self._vertex_objects = None  # the objects of the scene whose vertex the Vertex path shows
        self.details.addTab(self.vertex_math, "Vertex path")

        # The buffers beside the stage switches, the pixel's details under both: the buffers
        # keep the pane's height, the history table gets several rows.
        top = QWidget()
        tl = QVBoxLayout(top)
        tl.setContentsMargins(0, 0, 0, 0)
        beside = QHBoxLayout()
        beside.addWidget(buffers, 1)
        beside.addWidget(SideColumn([stages]))
        tl.addLayout(beside, 1)
        tl.addWidget(self.scrubber)
        tl.addWidget(self.step_caption)
        pictures_over_details(self, top, self.details)

        self.scrubber.step_changed.connect(self._step_edited)
        self.image.pixel_clicked.connect(self.pick_pixel)
        self.depth.image.pixel_clicked.connect(self.pick_pixel)
        model.raster_settings_changed.connect(self.show_settings)
        model.step_changed.connect(self._step_changed)
        model.buffer_pixel_changed.connect(self._show_pixel)
        self.show_settings(model.raster_settings)

    def _fit_verdict(self) -> None:
        """Give the verdict above the pixel's history the lines its fragments' rows do not need (up to
        :data:`~views.whole_rows.ROWS_SHOWN` of them): presenting on a 1280 x 720 projector a pixel
        of one fragment left two rows' room empty under a verdict cut short with "…"."""
        rows = min(self.history.rowCount(), ROWS_SHOWN)
        need = sum(self.history.rowHeight(r) for r in range(rows)) or self.history.fontMetrics().lineSpacing()
        self.verdict.share_room(self.history, need)

    def eventFilter(self, watched, event) -> bool:
        if event.type() == QEvent.Type.Resize and watched is self.history.viewport():
            self._fit_verdict()
        return super().eventFilter(watched, event)

    @property
    def picked(self) -> tuple[int, int] | None:
        """The pixel whose history is listed (the model's)."""
        return self.model.buffer_pixel

    def _settings_edited(self) -> None:
        self.model.set_raster_settings(RasterSettings(
            **{k: b.isChecked() for k, b in self.switches.items()},
            depth_format=self.depth_format.currentData(), record_steps=True))

    def show_settings(self, settings: RasterSettings) -> None:
        """Show ``settings`` in the stage switches and the depth format without writing them back."""
        for key, box in self.switches.items():
            box.blockSignals(True)
            box.setChecked(getattr(settings, key))
            box.blockSignals(False)
        self.depth_format.blockSignals(True)
        self.depth_format.setCurrentIndex(self.depth_format.findData(settings.depth_format))
        self.depth_format.blockSignals(False)

    def _step_edited(self, k: int) -> None:
        self.model.set_step(None if k >= self.scrubber.slider.maximum() else k)

    def _step_changed(self, _step) -> None:
        """Show the model's new step, unless the render shown is of another scene: the render of the
        model's scene shows it when it comes (a lesson step sets its scene, then its step)."""
        if self.scene is self.model.scene:
            self.show_step(self._model_step())

    def _model_step(self) -> int:
        """The model's step, within the current render's steps (``None``: the last)."""
        count = self.result.history.n_steps if self.result is not None else 0
        step = self.model.step
        return count if step is None else min(step, count)

    def show_preview(self, image) -> None:
        """While the observer moves: a coarse image memory (a :class:`DisplayImage`) only."""
        self.image.set_image(image)
        self.step_caption.setText("Preview while the observer moves: the steps and the "
                                  "z-buffer follow once it rests.")

    def show_result(self, result: RasterResult, scene: Scene, picture: StepPicture | None = None) -> None:
        """Show a finished recording render at the model's step (the last, unless one was chosen).

        ``picture``: that step's picture when a worker made it already (:func:`step_picture`).
        """
        self.result, self.scene = result, scene
        self.counts.setPlainText(self._counts_text())
        if self._vertex_objects is not None and self._vertex_objects != scene.objects:
            self.clear_vertex()  # another scene: its vertex is not in this one
        self.vertex_math.follow_camera(scene.camera)
        self.clipped_shown.emit(result.clipping.clipped_polygons())
        self.scrubber.blockSignals(True)
        self.scrubber.set_count(result.history.n_steps)
        self.scrubber.set_step(self._model_step())
        self.scrubber.blockSignals(False)
        self.show_step(self.scrubber.step, picture)

    @property
    def pending(self) -> bool:
        """The picture of the step shown by the scrubber is being made on a worker."""
        return self._pictures.busy

    def show_step(self, k: int, picture: StepPicture | None = None) -> None:
        """Buffers after the first ``k`` polygons, with polygon k's fragments outlined.

        The scrubber moves at once; the buffers follow when a worker has made their picture
        (``picture``: made already, painted at once), and a hidden panel makes it once shown.
        """
        if self.result is None:
            return
        self.scrubber.blockSignals(True)
        self.scrubber.set_step(k)
        self.scrubber.blockSignals(False)
        self._show_pixel(self.picked)
        overdraw = self.overdraw.isChecked()
        if picture is not None and picture.step == k and not overdraw:
            self._pictures.cancel()
            self._stale = False
            self._paint_step((picture, None))
            return
        self._stale = not self.isVisible()
        if self._stale:
            self._pictures.cancel()
            return
        result, scene = self.result, self.scene
        self._pictures.submit(lambda cancelled, progress: _step_shown(result, scene, k, overdraw))

    def showEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        super().showEvent(event)
        if self._stale:
            self.show_step(self.scrubber.step)

    def _paint_step(self, shown: tuple) -> None:
        """Paint a step's picture and overdraw (:func:`_step_shown`) and single out its polygon."""
        picture, overdraw = shown
        history = self.result.history
        self.overdraw_scale.setVisible(overdraw is not None)
        if overdraw is not None:
            heat = overdraw.heat
            self.image.set_image(overdraw.image)
            self.overdraw_scale.set_scale(overdraw.colorbar, "0", f"{heat.top:,}",
                                          f"fragments a pixel up to step {picture.step}; {heat.total:,} "
                                          f"in all, {heat.mean:.2f} a pixel")
        else:
            self.image.set_image(picture.image)
        self.depth.set_depth(picture.depth, history.near, history.far, picture.depth_image)
        self.step_caption.setText(picture.caption)
        # The whole picture (no step chosen, as a lesson shows it) singles out no polygon.
        chosen = self.model.step is not None
        self.polygon_shown.emit(picture.polygon if chosen else None)
        for view in (self.image, self.depth.image):
            view.set_highlight(picture.mask if chosen else None, outline=picture.outline)
        # Its edges are drawn only where pixels are large, and only for a chosen step, as the outline;
        # over the cleared buffers, dashed, the edges of the polygon drawn next.
        coming = picture.polygon is None and picture.coming is not None
        corners = self._window_corners(picture.coming if coming else picture.polygon)
        self.image.set_edges(corners if chosen else None, coming=coming)

    def _window_corners(self, polygon) -> np.ndarray | None:
        """The drawn polygon's corners (world) in pixel coordinates (None at step 0 or behind the eye);
        the image draws them where its pixels show large enough to see which centres are covered."""
        if polygon is None:
            return None
        pixels = self._pixels_of(polygon)
        return None if any(q is None for q in pixels) else np.array(pixels)

    def _pixels_of(self, corners) -> list:
        """Each world point of ``corners`` projected to the scene's image: its pixel coordinates, or None
        behind the eye (the camera's matrices worked out once, not for each point)."""
        cam = self.scene.camera
        view_from_world, clip_from_view = cam.view_from_world, cam.clip_from_view
        return [project_point(c, view_from_world, clip_from_view, cam.width, cam.height).pixel
                for c in corners]

    def _polygon_name(self, p: int) -> str:
        return polygon_name(self.result, self.scene, p)

    def pick_pixel(self, x: int, y: int) -> None:
        """Pick pixel ``(x, y)``: its fragments up to the current step are listed."""
        self.model.set_buffer_pixel((x, y))

    def _show_pixel(self, pixel) -> None:
        """List every fragment that reached ``pixel`` up to the current step (``None``: clear)."""
        history = None if self.result is None else self.result.history
        if pixel is not None and history is not None and not (
                pixel[0] < history.width and pixel[1] < history.height):
            pixel = None  # the pick belongs to a newer image than this render's
        self.image.set_picked(pixel)
        self.depth.image.set_picked(pixel)
        if pixel is None or history is None:
            self.history.setRowCount(0)
            self.verdict.show_verdict(None)
            self.history_caption.setText(HISTORY_PROMPT)
            self.numbers.clear()
            return
        x, y = pixel
        if self._dropped[0] != (self.result, pixel):  # found once per pixel, not at every step
            self._dropped = ((self.result, pixel), dropped_fragments(self.result, x, y))
        self.verdict.show_verdict(raster_verdict(self.result, x, y, self.scrubber.step, self._dropped[1]))
        events = [e for e in self.result.history.pixel_history(x, y)
                  if e.polygon < self.scrubber.step]
        self.history.setRowCount(len(events))
        for row, e in enumerate(events):
            cells = [QTableWidgetItem(str(e.polygon + 1)),
                     QTableWidgetItem(self._polygon_name(e.polygon)),
                     QTableWidgetItem(f"{e.distance:.4f}"),
                     QTableWidgetItem(f"{e.stored_distance:.4f}"),
                     QTableWidgetItem("pass: nearer" if e.passed else "fail: farther"),
                     _swatch(e.color_before), _swatch(e.color_after),
                     QTableWidgetItem("" if e.blend is None else
                                      f"{e.blend.alpha:.2f}: c0 = αs·cs + (1 − αs)·cd")]
            for col, cell in enumerate(cells):
                self.history.setItem(row, col, cell)
        # One line: what a depth is and when a fragment passes, the depth columns' tooltips say
        # (at text x2 on 1280 x 720 the sentence took two more lines from the fragments' rows).
        self.history_caption.setText(
            f"Pixel ({x}, {y}): {counted(len(events), 'fragment')} up to step {self.scrubber.step}.")
        self.numbers.setPlainText(self._numbers_text(events))
        self._fit_verdict()
        visible = [e for e in events if e.passed]
        if visible:
            self._show_vertex_path(visible[-1].polygon, x, y)

    def _show_vertex_path(self, p: int, x: int, y: int) -> None:
        """The path of polygon ``p``'s corner nearest to pixel ``(x, y)``, world to pixel."""
        corners = self.result.draw.polygons.world_vertices(p)
        pixels = self._pixels_of(corners)
        gaps = [np.inf if q is None else np.hypot(q[0] - x - 0.5, q[1] - y - 0.5) for q in pixels]
        k = int(np.argmin(gaps))
        self.show_vertex(corners[k], self.scene, f"corner {k} of {self._polygon_name(p)}")

    def show_vertex(self, point, scene: Scene, name: str) -> None:
        """Follow world point ``point``, a vertex of ``scene``'s objects called ``name``, to its pixel
        in the Vertex path tab; it is cleared when a scene with other objects is shown."""
        self._vertex_objects = scene.objects
        self.vertex_math.show_vertex(point, scene.camera, name)

    def clear_vertex(self) -> None:
        """Empty the Vertex path tab (it asks for a pixel to be clicked)."""
        self._vertex_objects = None
        self.vertex_math.clear(VERTEX_PROMPT)

    def _numbers_text(self, events) -> str:
        r = self.result
        m = r.clip_from_view
        lines = ["clip_from_view (projection matrix in use):"]
        lines += ["  [" + "  ".join(f"{v:9.4f}" for v in row) + " ]" for row in m]
        x, y = self.picked
        visible = [e for e in events if e.passed]
        if visible:
            e = visible[-1]
            face = r.face_index(e.object_index, e.triangle_index)
            n = r.faces.normal[face]
            lines += ["", f"face at pixel ({x}, {y}): {self._polygon_name(e.polygon)}",
                      f"  camera-space normal N = ({n[0]:.3f}, {n[1]:.3f}, {n[2]:.3f})",
                      f"  Nz = {r.faces.nz[face]:.3f} → "
                      f"{'faces the observer' if r.faces.facing[face] else 'faces away (culled)'}"]
        return "\n".join(lines)

    def _counts_text(self) -> str:
        s = self.result.stats
        lines = ["per stage:"]
        for key, value in s.items():
            if isinstance(value, dict):
                continue
            lines.append(f"  {key.replace('_', ' ')}: {value}")
        lines.append("time (ms):")
        lines += [f"  {k}: {v * 1000:.1f}" for k, v in s.get("times", {}).items()]
        return "\n".join(lines)
