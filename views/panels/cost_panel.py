"""The Cost panel: what accuracy costs in time, swept knob by knob, point by point.

Pick a knob (or all), run: the sweep (:class:`core.accuracy.sweep.Sweep`)
runs on the thread pool, one render at a time, and every finished setting
becomes a point on the error-against-time plot as it arrives.  Cancel stops
the running render within a pixel or a triangle (:mod:`core.stopping`); Run
again resumes where it stopped.  Clicking a point shows that setting's image,
the reference and the FLIP error map side by side (and the samples per pixel
for adaptive supersampling), with a sentence on why the knob's curve has its
shape.  The CSV and the plot can be exported.

Before a sweep starts its cost is estimated (:mod:`core.accuracy.sweep_cost`):
one over the memory budget does not start and says what to reduce; a long one
says how long, in its status line, while it runs.

matplotlib loads, and the figures are made, when the panel is first shown
(or first asked for a point), so the main window opens without it.  The plot
and the point's images (:mod:`views.images.point_images`) are laid out and
drawn off the GUI thread (:mod:`views.images.figure_image`), the plot in a
process of its own (:mod:`views.images.cost_plot_process`), never while the
pane is hidden; the window only paints their pictures.
"""

from __future__ import annotations

import math
import threading
from dataclasses import replace

import numpy as np
from PySide6.QtCore import QEvent, QSize, Qt, QThreadPool, QTimer, Signal
from PySide6.QtWidgets import (
    QComboBox,
    QDoubleSpinBox,
    QFrame,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QProgressBar,
    QPushButton,
    QScrollArea,
    QSizePolicy,
    QSpinBox,
    QVBoxLayout,
    QWidget,
)

from core import budget
from core.accuracy import sweep_cost
from core.accuracy.explanations import EXPLANATIONS
from core.accuracy.reference import REFERENCE_SPP
from core.accuracy.sweep import (
    DEFAULT_TOLERANCE,
    KNOB_NAMES,
    KNOBS,
    Knee,
    Point,
    Progress,
    Sweep,
    marked_rows,
    unavailable,
)
from core.scene import Scene
from views.file_dialogs import ask_save
from views.images import cost_files, cost_plot_process, plot_theme
from views.images.agg_figure import Drawn
from views.images.cost_plot import point_position
from views.images.figure_image import FigureImage
from views.images.point_images import point_images_drawing
from views.jobs import Job, JobRunner
from views.panels.cost_sheet import CostSheet

MODES = [("raytrace", "Ray tracing"), ("raycast", "Ray casting"), ("raster", "Rasterization")]
#: The sweep's image is at most this wide (the scene's aspect kept), so a sweep takes minutes, not hours.
DEFAULT_WIDTH = 160
#: A sweep estimated to take longer than this (seconds) says how long in its status line.
LONG_SWEEP_SECONDS = 600
REPLOT_MS = 1000
"""While a sweep runs, the plot is drawn again at most this often, with the last full layout's axes;
the finished sweep is drawn in full.  (A full draw, matplotlib's constrained layout done three times
to tidy the labels, takes a core about half a second on a small machine, and the points of cheap
settings come in several a second.)"""


class _CanvasBox(QWidget):
    """Where a canvas goes once made; meanwhile it asks for the room the canvas will ask for."""

    def __init__(self):
        super().__init__()
        QVBoxLayout(self).setContentsMargins(0, 0, 0, 0)

    def sizeHint(self) -> QSize:
        return QSize(640, 480)  # matplotlib's default figure, 6.4 x 4.8 inches at 100 dpi


class _VerticalScrollArea(QScrollArea):
    """Scrolls its word-wrapped label up and down only, at the area's width: all the words show when
    there is room, and they scroll when there is not (the explanation beside the images)."""

    def __init__(self, label: QLabel):
        super().__init__()
        self.setWidget(label)
        self.setFrameShape(QFrame.Shape.NoFrame)
        self.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)

    def refit(self) -> None:
        """Size the words to the width there is (call after their text changed)."""
        self._fit()
        self.updateGeometry()

    def _fit(self) -> None:
        width = max(self.width(), 1)
        height = self.widget().heightForWidth(width)
        if height > self.height():  # a scroll bar shows: the words get narrower
            width = max(width - self.verticalScrollBar().sizeHint().width(), 1)
            height = self.widget().heightForWidth(width)
        self.widget().resize(width, height)

    def sizeHint(self) -> QSize:
        width = max(self.width(), 1)
        return QSize(width, self.widget().heightForWidth(width))

    def minimumSizeHint(self) -> QSize:
        return QSize(0, 3 * self.fontMetrics().lineSpacing())

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._fit()
        if event.size().width() != event.oldSize().width():
            self.updateGeometry()  # the words' height follows the width


