"""Controls that move the observer and change its lens.

The panel shows the model's :class:`core.camera.Camera` and, when the user
edits a control, asks the model for the camera they want.  It keeps no
camera of its own: it reads the model's at edit time, and shows whatever
camera the model has whenever it changes or refuses a request.  Number
boxes take the whole range a scene file allows (±1,000,000 scene units).
"""

from __future__ import annotations

from PySide6.QtCore import QSize, Qt
from PySide6.QtWidgets import (
    QCheckBox,
    QComboBox,
    QDoubleSpinBox,
    QFormLayout,
    QGroupBox,
    QHBoxLayout,
    QSizePolicy,
    QSlider,
    QVBoxLayout,
    QWidget,
)

from core.camera import PITCH_LIMIT_DEG, Camera
from core.files.scene_file import MAX_MAGNITUDE
from views.flow_layout import FlowLayout

RESOLUTIONS = [(160, 120), (320, 240), (480, 360), (640, 480), (960, 720)]


class _NumberBox(QDoubleSpinBox):
    """A number box as wide as a typical value, not as its extreme ones (±1,000,000 is allowed);
    at the least as wide as the value it shows, so that at a large text size the eye's three boxes
    share a narrow column (as wide as a typical value each, they widened the Controls past the dock,
    which cut them at text x2 on 1280 x 720)."""

    TYPICAL = "-8888.88"

    def __init__(self):
        super().__init__()
        # Minimum, the box's policy, makes a layout take the size hint as the least size.
        self.setSizePolicy(QSizePolicy.Policy.Preferred, self.sizePolicy().verticalPolicy())
        self.textChanged.connect(lambda _: self.updateGeometry())  # another least width

    def _narrowed(self, hint: QSize, text: str) -> QSize:
        fm = self.fontMetrics()
        widest = max(fm.horizontalAdvance(self.textFromValue(v)) for v in (self.minimum(), self.maximum()))
        extra = widest - fm.horizontalAdvance(text)
        return QSize(hint.width() - max(0, extra), hint.height())

    def sizeHint(self) -> QSize:
        return self._narrowed(super().sizeHint(), self.TYPICAL)

    def minimumSizeHint(self) -> QSize:
        return self._narrowed(super().minimumSizeHint(), self.text() + " ")


def _spin(lo, hi, step, decimals, suffix="", tip=""):
    box = _NumberBox()
    box.setRange(lo, hi)
    box.setSingleStep(step)
    box.setDecimals(decimals)
    box.setSuffix(suffix)
    box.setKeyboardTracking(False)
    box.setToolTip(tip)
    return box


class _AngleControl(QWidget):
    """A slider and a spin box showing the same angle in degrees."""

    def __init__(self, lo, hi, tip):
        super().__init__()
        self.slider = QSlider(Qt.Orientation.Horizontal)
        self.slider.setRange(lo, hi)
        self.slider.setToolTip(tip)
        self.spin = _spin(lo, hi, 1.0, 1, "°", tip)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.slider, 3)
        layout.addWidget(self.spin, 2)
        self.slider.valueChanged.connect(lambda v: self.spin.setValue(float(v)))

    def set_value(self, value: float) -> None:
        for w in (self.slider, self.spin):
            w.blockSignals(True)
        self.slider.setValue(round(value))
        self.spin.setValue(value)
        for w in (self.slider, self.spin):
            w.blockSignals(False)


