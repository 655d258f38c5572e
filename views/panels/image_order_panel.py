"""The image-order panel: the traced image, the effects plan, and one pixel's ray tree.

Every pixel is computed on its own: a ray from the eye through the pixel,
its first hit, shadow rays toward the lights, and (in ray tracing) reflected
and refracted rays.  Clicking a pixel traces it again with every ray kept,
shows the tree in the 3D pane and lists it here with the colours combined
from the last hits back to the first, under one sentence that says what
decided the pixel (:mod:`core.pixel_verdict`).

A chosen heat map is coloured and laid over the traced image on a worker thread
(a lesson step that turns it on held the window for a quarter of a second doing
it on the GUI thread); the window only paints it.  While an exercise asks what the map would
show, the traced image is shown without it (:meth:`ImageOrderPanel.withhold_heat`).
"""

from __future__ import annotations

import numpy as np
from PySide6.QtCore import QEvent, Qt, QTimer, Signal
from PySide6.QtGui import QFont
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QFormLayout,
    QHBoxLayout,
    QLabel,
    QPlainTextEdit,
    QSpinBox,
    QSplitter,
    QTabWidget,
    QVBoxLayout,
    QWidget,
)

from core.accuracy.supersampling import AdaptiveImage
from core.image_order.flat_layout import HEAT_BOUNDS_TESTS, HEAT_PRIM_TESTS
from core.image_order.ray_tracing import TraceSettings
from core.image_order.ray_tree import RayNode
from core.in_words import counted
from core.pixel_verdict import trace_verdict
from core.scene import Scene
from views.images.color_scale import ColorScale, heat_over
from views.images.image_view import DisplayImage, ImageView
from views.jobs import JobRunner, own_thread
from views.panels.panel_layout import pictures_over_details
from views.panels.raytree_view import KIND_COLORS, RayKindLegend, RayTreeWidget
from views.panels.side_column import SideColumn
from views.text.verdict_label import VerdictLabel
from views.text.worked_math import WorkedMath

#: Rows of the ray tree a lesson that points at a ray makes room for (the image gives up height),
#: and the share of the panel's height the image keeps all the same.
TREE_ROWS = 4
IMAGE_SHARE = 0.4
MODES = [("raytrace", "Ray tracing"), ("raycast", "Ray casting")]
HEATS = [("off", "Off"), ("prim", "Primitive tests"), ("bounds", "Box and sphere tests")]
HEAT_INDEX = {"prim": HEAT_PRIM_TESTS, "bounds": HEAT_BOUNDS_TESTS}
#: The heat map offered while adaptive supersampling is on.
SAMPLES_HEAT = ("samples", "Samples per pixel")
ACCELS = [("bvh", "BVH"), ("grid+spheres", "Grid + spheres"), ("grid", "Grid of cuboids"),
          ("spheres", "Bounding spheres"), ("none", "None")]


def accel_words(method: str) -> str:
    """An acceleration method as a caption says it: "BVH", "grid of cuboids", "no acceleration"."""
    if method == "none":
        return "no acceleration"
    return "BVH" if method == "bvh" else dict(ACCELS)[method].lower()


def _combo(items, tip):
    box = QComboBox()
    for key, text in items:
        box.addItem(text, key)
    box.setToolTip(tip)
    return box