def _sweep_job(sweep: Sweep, lock: threading.Lock) -> Job:
    """A job (:mod:`views.jobs`) that runs ``sweep``'s events, each its partial result (the percent
    is unused: the :class:`Progress` events say how far), and returns whether every setting is done;
    cancelled, it stops inside the running render."""

    def job(cancelled, progress):
        with lock:  # a stopped run ends before the resumed one starts
            if cancelled.is_set():
                return None
            # Settings a stopped run finished after it was cancelled were never shown: report them first.
            earlier = [*sweep.points.values(), *(Knee(k, i) for k, i in sweep.knee_indices().items())]
            for event in earlier:
                progress(0, event)
            events = sweep.events()
            try:
                for event in events:
                    if cancelled.is_set():
                        return None
                    progress(0, event)
            finally:
                events.close()
            return sweep.finished

    return job


class CostPanel(QWidget):
    """Sweeps of the accuracy knobs of a scene, plotted as they run.

    Signals
    -------
    point_selected(int) : the setting index of the clicked point.
    sweep_finished(bool) : a run ended, ``True`` when every setting is done.
    plot_drawn() : a new picture of the plot is shown.

    Attributes
    ----------
    memory_limit : a sweep estimated to need more bytes does not start; ``None``:
        half of the memory available when it would start.
    """

    point_selected = Signal(int)
    sweep_finished = Signal(bool)
    plot_drawn = Signal()

    def __init__(self, parent: QWidget | None = None, pool: QThreadPool | None = None):
        super().__init__(parent)
        self.memory_limit: int | None = None
        self._slow_note = ""  # the estimated time of a long sweep, added to its status line
        self._scene: Scene | None = None
        self.sweep: Sweep | None = None
        self._points: dict[int, Point] = {}
        self._knees: dict[str, int] = {}
        self._lines: dict = {}
        self._layout: tuple | None = None  # the axes' places in the last full draw of the plot (_places)
        self._replot = QTimer(self)
        self._replot.setSingleShot(True)
        self._replot.setInterval(REPLOT_MS)
        self._replot.timeout.connect(lambda: self._draw_plot(quick=True))
        # A new scene's empty plot and images are asked for a turn later: a lesson step sets its scene
        # while this pane still shows and then shows its own tab, and the plot laid out meanwhile held
        # the window for its first steps (a full layout takes a core a second or more, mostly in Python).
        self._after_reset = QTimer(self, singleShot=True, interval=0)
        self._after_reset.timeout.connect(self._draw_stale)
        self.selected: int | None = None
        self._swept_with: tuple | None = None
        self._sweep_lock = threading.Lock()  # one run at a time, even just after a cancel
        self._runner = JobRunner(self, pool)  # every event delivered: each point is one on the plot
        self._runner.progress.connect(lambda _, event: self._on_event(event))
        self._runner.finished.connect(self._on_done)
        self._runner.failed.connect(self._on_failed)

        self.knob = QComboBox()
        self.knob.addItem("all knobs", "all")
        for name in KNOB_NAMES:
            self.knob.addItem(KNOBS[name].title, name)
        self.knob.setToolTip("The setting to sweep; everything else stays at its default")
        self.knob.setMaximumWidth(260)
        self.mode = QComboBox()
        for key, text in MODES:
            self.mode.addItem(text, key)
        self.mode.setToolTip("The pipeline for knobs both pipelines have (supersampling, resolution); "
                             "the others always use their own")
        self.width_px = QSpinBox()
        self.width_px.setRange(16, 640)
        self.width_px.setValue(DEFAULT_WIDTH)
        self.width_px.setSuffix(" px")
        self.width_px.setToolTip("Width of the swept images (the scene's aspect is kept)")
        self.reference_spp = QSpinBox()
        self.reference_spp.setRange(1, 16)
        self.reference_spp.setValue(REFERENCE_SPP)
        self.reference_spp.setPrefix("reference ")
        self.reference_spp.setSuffix("² spp")
        self.reference_spp.setToolTip("Samples per pixel of the reference, along each axis")
        self.tolerance = QDoubleSpinBox()
        self.tolerance.setRange(0.0, 1.0)
        self.tolerance.setDecimals(3)
        self.tolerance.setSingleStep(0.005)
        self.tolerance.setValue(DEFAULT_TOLERANCE)
        self.tolerance.setPrefix("knee ±")
        self.tolerance.setToolTip("The knee: the cheapest setting whose FLIP is within this of the best's")
        self.run_button = QPushButton("Run")
        self.cancel_button = QPushButton("Cancel")
        self.cancel_button.setEnabled(False)
        self.export_csv_button = QPushButton("Export CSV…")
        self.export_plot_button = QPushButton("Export plot…")
        self.progress = QProgressBar()
        self.progress.setRange(0, 1000)
        self.progress.setTextVisible(False)
        # Shown once a sweep starts: empty, before any, it read as a text field to type into.  Its room
        # is kept, so that the status beside it stays where it is.
        keep_room = self.progress.sizePolicy()
        keep_room.setRetainSizeWhenHidden(True)
        self.progress.setSizePolicy(keep_room)
        self.progress.hide()
        self.status = QLabel("Set a scene, pick a knob and press Run.")
        self.status.setWordWrap(True)
        self._keep_two_status_lines()
        self.explanation = QLabel()
        self.explanation.setWordWrap(True)
        self.explanation.setTextFormat(Qt.TextFormat.RichText)
        self.explanation.setAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        self.explanation.setSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.Minimum)

        self.canvas = self.image_canvas = None  # see _make_canvases
        self._plot_stale = False  # the plot waits to be drawn until the pane is shown
        self._images_stale = False  # so do the point's images
        self._dark = False  # the figures were drawn in the dark theme
        self._dpi = plot_theme.DPI  # the figures' resolution, after the text size they were made for
        self._plot_box, self._image_box = _CanvasBox(), _CanvasBox()
        self._image_box.setMinimumSize(200, 160)

        controls = QGridLayout()  # three to a row, so that a narrow window keeps every control in view
        for i, w in enumerate((self.knob, self.mode, self.width_px, self.reference_spp, self.tolerance,
                               self.run_button, self.cancel_button, self.export_csv_button,
                               self.export_plot_button)):
            controls.addWidget(w, i // 3, i % 3)
        controls.setColumnStretch(3, 1)
        right = QWidget()
        right_layout = QVBoxLayout(right)
        right_layout.setContentsMargins(0, 0, 0, 0)
        right_layout.addWidget(self._image_box, 1)
        self._words = _VerticalScrollArea(self.explanation)
        right_layout.addWidget(self._words)
        self.sheet = CostSheet(self._plot_box, right)  # side by side, or pages on a small pane
        self.sheet.shown.connect(self._draw_stale)
        layout = QVBoxLayout(self)
        layout.addLayout(controls)
        status_row = QHBoxLayout()
        status_row.addWidget(self.progress, 1)
        status_row.addWidget(self.status, 3)
        layout.addLayout(status_row)
        layout.addWidget(self.sheet, 1)

        self.run_button.clicked.connect(self.run)
        self.cancel_button.clicked.connect(self.cancel)
        self.export_csv_button.clicked.connect(self._ask_export_csv)
        self.export_plot_button.clicked.connect(self._ask_export_plot)
        self.knob.currentIndexChanged.connect(self._show_explanation)
        self._show_explanation()
        self._draw_plot()
        self._update_buttons()

    def showEvent(self, event) -> None:
        if self.canvas is None:
            self._make_canvases()
        else:
            self._draw_stale()
        super().showEvent(event)

    def _draw_stale(self) -> None:
        """Draw the plot and the images if they wait to be (a hidden pane's or page's wait on)."""
        if self._plot_stale:
            self._draw_plot()
        if self._images_stale:
            self._draw_images()

    def changeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        """The plot and the images follow the window's theme (dark in high contrast) and text size."""
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:
            self._keep_two_status_lines()
            if self.canvas is not None and plot_theme.figure_dpi(self) != self._dpi:
                self._draw_images()
                self._draw_plot()
        if event.type() == QEvent.Type.PaletteChange and self.canvas is not None:
            dark = plot_theme.is_dark(self)
            if dark != self._dark:
                self._draw_plot()
                self._draw_images()

    def _keep_two_status_lines(self) -> None:
        """The status line keeps room for two lines, so that the finished sweep's two lines (its knees)
        do not shrink the plot: a new size is a full draw of it."""
        self.status.setMinimumHeight(2 * self.status.fontMetrics().lineSpacing())

    def _make_canvases(self) -> None:
        """Make the plot's and the images' figures and canvases, once (matplotlib loads here)."""
        if self.canvas is not None:
            return
        self.canvas = FigureImage()
        self.canvas.clicked.connect(self._on_click)
        self.canvas.resized.connect(self._draw_plot)
        self.canvas.drawn.connect(self._plot_drawn)
        self.canvas.failed.connect(lambda message: self.status.setText(f"The plot failed: {message}"))
        self._plot_box.layout().addWidget(self.canvas)
        self.canvas.show()  # now, not a turn later: whether it shows decides whether it is drawn
        self.image_canvas = FigureImage()
        self.image_canvas.resized.connect(self._draw_images)
        self.image_canvas.failed.connect(lambda message: self.status.setText(f"The images failed: {message}"))
        self._image_box.layout().addWidget(self.image_canvas)
        self.image_canvas.show()
        self._draw_images()
        self._draw_plot()

    @property
    def plot_figure(self):
        """The figure of the plot shown now (drawn off the GUI thread; read it only), or ``None``."""
        shown = self.canvas.shown if self.canvas is not None else None
        return shown.figure if shown is not None else None

    @property
    def image_figure(self):
        """The figure of the images shown beside the plot now (drawn off the GUI thread; read it only),
        or ``None``."""
        shown = self.image_canvas.shown if self.image_canvas is not None else None
        return shown.figure if shown is not None else None

    # -- inputs ---------------------------------------------------------------

    def set_scene(self, scene: Scene) -> None:
        """Sweep ``scene`` from now on (a running sweep is cancelled, found points are cleared)."""
        self.cancel()
        self._scene = scene
        self._reset()
        for i in range(1, self.knob.count()):
            reason = unavailable(self.knob.itemData(i), scene)
            item = self.knob.model().item(i)
            item.setEnabled(reason is None)
            item.setToolTip(reason or "")
        if not self.knob.model().item(self.knob.currentIndex()).isEnabled():
            self.knob.setCurrentIndex(0)
        self.status.setText("Pick a knob and press Run.")
        self._update_buttons()

    @property
    def scene(self) -> Scene | None:
        """The scene a sweep starts from (the last :meth:`set_scene`)."""
        return self._scene

    def _sweep_scene(self) -> Scene:
        cam = self._scene.camera
        width = min(cam.width, self.width_px.value())
        height = max(1, round(width * cam.height / cam.width))
        return replace(self._scene, camera=cam.replace(width=width, height=height))

    def _parameters(self) -> tuple:
        return (self.knob.currentData(), self.mode.currentData(), self.width_px.value(),
                self.reference_spp.value(), round(self.tolerance.value(), 6))

    # -- running --------------------------------------------------------------

    @property
    def running(self) -> bool:
        return self._runner.busy

    @property
    def finished(self) -> bool:
        """Every setting of the current sweep is done."""
        return self.sweep is not None and len(self._points) == len(self.sweep.settings)

    def run(self) -> None:
        """Start the sweep, or resume it if it was stopped with the same choices."""
        if self._scene is None or self.running:
            return
        if self.sweep is None or self._swept_with != self._parameters():
            self._reset()
            knob, mode, _, spp, tolerance = self._parameters()
            self.sweep = Sweep(self._sweep_scene(), (knob,), mode, tolerance, reference_spp=spp)
            self._swept_with = self._parameters()
        if not self.sweep.settings:
            self.status.setText("Nothing to sweep: " + "; ".join(f"{k}: {r}" for k, r in
                                                                 self.sweep.skipped.items()))
            return
        if not self._within_budget():
            return
        self._runner.submit(_sweep_job(self.sweep, self._sweep_lock))
        self.status.setText("Starting…")
        self._update_buttons()

    def _within_budget(self) -> bool:
        """Whether the sweep's estimated memory is within the budget; if not, the status says why."""
        cost = sweep_cost.estimate(self.sweep)
        cam = self.sweep.scene.camera
        over = budget.refusal(f"This sweep of {len(self.sweep.settings)} settings at {cam.width} × "
                              f"{cam.height}", cost, *budget.memory_limit(self.memory_limit))
        if over:
            self.status.setText(f"{over}. Not started: use a smaller width or fewer objects or triangles.")
            return False
        self._slow_note = (f" (the sweep: about {budget.format_seconds(cost.seconds)} in all)"
                           if cost.seconds > LONG_SWEEP_SECONDS else "")
        return True

    def cancel(self) -> None:
        """Stop the running sweep inside its current render, within a pixel or a triangle (Run resumes it)."""
        if self.running:
            self._runner.cancel()  # whatever the stopped run still reports is dropped
            self._draw_now()
            self.status.setText(f"Stopped after {len(self._points)} of {len(self.sweep.settings)} "
                                "settings; Run resumes.")
            self._update_buttons()

    def _reset(self) -> None:
        self._replot.stop()
        drawn = bool(self._points)  # else the empty plot is already shown
        self.sweep, self._swept_with = None, None
        self._points, self._knees, self.selected = {}, {}, None
        self.progress.setValue(0)
        if drawn:
            self._plot_stale = self._images_stale = True  # shown again, the pane draws them at once
            self._after_reset.start()

    def _on_event(self, event) -> None:
        if isinstance(event, Progress):
            self.progress.setValue(round(1000 * event.done / max(event.total, 1)))
            self.status.setText(event.what + self._slow_note)
        elif isinstance(event, Point):
            self._points[event.index] = event
            if self.selected is None:
                self.show_point(event.index)  # draws the plot too
            elif not self._replot.isActive():
                self._replot.start()
        elif isinstance(event, Knee):
            self._knees[event.knob] = event.index
            if not self._replot.isActive():
                self._replot.start()

    def _draw_now(self) -> None:
        """Draw what was found in full, now (a sweep ended or stopped)."""
        self._replot.stop()
        self._draw_plot()

    def _on_done(self, finished: bool) -> None:
        self._draw_now()
        if finished:
            self.progress.setValue(1000)
            skipped = "; ".join(f"{k} not swept: {r}" for k, r in self.sweep.skipped.items())
            knees = ", ".join(f"{k} {self._points[i].row.value}" for k, i in self._knees.items())
            self.status.setText(f"Done. Knees: {knees}." + (f"  ({skipped})" if skipped else ""))
        self._update_buttons()
        self.sweep_finished.emit(finished)

    def _on_failed(self, message: str) -> None:
        self._draw_now()
        self.status.setText(f"The sweep failed: {message}")
        self._update_buttons()

    def _update_buttons(self) -> None:
        self.progress.setVisible(self.running or bool(self._points))
        self.run_button.setEnabled(self._scene is not None and not self.running)
        resumable = self.sweep is not None and not self.finished and bool(self._points)
        self.run_button.setText("Resume" if resumable else "Run")
        self.cancel_button.setEnabled(self.running)
        self.export_csv_button.setEnabled(bool(self._points))
        self.export_plot_button.setEnabled(bool(self._points))

    def closeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        self.cancel()
        super().closeEvent(event)

    # -- what was found -------------------------------------------------------

    def rows(self) -> list:
        """The rows received so far, in setting order, knees marked."""
        return marked_rows(self._points, self._knees)

    def _draw_plot(self, quick: bool = False) -> None:
        """Ask for the points found so far to be drawn, off the GUI thread.  ``quick`` (while a sweep
        runs): the axes keep the places of the last full draw, when there are as many.  A hidden plot
        (a hidden pane, or the point's page shown) is drawn when it is shown."""
        if self.canvas is None:
            return  # drawn when the canvas is made
        self._plot_stale = not self.canvas.isVisible()
        if self._plot_stale:
            return  # drawn when shown (a lesson step resets the plot of a hidden tab)
        self._dark = plot_theme.is_dark(self)
        ratio = self.canvas.devicePixelRatioF()
        self.canvas.request(self._plot_drawing(self.canvas.width() * ratio, self.canvas.height() * ratio,
                                               plot_theme.figure_dpi(self) * ratio,
                                               self._layout if quick else None))

    def _plot_drawing(self, width: float, height: float, dpi: float, layout: list | None):
        """A function that draws the plot as it is now on a new figure, for any thread."""
        rows, indices, dark = self.rows(), sorted(self._points), self._dark
        selected = self._points[self.selected].row if self.selected in self._points else None

        def draw() -> Drawn:
            return cost_plot_process.drawn(width, height, dpi, rows, indices, dark, selected, layout)

        return draw

    def _plot_drawn(self, drawn: Drawn) -> None:
        """A new picture of the plot is shown: its lines answer clicks; a full one's places are kept."""
        self._lines = drawn.extra["lines"]
        if drawn.extra["layout"] is not None:
            self._layout = drawn.extra["layout"]
        self.plot_drawn.emit()

    def _on_click(self, x: float, y: float) -> None:
        """A press on the plot at (x, y), the shown figure's pixels: the point under it is shown, the
        nearest where several lie within reach (settings that cost about the same and err about as
        much, as the deepest rays of a depth sweep, sit a few pixels apart)."""
        from matplotlib.backend_bases import MouseEvent

        event = MouseEvent("button_press_event", self.plot_figure.canvas, x, y, button=1)
        nearest, distance = None, math.inf
        for line, indices in self._lines.items():
            hit, info = line.contains(event)
            if not hit:
                continue
            shown = line.get_transform().transform(line.get_xydata())
            for i in info["ind"]:
                away = math.hypot(shown[i][0] - x, shown[i][1] - y)
                if away < distance:
                    nearest, distance = indices[int(i)], away
        if nearest is not None:
            self.sheet.show_point_page()  # on a small pane the point has a page of its own
            self.show_point(nearest)

    def point_position(self, index: int) -> tuple[float, float]:
        """Where setting ``index``'s point is drawn on the plot canvas, in widget pixels (x right, y down)."""
        ax, x, y = point_position(self.plot_figure, self._points[index].row)
        return self.canvas.to_widget(*ax.transData.transform((x, y)))

    def show_point(self, index: int) -> None:
        """Show setting ``index``'s image, the reference and the error map side by side (drawn off the
        GUI thread: :attr:`image_figure` is that figure once drawn)."""
        self._make_canvases()
        point = self._points[index]
        self.selected = index
        self._draw_images()
        self._draw_plot()
        self._show_explanation(point.row.knob)
        self.point_selected.emit(index)

    def _draw_images(self) -> None:
        """Ask for the selected point's images to be drawn off the GUI thread (a hidden pane's when it
        is shown); with none selected the pane shows none."""
        if self.image_canvas is None:
            return  # drawn when the canvases are made
        point = self._points.get(self.selected)
        if point is None:
            self._images_stale = False
            self.image_canvas.clear()
            return
        self._images_stale = not self.image_canvas.isVisible()
        if self._images_stale:
            return
        reference = self.sweep.references[point.row.mode]
        self._dpi = plot_theme.figure_dpi(self)
        ratio = self.image_canvas.devicePixelRatioF()
        self.image_canvas.request(point_images_drawing(
            point, reference, self.image_canvas.width() * ratio, self.image_canvas.height() * ratio,
            self._dpi * ratio, plot_theme.is_dark(self)))

    def shown_images(self) -> list[np.ndarray]:
        """The arrays shown beside the plot now (setting, reference, error map, samples); none before
        the images are drawn."""
        figure = self.image_figure
        return [] if figure is None else [ax.images[0].get_array() for ax in figure.axes if ax.images]

    def _show_explanation(self, knob: str | None = None) -> None:
        name = knob if isinstance(knob, str) else self.knob.currentData()
        if name == "all":
            self.explanation.setText("<b>Every knob</b>: each curve is one setting swept with everything "
                                     "else at its default; the ringed point is its knee, the cheapest "
                                     "setting you cannot tell from the best.  Click a point to see it.")
        else:
            self.explanation.setText(f"<b>{KNOBS[name].title}</b>: {EXPLANATIONS[name]}")
        self._words.refit()

    # -- export ---------------------------------------------------------------

    def export_csv(self, path) -> None:
        """Write the rows found so far as CSV (atomically)."""
        cost_files.write_csv(self.rows(), path)

    def export_plot(self, path) -> None:
        """Write the plot as PNG or SVG, after the suffix (atomically)."""
        self._make_canvases()
        ratio = self.canvas.devicePixelRatioF()
        drawn = self._plot_drawing(self.canvas.width() * ratio, self.canvas.height() * ratio,
                                   plot_theme.figure_dpi(self) * ratio, None)()
        cost_files.save_figure(drawn.figure, path)

    def _ask_export_csv(self) -> None:
        path, _ = ask_save(self, "Export the sweep as CSV", "cost.csv", "CSV (*.csv)") or ("", "")
        if path:
            self._export(self.export_csv, path)

    def _ask_export_plot(self) -> None:
        path, _ = ask_save(self, "Export the plot", "cost.png", "PNG (*.png);;SVG (*.svg)") or ("", "")
        if path:
            self._export(self.export_plot, path)

    def _export(self, write, path) -> None:
        try:
            write(path)
        except (OSError, ValueError) as exc:
            self.status.setText(f"Cannot write {path}: {exc}")
            return
        self.status.setText(f"Wrote {path}")