class CameraPanel(QWidget):
    """Eye position, orbit around the target, viewing angle, planes, projection.

    ``model`` is the window's state (:class:`app.window.state.SceneModel` or any
    object with its ``camera``, ``set_camera`` and signals).
    """

    def __init__(self, model, parent: QWidget | None = None):
        super().__init__(parent)
        self.model = model
        big = MAX_MAGNITUDE
        self.eye = [_spin(-big, big, 0.25, 2, tip=f"Eye {a}: the observer's position")
                    for a in "xyz"]
        self.yaw = _AngleControl(-180, 180, "Yaw: walk the observer around the target (←/→)")
        limit = round(PITCH_LIMIT_DEG)
        self.pitch = _AngleControl(-limit, limit, "Pitch: raise or lower the observer (↑/↓)")
        self.distance = _spin(0.01, 2 * big, 0.5, 2, tip="Distance from the eye to the target (+/−)")
        self.fov = _AngleControl(1, 179, "Viewing angle α: the frustum's vertical opening")
        self.near = _spin(0.01, 2 * big, 0.1, 2, tip="Front (near) plane: nothing closer is drawn")
        self.far = _spin(0.02, 4 * big, 1.0, 2, tip="End (far) plane: nothing farther is drawn")
        self.projection = QComboBox()
        self.projection.addItems(["perspective", "orthographic"])
        self.projection.setToolTip("Perspective: rays meet at the eye.  "
                                   "Orthographic: parallel rays (P toggles)")
        self.ortho_height = _spin(0.01, 2 * big, 0.5, 2, tip="Height of the orthographic view volume")
        self.resolution = QComboBox()
        self.resolution.addItems([f"{w} × {h}" for w, h in RESOLUTIONS])
        self.resolution.setToolTip("Image size in pixels: more pixels, more rays, more time")

        observer = QGroupBox("Observer")
        form = QFormLayout(observer)
        form.setRowWrapPolicy(QFormLayout.RowWrapPolicy.WrapLongRows)  # narrow at large text: label above
        eye_row = QWidget()  # one line, or more in a narrow column at a large text size
        eye_flow = FlowLayout(eye_row)
        eye_flow.setSpacing(6)
        for box in self.eye:
            eye_flow.addWidget(box)
        form.addRow("Eye x, y, z", eye_row)
        form.addRow("Yaw", self.yaw)
        form.addRow("Pitch", self.pitch)
        form.addRow("Distance", self.distance)
        lens = QGroupBox("Lens and frustum")
        form2 = QFormLayout(lens)
        form2.setRowWrapPolicy(QFormLayout.RowWrapPolicy.WrapLongRows)
        form2.addRow("Viewing angle α", self.fov)
        form2.addRow("Near plane", self.near)
        form2.addRow("Far plane", self.far)
        form2.addRow("Projection", self.projection)
        form2.addRow("Ortho height", self.ortho_height)
        form2.addRow("Image size", self.resolution)
        # Its name as the row's label: a narrow column puts it above the box (one line of check box
        # text was wider than the Controls at text x2 on 1280 x 720).
        self.frustum_labels = QCheckBox("fill and label them")
        self.frustum_labels.setToolTip("Show the frustum's front (near) and end (far) planes filled in the "
                                       "3D pane, with their distances")
        self.frustum_labels.toggled.connect(lambda on: model.set_overlay("frustum", on))
        form2.addRow("Near and far planes", self.frustum_labels)
        layout = QVBoxLayout(self)
        layout.addWidget(observer)
        layout.addWidget(lens)
        layout.addStretch(1)

        for box in self.eye:
            box.valueChanged.connect(self._eye_edited)
        cam = lambda: self.model.camera  # noqa: E731 - read the camera in force at edit time
        self.yaw.spin.valueChanged.connect(lambda v: self._orbit(v, cam().pitch_deg, cam().distance))
        self.pitch.spin.valueChanged.connect(lambda v: self._orbit(cam().yaw_deg, v, cam().distance))
        self.distance.valueChanged.connect(lambda v: self._orbit(cam().yaw_deg, cam().pitch_deg, v))
        self.fov.spin.valueChanged.connect(lambda v: self._request(fov_y_deg=v))
        self.near.valueChanged.connect(lambda v: self._request(near=v))
        self.far.valueChanged.connect(lambda v: self._request(far=v))
        self.projection.currentTextChanged.connect(lambda v: self._request(projection=v))
        self.ortho_height.valueChanged.connect(lambda v: self._request(ortho_height=v))
        self.resolution.currentIndexChanged.connect(self._resolution_edited)
        model.camera_changed.connect(self.set_camera)
        model.camera_refused.connect(lambda _: self.set_camera(model.camera))
        model.scene_changed.connect(lambda scene: self.set_camera(scene.camera))
        model.overlays_changed.connect(self._show_overlays)
        self.set_camera(model.camera)

    @property
    def _spins(self):
        return [*self.eye, self.distance, self.near, self.far, self.ortho_height,
                self.projection, self.resolution]

    def set_camera(self, camera: Camera) -> None:
        """Show ``camera`` in every control without asking for a change."""
        for w in self._spins:
            w.blockSignals(True)
        for box, value in zip(self.eye, camera.eye, strict=True):
            box.setValue(value)
        self.distance.setValue(camera.distance)
        self.near.setValue(camera.near)
        self.far.setValue(camera.far)
        self.ortho_height.setValue(camera.ortho_height)
        self.projection.setCurrentText(camera.projection)
        size = (camera.width, camera.height)
        # A size not in the list shows as it is, and picking any listed one changes it.
        self.resolution.setPlaceholderText(f"{camera.width} × {camera.height}")
        self.resolution.setCurrentIndex(RESOLUTIONS.index(size) if size in RESOLUTIONS else -1)
        for w in self._spins:
            w.blockSignals(False)
        self.yaw.set_value(camera.yaw_deg)
        self.pitch.set_value(camera.pitch_deg)
        self.fov.set_value(camera.fov_y_deg)
        self.ortho_height.setEnabled(camera.projection == "orthographic")
        self.fov.setEnabled(camera.projection == "perspective")

    def _show_overlays(self, shown) -> None:
        self.frustum_labels.blockSignals(True)
        self.frustum_labels.setChecked("frustum" in shown)
        self.frustum_labels.blockSignals(False)

    def _request(self, **changes) -> None:
        self.model.set_camera(self.model.camera.replace(**changes))

    def _eye_edited(self) -> None:
        self._request(eye=[box.value() for box in self.eye])

    def _orbit(self, yaw_deg: float, pitch_deg: float, distance: float) -> None:
        """Only the control the user touched changes; the others keep full precision."""
        self.model.set_camera(self.model.camera.orbit(yaw_deg, pitch_deg, distance))

    def _resolution_edited(self, index: int) -> None:
        width, height = RESOLUTIONS[index]
        self._request(width=width, height=height)