class ImageOrderPanel(QWidget):
    """Settings, traced image, effects plan with ray counts, and the picked pixel's ray tree.

    The controls write to the model (``model.set_trace_settings``,
    ``model.set_overlay``, ``model.set_ray_pixel``) and show what the model holds.
    Adaptive supersampling is this pane's own setting (:attr:`adaptive_threshold`);
    while it is on, the heat map may show its samples per pixel.

    Signals
    -------
    adaptive_changed() : adaptive supersampling was switched on or off, or its threshold changed.
    """

    adaptive_changed = Signal()

    def __init__(self, model, parent: QWidget | None = None):
        super().__init__(parent)
        self.model = model
        self.mode = _combo(MODES, "Ray casting stops at the first hit and its shadow rays; ray tracing "
                                  "follows reflected and refracted rays too")
        self.depth = QSpinBox()
        self.depth.setRange(0, 12)
        self.depth.setValue(5)
        self.depth.setToolTip("Deepest reflection / refraction followed (the ray tree's height)")
        self.min_weight = QDoubleSpinBox()
        self.min_weight.setRange(0.0, 0.5)
        self.min_weight.setDecimals(3)
        self.min_weight.setSingleStep(0.005)
        self.min_weight.setValue(0.01)
        self.min_weight.setToolTip("A ray contributing less than this to the pixel is not traced")
        self.accel = _combo(ACCELS, "How a ray finds the objects it may hit: test every object, bounding "
                                    "spheres first, a grid of cuboids walked along the ray, or a bounding "
                                    "volume hierarchy (BVH).  The image is the same, the work differs")
        self.offset = _combo([("scaled", "Scaled"), ("fixed", "Fixed ε")],
                             "How far secondary rays start off the surface; a fixed tiny ε far from "
                             "the origin gives shadow acne")
        self.epsilon = QDoubleSpinBox()
        self.epsilon.setDecimals(8)
        self.epsilon.setRange(0.0, 1.0)
        self.epsilon.setSingleStep(1e-4)
        self.epsilon.setValue(1e-4)
        self.epsilon.setToolTip("The fixed offset ε (used with 'Fixed ε')")
        self.heat = _combo(HEATS, "Colour each pixel by the intersection tests its rays cost (all of them: "
                                  "primary, shadow, reflected, refracted), over the traced image; change "
                                  "the acceleration to see where each method spends its tests.  Box tests "
                                  "are the BVH's boxes and the grid's cells walked")
        self.heat.currentIndexChanged.connect(self._show_heat)
        self.adaptive = QCheckBox("Adaptive supersampling")
        self.adaptive.setToolTip("Whitted's adaptive supersampling: trace the corners of every pixel; only "
                                 "the pixels whose corners differ by more than the threshold get 4 × 4 "
                                 "samples.  The heat map can then show the samples each pixel took")
        self.threshold = QDoubleSpinBox()
        self.threshold.setRange(0.0, 1.0)
        self.threshold.setDecimals(3)
        self.threshold.setSingleStep(0.01)
        self.threshold.setValue(0.05)
        self.threshold.setEnabled(False)
        self.threshold.setToolTip("Largest difference (any channel, linear RGB from 0 to 1) a pixel's four "
                                  "corners may show before the pixel gets 4 × 4 samples")
        self.adaptive.toggled.connect(self._adaptive_toggled)
        self.threshold.valueChanged.connect(lambda _: self.adaptive_changed.emit())
        self._adaptive: AdaptiveImage | None = None  # the adaptive render shown, or None
        self.heat_scale = ColorScale("Heat map colour scale: the map's darkest colour means no test, its "
                                     "brightest the most any pixel of this image took")
        self.heat_scale.hide()
        self.heat_withheld = QLabel()  # says why the heat map chosen is not shown (withhold_heat)
        self.heat_withheld.setWordWrap(True)
        self.heat_withheld.hide()
        self.heat_withheld.installEventFilter(self)
        self._traced: DisplayImage | None = None  # the traced image, under the heat map
        self._heats = JobRunner(self, own_thread(self))  # lays the heat map over it off the GUI thread
        self._heats.finished.connect(self._paint_heat)
        self._heat: np.ndarray | None = None  # (H, W, 2) its pixels' tests, or None
        self.show_spheres = QCheckBox("bounding spheres")
        self.show_grid = QCheckBox("grid cells")
        self.show_walk = QCheckBox("cells the ray walks")
        self._overlay_boxes = {"spheres": self.show_spheres, "grid": self.show_grid,
                               "walk": self.show_walk}
        for name, box in self._overlay_boxes.items():
            box.setToolTip("Show in the 3D pane")
            box.toggled.connect(lambda on, name=name: model.set_overlay(name, on))
        self.show_walk.setToolTip("Show in the 3D pane the grid cells the picked pixel's primary ray "
                                  "passes through")

        form_box = QWidget()
        form = QFormLayout(form_box)
        form.setContentsMargins(0, 0, 0, 0)
        form.setRowWrapPolicy(QFormLayout.RowWrapPolicy.WrapLongRows)  # narrow: labels above the fields
        for label, widget in [("Method", self.mode), ("Acceleration", self.accel), ("Max depth", self.depth),
                              ("Min weight", self.min_weight), ("Ray offset", self.offset),
                              ("ε", self.epsilon), ("", self.adaptive), ("Threshold", self.threshold),
                              ("Heat map", self.heat)]:
            form.addRow(label, widget)
        form.addRow(self.heat_scale)  # under its choice: in view at 1280 x 720, where the column scrolls
        form.addRow(self.heat_withheld)
        form.addRow(QLabel("Show in 3D:"))
        for box in (self.show_spheres, self.show_grid, self.show_walk):
            form.addRow(box)

        self.image = ImageView()
        self.rays = QLabel()
        self.rays.setTextFormat(Qt.TextFormat.RichText)
        self.plan = QLabel()
        self.plan.setWordWrap(True)
        self.plan.setTextFormat(Qt.TextFormat.RichText)
        self.plan.setAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        self.tree = RayTreeWidget()
        self.explanation = QPlainTextEdit()
        self.explanation.setReadOnly(True)
        font = QFont("monospace")
        font.setStyleHint(QFont.StyleHint.Monospace)
        self.explanation.setFont(font)
        self.explanation.setPlaceholderText(
            "Click a pixel to trace it again with every ray kept: its ray tree appears in the "
            "3D pane and here, with the colours computed from the last hits back to the first.")
        tree_page = QWidget()
        tl = QVBoxLayout(tree_page)
        tl.setContentsMargins(0, 0, 0, 0)
        self.verdict = VerdictLabel()  # the tree's caption: what decided the pixel, its figures on hover
        tl.addWidget(self.verdict)
        self.beside = QSplitter(Qt.Orientation.Horizontal)  # side by side: both get the page's height
        self.beside.addWidget(self.tree)
        self.beside.addWidget(self.explanation)
        self.beside.setStretchFactor(0, 3)
        self.beside.setStretchFactor(1, 2)
        tl.addWidget(self.beside, 1)
        self.tree.crowded_changed.connect(self._place_second_stage)
        self.worked_math = WorkedMath()
        self.ray_kind: str | None = None  # the kind of ray to select in each new tree (a lesson's)
        self.details = QTabWidget()
        self.details.addTab(tree_page, "Ray tree")
        self.details.addTab(self.worked_math, "Worked math")
        self.details.addTab(self.plan, "Effects plan")
        # The image beside its settings, the picked pixel's details under both: the image
        # keeps the pane's height, the tables get several rows.
        top = QWidget()
        top_layout = QHBoxLayout(top)
        top_layout.setContentsMargins(0, 0, 0, 0)
        top_layout.addWidget(self.image, 1)
        self.column = SideColumn([form_box, self.rays, QLabel("<b>Ray colours</b>"),
                                  RayKindLegend(per_line=3)])
        top_layout.addWidget(self.column)
        self.split = pictures_over_details(self, top, self.details)
        self._room_for_tree = False  # asked by a lesson, kept until the user drags the divider
        self.split.splitterMoved.connect(self._leave_room_as_dragged)
        self.tree.viewport().installEventFilter(self)

        for w in (self.mode, self.accel, self.offset):
            w.currentIndexChanged.connect(self._settings_edited)
        for w in (self.depth, self.min_weight, self.epsilon):
            w.valueChanged.connect(self._settings_edited)
        self.image.pixel_clicked.connect(lambda x, y: model.set_ray_pixel((x, y)))
        model.trace_settings_changed.connect(self.show_settings)
        model.overlays_changed.connect(self._show_overlays)
        model.ray_pixel_changed.connect(self._ray_pixel_changed)
        self.show_settings(model.trace_settings)

    @property
    def _controls(self):
        return [self.mode, self.accel, self.offset, self.depth, self.min_weight, self.epsilon]

    def _settings_edited(self) -> None:
        self.model.set_trace_settings(TraceSettings(
            mode=self.mode.currentData(), max_depth=self.depth.value(),
            min_weight=self.min_weight.value(), accel=self.accel.currentData(),
            offset=self.offset.currentData(), epsilon=self.epsilon.value()))

    def show_ray_tree(self) -> None:
        """Bring the ray tree forward with room for ``TREE_ROWS`` of its rows.

        In a small window or with large text the image above takes most of the
        height and the tree shows a row or two; then the image gives up what the
        rows need, but keeps ``IMAGE_SHARE`` of the height.  The panel may just
        have been shown and not yet laid out, so the room is made again whenever
        the tree's size changes (a step's panes appearing, the window resized),
        until the user drags the divider: then the user's choice stands.
        """
        self.details.setCurrentIndex(0)
        self._room_for_tree = True
        self._make_room_for_tree()

    def _make_room_for_tree(self) -> None:
        row = max(self.tree.sizeHintForRow(0), self.tree.fontMetrics().lineSpacing() + 6)
        short = TREE_ROWS * row - self.tree.viewport().height()
        image, details = self.split.sizes()
        give = min(short, image - round(IMAGE_SHARE * (image + details)))
        if give > 0:
            self.split.setSizes([image - give, details + give])

    def _place_second_stage(self, crowded: bool) -> None:
        """The second stage beside the tree, or in a tab of its own when the tree's columns need the
        page's width (at text x2 on 1280 x 720 they were cut beside it)."""
        if crowded and self.details.indexOf(self.explanation) < 0:
            self.details.insertTab(1, self.explanation, "Second stage")
        elif not crowded and self.explanation.parentWidget() is not self.beside:
            shown = self.details.currentWidget() is self.explanation
            self.beside.addWidget(self.explanation)  # out of the tabs
            self.beside.setSizes([3 * self.beside.width() // 5, 2 * self.beside.width() // 5])
            if shown:
                self.details.setCurrentIndex(0)
        self.tree.widen_soon()

    def _leave_room_as_dragged(self) -> None:
        self._room_for_tree = False

    def _fit_verdict(self) -> None:
        """Give the verdict over the tree the lines the tree can spare above its rays' rows, up to
        ``TREE_ROWS`` of them: whole where there is room (at x2 on 1920x1080), on fewer lines ending in
        "…" where not (presenting on a 1280 x 720 projector, a ray cast with one shadow ray left two
        rows' room empty under a verdict cut to one line)."""
        row = max(self.tree.sizeHintForRow(0), self.tree.fontMetrics().lineSpacing() + 6)
        self.verdict.share_room(self.tree, max(1, min(self.tree.row_count(), TREE_ROWS)) * row)

    def eventFilter(self, watched, event) -> bool:
        if watched is self.heat_withheld and event.type() in (QEvent.Type.Show, QEvent.Type.Resize):
            # Shown, and laid out: into the column's view (at x2 it came where the view ends).
            QTimer.singleShot(0, self, lambda: self.column.ensureWidgetVisible(self.heat_withheld, 0, 0))
        if event.type() == QEvent.Type.Resize and watched is self.tree.viewport():
            if self._room_for_tree:
                self._make_room_for_tree()
            self._fit_verdict()
        return super().eventFilter(watched, event)

    def show_settings(self, settings: TraceSettings) -> None:
        """Show ``settings`` in the controls without writing them back."""
        for w in self._controls:
            w.blockSignals(True)
        self.mode.setCurrentIndex(self.mode.findData(settings.mode))
        self.accel.setCurrentIndex(self.accel.findData(settings.accel))
        self.offset.setCurrentIndex(self.offset.findData(settings.offset))
        self.depth.setValue(settings.max_depth)
        self.min_weight.setValue(settings.min_weight)
        self.epsilon.setValue(settings.epsilon)
        for w in self._controls:
            w.blockSignals(False)
        self.epsilon.setEnabled(settings.offset == "fixed")
        self.depth.setEnabled(settings.mode == "raytrace")

    @property
    def adaptive_threshold(self) -> float | None:
        """Adaptive supersampling's threshold (linear RGB), ``None`` while it is off."""
        return self.threshold.value() if self.adaptive.isChecked() else None

    def _adaptive_toggled(self, on: bool) -> None:
        """Offer the samples-per-pixel heat map only while adaptive supersampling is on."""
        self.threshold.setEnabled(on)
        index = self.heat.findData(SAMPLES_HEAT[0])
        if on and index < 0:
            self.heat.addItem(SAMPLES_HEAT[1], SAMPLES_HEAT[0])
        elif not on and index >= 0:
            if self.heat.currentIndex() == index:
                self.heat.setCurrentIndex(self.heat.findData("off"))
            self.heat.removeItem(index)
        self.adaptive_changed.emit()

    def _show_overlays(self, shown) -> None:
        for name, box in self._overlay_boxes.items():
            box.blockSignals(True)
            box.setChecked(name in shown)
            box.blockSignals(False)

    def _ray_pixel_changed(self, pixel) -> None:
        self.image.set_picked(pixel)
        if pixel is None:
            self.tree.clear()
            self.verdict.show_verdict(None)
            self.explanation.clear()
            self.worked_math.clear()

    def show_stats(self, stats: dict) -> None:
        """The effects plan and the rays actually traced, by kind."""
        rays = stats["rays"]
        chips = "<br>".join(
            f'<span style="background:{KIND_COLORS[k]}; color:black">&nbsp;{k} {rays[k]:,}&nbsp;</span>'
            for k in KIND_COLORS)
        accel = stats["accel"]
        reasons = "<br>".join(f"• {r}" for r in stats["plan"]["reasons"])
        self.rays.setText(
            f"<b>Rays traced</b><br>{chips}<br>"
            f"{accel['tests_per_ray']:.1f} tests a ray"
            + (f"<br>{accel['cells_per_ray']:.1f} grid cells a ray" if accel["cells_per_ray"] else ""))
        self.plan.setText(f"<b>What this scene calls for</b> — only these effects are simulated:"
                          f"<br>{reasons}")

    def show_traced(self, image: DisplayImage, heat: np.ndarray | None = None,
                    adaptive: AdaptiveImage | None = None) -> None:
        """Show the traced ``image`` (or a part of it), with its pixels' tests ``heat`` (H, W, 2)
        when the whole image came with them, and ``adaptive``, the adaptive supersampling that
        made ``image`` when it is on: the heat map is laid over it if one is chosen."""
        self._traced, self._heat, self._adaptive = image, heat, adaptive
        self._show_heat()

    def _heat_counts(self, kind: str) -> np.ndarray | None:
        if kind == SAMPLES_HEAT[0]:
            return None if self._adaptive is None else self._adaptive.samples
        return None if kind == "off" or self._heat is None else self._heat[..., HEAT_INDEX[kind]]

    @property
    def pending(self) -> bool:
        """The chosen heat map is being laid over the traced image on a worker."""
        return self._heats.busy

    def withhold_heat(self, why: str) -> None:
        """Show the traced image without the heat map chosen, and ``why`` in its place (an exercise
        waiting for its answer asks what the map would show), scrolled into the settings' view;
        ``""``: show the map again.  Told again what it was told (each step, each tab brought
        forward), it changes nothing: the map is not laid over the image a second time."""
        if why == self.heat_withheld.text():
            return
        self.heat_withheld.setText(why)
        self._show_heat()

    def _show_heat(self) -> None:
        kind = self.heat.currentData()
        withheld = bool(self.heat_withheld.text()) and kind != "off"
        self.heat_withheld.setVisible(withheld)
        counts = None if withheld else self._heat_counts(kind)
        if self._traced is None or counts is None:
            self._heats.cancel()
            self.heat_scale.setVisible(False)
            if self._traced is not None:
                self.image.set_image(self._traced)
            return
        what, traced = self.heat.currentText().lower(), self._traced
        self._heats.submit(lambda cancelled, progress: (kind, heat_over(counts, what, traced.rgb,
                                                                          f"heat map: {what}")))

    def _paint_heat(self, shown: tuple) -> None:
        kind, over = shown
        if kind != self.heat.currentData() or self.heat_withheld.text():
            return  # laid over before another map was chosen, or the map was withheld
        heat = over.heat
        self.image.set_image(over.image)
        if kind == SAMPLES_HEAT[0]:
            a = self._adaptive
            units = (f"samples a pixel, 1 where its corners agree; {int(a.refined.sum()):,} pixels refined, "
                     f"{a.traced:,} rays traced")
        else:
            units = (f"{heat.what} a pixel; {heat.total:,} in all, {heat.mean:.1f} a pixel "
                     f"({self.accel.currentText()})")
            if self._adaptive is not None:
                units += "; of the rays through the pixel centres, before adaptive supersampling"
        self.heat_scale.set_scale(over.colorbar, "0", f"{heat.top:,}", units)
        self.heat_scale.setVisible(True)

    def show_tree(self, x: int, y: int, root: RayNode, scene: Scene) -> None:
        """Pixel ``(x, y)``'s ray tree ``root``, traced in ``scene``, and the worked math of its first hit."""
        self.image.set_picked((x, y))
        n = sum(1 for node in root.walk() if node.traced)
        self.verdict.show_verdict(trace_verdict(root, scene, self.model.trace_settings.mode, x, y),
                                  f"Ray tree of pixel ({x}, {y}): {counted(n, 'ray')} traced; pixel colour "
                                  f"({', '.join(f'{c:.3f}' for c in root.pixel_color)})")
        self.tree.set_tree(root)
        self._fit_verdict()  # the lines its rows leave
        self.worked_math.show_ray(scene, root)
        self.tree.select_kind(self.ray_kind)
        self.explanation.setPlainText(
            "Second stage: colours from the last hits back to the first\n"
            + "\n".join(root.explain()))
