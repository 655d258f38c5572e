"""The scene editor's panel: a tree of the scene's objects and lights, and the selected one's fields.

The tree lists the objects and the lights by name, and the background; the
item selected there (or by a click in the 3D pane) is the model's
``selection``.  Under the tree, the property panel shows that item's fields as
the scene file has them: an object's type parameters (centre, radius, size,
segments, ...) and its material, a light's position, colour and intensity,
the background's colour.

The panel keeps no copy of the scene: it shows the model's, and when the user
finishes typing in a field (Enter, or leaving it) it asks for the change with
``field_edited(item, key, value)``, the value read as the file would read it
(``0.5`` a number, ``[1, 0, 0]`` a list, anything else text), so that the
editor can check it exactly as the loader checks a file.  A refused value is
answered with :meth:`SceneTreePanel.show_problem`: the loader's message in red
beside the field, the typed text left for correcting.

Colours are linear RGB in [0, 1] (see :mod:`core.srgb`); the colour dialog
works in sRGB, as screens do, and converts.
"""

from __future__ import annotations

import html
import json

import numpy as np
from PySide6.QtCore import QEvent, Qt, QTimer, Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QColorDialog,
    QFormLayout,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QPushButton,
    QScrollArea,
    QSizePolicy,
    QSplitter,
    QToolButton,
    QTreeWidget,
    QTreeWidgetItem,
    QVBoxLayout,
    QWidget,
)

from core import checked_edits, shapes
from core.in_words import counted
from core.scene import Mesh
from core.srgb import linear_to_srgb, srgb_to_linear

PROBLEM_COLOR = "#ff6b6b"
ITEM_ROLE = Qt.ItemDataRole.UserRole
BUTTONS_PER_ROW = 2
"""Buttons under the tree, per row."""

LABELS = {
    "name": "name", "center": "centre", "base_center": "base centre", "position": "position",
    "radius": "radius", "size": "size", "base_size": "base size", "height": "height",
    "segments": "segments", "rings": "rings", "notch": "notch", "intensity": "intensity",
    "color": "colour", "material.color": "colour", "material.opacity": "opacity",
    "material.reflectivity": "reflectivity", "material.transparency": "transparency",
    "material.ior": "refractive index", "material.ambient": "ambient k_a",
    "material.diffuse": "diffuse k_d", "material.specular": "specular k_s",
    "material.shininess": "shininess n",
}
"""How each field of the scene file is called in the panel and in the edits' names."""

MATERIAL_TIPS = {
    "color": "surface colour, linear RGB, each in [0, 1]",
    "opacity": "the lecture's α_s for blending c0 = α_s·c_s + (1 − α_s)·c_d; 1 is opaque; in [0, 1]",
    "reflectivity": "fraction of light mirrored (ray tracing), in [0, 1]",
    "transparency": "fraction of light refracted through (ray tracing), in [0, 1]",
    "ior": "index of refraction n of Snell's law, >= 1",
    "ambient": "Phong coefficient k_a, in [0, 1]",
    "diffuse": "Phong coefficient k_d, in [0, 1]",
    "specular": "Phong coefficient k_s, in [0, 1]",
    "shininess": "Phong exponent n (larger: smaller highlight), > 0",
}
KIND_TIPS = {"point": "scene units", "size3": "x, y, z, each > 0", "size2": "x, z, each > 0",
             "length": "scene units, > 0"}
COMPONENTS = {"point": "xyz", "mesh position": "xyz", "size3": "xyz", "size2": "xz", "color": "rgb"}


def label(key: str) -> str:
    """The panel's word for the file field ``key`` (``"material.color"`` -> ``"colour"``)."""
    return LABELS.get(key, key.rsplit(".", 1)[-1].replace("_", " "))


def read_text(text: str):
    """A field's text as the scene file would hold it: a JSON value (number, list, ...) or the text."""
    try:
        return json.loads(text.strip())
    except ValueError:
        return text.strip()


def show_value(value) -> str:
    """A number (or text) as a field shows it: whole numbers without a point, others to 10 digits."""
    if isinstance(value, bool) or not isinstance(value, (int, float)):
        return str(value)
    return str(value) if isinstance(value, int) else f"{value:.10g}"


class _Field(QWidget):
    """One field of the form: one or more line edits, a red line for the loader's problem.

    Signals
    -------
    edited(object value) : the user finished changing it (Enter or leaving a box).
    """

    edited = Signal(object)

    def __init__(self, components: str = "", tip: str = ""):
        super().__init__()
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.setSpacing(3)
        self.boxes: list[QLineEdit] = []
        self._set: list = []  # the value given (set_value), component by component
        for c in components or [None]:
            if c is not None:
                layout.addWidget(QLabel(c))
            box = QLineEdit()
            box.setToolTip(tip)
            box.setMinimumWidth(44)
            box.editingFinished.connect(self._finished)
            layout.addWidget(box, 1)
            self.boxes.append(box)
        self.vector = bool(components)
        self.problem = QLabel()
        self.problem.setWordWrap(True)
        self.problem.setStyleSheet(f"color: {PROBLEM_COLOR};")
        self.problem.setVisible(False)

    def set_value(self, value) -> None:
        values = value if self.vector else [value]
        self._set = list(values)  # as given: a box shows 10 digits, an unedited one keeps them all
        for box, v in zip(self.boxes, values, strict=False):
            box.setText(show_value(v))  # also clears "modified"
            box.setCursorPosition(0)
        self.show_problem("")

    def value(self):
        """The field's value: what was typed in the boxes the user changed, the value given for the
        others (editing y of a centre leaves x as it was, not rounded to what its box shows)."""
        values = [self._set[k] if k < len(self._set) and not box.isModified() else read_text(box.text())
                  for k, box in enumerate(self.boxes)]
        return values if self.vector else values[0]

    def show_problem(self, text: str) -> None:
        self.problem.setText(text)
        self.problem.setVisible(bool(text))

    def _finished(self) -> None:
        if any(b.isModified() for b in self.boxes):
            value = self.value()
            for b in self.boxes:
                b.setModified(False)
            self.edited.emit(value)


class _NameField(_Field):
    def value(self):
        return self.boxes[0].text()


class _ColorField(_Field):
    """A colour: a swatch that opens the colour dialog, and its three linear components."""

    def __init__(self, tip: str, title: str):
        super().__init__("rgb", tip)
        self.title = title
        self.swatch = QPushButton()
        self.swatch.setFixedWidth(34)
        self.swatch.setToolTip("Pick the colour (the dialog shows sRGB, as the screen does)")
        self.swatch.clicked.connect(self.pick)
        self.layout().insertWidget(0, self.swatch)

    def set_value(self, value) -> None:
        super().set_value(value)
        r, g, b = (np.round(linear_to_srgb(np.asarray(value, float)) * 255)).astype(int)
        # With a border of its own the button is drawn flat in the colour; with only a background,
        # the style shades it (linear red came out pink).
        self.swatch.setStyleSheet(f"background-color: rgb({r}, {g}, {b}); border: 1px solid gray;")
        self._linear = list(value)

    def pick(self) -> None:
        """Open the colour dialog on the current colour; a chosen colour is an edit."""
        dialog = QColorDialog(QColor.fromRgbF(*linear_to_srgb(np.asarray(self._linear, float))), self)
        dialog.setWindowTitle(self.title)
        dialog.setOption(QColorDialog.ColorDialogOption.DontUseNativeDialog)
        if dialog.exec() == QColorDialog.DialogCode.Accepted:
            c = dialog.selectedColor()
            linear = srgb_to_linear(np.array([c.redF(), c.greenF(), c.blueF()]))
            self.edited.emit([round(float(x), 4) for x in linear])


class _Tree(QTreeWidget):
    """The tree keeps the keys it moves with, even where they are also the observer's shortcuts, and its
    names' column as wide as they are at any text size (at x2 "cube" showed as "c…")."""

    OWN_KEYS = {Qt.Key.Key_Up, Qt.Key.Key_Down, Qt.Key.Key_Left, Qt.Key.Key_Right,
                Qt.Key.Key_Home, Qt.Key.Key_End}

    def event(self, event):
        if event.type() == QEvent.Type.ShortcutOverride and event.key() in self.OWN_KEYS:
            event.accept()
            return True
        if event.type() == QEvent.Type.FontChange:
            QTimer.singleShot(0, self, lambda: self.resizeColumnToContents(0))  # once the rows have it
        return super().event(event)


class SceneTreePanel(QWidget):
    """The scene's tree and the selected item's fields (see the module docstring).

    Signals
    -------
    field_edited(object item, str key, object value) : change field ``key`` of ``item``.
    move_requested(object item, object position) : place a mesh's centre at ``position``
        (meshes have no position field in the file: their vertices move).
    """

    field_edited = Signal(object, str, object)
    move_requested = Signal(object, object)

    def __init__(self, model, parent: QWidget | None = None):
        super().__init__(parent)
        self.model = model
        self.tree = _Tree()
        self.tree.setColumnCount(2)
        self.tree.setHeaderLabels(["Name", "Type"])
        self.tree.setToolTip("The scene's objects and lights; F2 or a double click renames")
        self.tree.setEditTriggers(QTreeWidget.EditTrigger.DoubleClicked
                                  | QTreeWidget.EditTrigger.EditKeyPressed)
        self.tree.currentItemChanged.connect(self._tree_selected)
        self.tree.itemChanged.connect(self._tree_renamed)
        self.buttons = QGridLayout()  # two to a row: the dock stays narrow at large text
        self.buttons.setContentsMargins(0, 0, 0, 0)
        self.buttons.setSpacing(2)
        self.title = QLabel()
        self.title.setWordWrap(True)
        self.form_host = QWidget()
        self.form = QFormLayout(self.form_host)
        self.form.setFieldGrowthPolicy(QFormLayout.FieldGrowthPolicy.AllNonFixedFieldsGrow)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        properties = QWidget()
        prop_layout = QVBoxLayout(properties)
        prop_layout.setContentsMargins(0, 0, 0, 0)
        prop_layout.addWidget(self.title)
        prop_layout.addWidget(self.form_host)
        prop_layout.addStretch(1)
        scroll.setWidget(properties)
        top = QWidget()
        top_layout = QVBoxLayout(top)
        top_layout.setContentsMargins(0, 0, 0, 0)
        top_layout.addWidget(self.tree, 1)
        top_layout.addLayout(self.buttons)
        splitter = QSplitter(Qt.Orientation.Vertical)
        splitter.addWidget(top)
        splitter.addWidget(scroll)
        # The tree over the fields, 3 : 2: at 1280 x 720 a small scene's every row shows (the fields
        # scroll; they show one object's at a time).
        splitter.setStretchFactor(0, 3)
        splitter.setStretchFactor(1, 2)
        splitter.setSizes([300, 200])
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 4, 4, 4)
        layout.addWidget(splitter)
        self.fields: dict[str, _Field] = {}
        self._shown: tuple | None = None  # (item, field keys) the form was built for
        model.scene_changed.connect(self._scene_changed)
        model.selection_changed.connect(lambda _: self._show_selection())
        self._scene_changed()

    # -------------------------------------------------------------- tree
    def add_button(self, action=None, menu=None, text: str = "") -> QToolButton:
        """A button under the tree for ``action``, or titled ``text`` opening ``menu``."""
        button = QToolButton()
        if action is not None:
            button.setDefaultAction(action)
        else:
            button.setText(text)
            button.setToolTip(menu.toolTip())
            button.setMenu(menu)
            button.setPopupMode(QToolButton.ToolButtonPopupMode.InstantPopup)
        button.setToolButtonStyle(Qt.ToolButtonStyle.ToolButtonTextOnly)
        button.setSizePolicy(QSizePolicy.Policy.Expanding, QSizePolicy.Policy.Fixed)
        n = self.buttons.count()
        self.buttons.addWidget(button, n // BUTTONS_PER_ROW, n % BUTTONS_PER_ROW)
        return button

    def start_rename(self) -> None:
        """Let the user type a new name for the selected object or light in the tree."""
        item = self.tree.currentItem()
        if item is not None and item.flags() & Qt.ItemFlag.ItemIsEditable:
            self.tree.editItem(item, 0)

    def _scene_changed(self, *_) -> None:
        scene = self.model.scene
        self.tree.blockSignals(True)
        self.tree.clear()
        self.items: dict[tuple, QTreeWidgetItem] = {}
        objects = QTreeWidgetItem(self.tree, [f"Objects ({len(scene.objects)})"])
        for i, obj in enumerate(scene.objects):
            self._leaf(objects, ("object", i), obj.name, _type_name(obj))
        lights = QTreeWidgetItem(self.tree, [f"Lights ({len(scene.lights)})"])
        for i, light in enumerate(scene.lights):
            self._leaf(lights, ("light", i), light.name, "point light")
        background = QTreeWidgetItem(self.tree, ["Background", "colour"])
        background.setData(0, ITEM_ROLE, checked_edits.BACKGROUND)
        self.items[checked_edits.BACKGROUND] = background
        for top in (objects, lights):
            top.setFlags(Qt.ItemFlag.ItemIsEnabled)
            top.setExpanded(True)
        self.tree.resizeColumnToContents(0)
        self.tree.blockSignals(False)
        self._show_selection()

    def _leaf(self, parent, item, name, type_name) -> None:
        leaf = QTreeWidgetItem(parent, [name, type_name])
        leaf.setData(0, ITEM_ROLE, item)
        leaf.setFlags(leaf.flags() | Qt.ItemFlag.ItemIsEditable)
        self.items[item] = leaf

    def _tree_selected(self, current, _previous) -> None:
        self.model.set_selection(current.data(0, ITEM_ROLE) if current is not None else None)

    def _tree_renamed(self, leaf, column) -> None:
        item, scene = leaf.data(0, ITEM_ROLE), self.model.scene
        if column == 0 and item is not None and leaf.text(0) != checked_edits.name_of(scene, item):
            self.field_edited.emit(item, "name", leaf.text(0))
            if self.model.scene is scene:  # refused: the tree shows the name it has, once its editor
                # has let go of the item (set here, inside the editor's commit, the text crashed Qt)
                QTimer.singleShot(0, self.tree, lambda: self._show_name(item))

    def _show_name(self, item) -> None:
        """The tree's leaf of ``item`` reads its name in the scene."""
        leaf = self.items.get(item)  # None if the tree was built anew for a scene without it
        if leaf is not None:
            self.tree.blockSignals(True)
            leaf.setText(0, checked_edits.name_of(self.model.scene, item))
            self.tree.blockSignals(False)

    # ------------------------------------------------------------- form
    def _show_selection(self) -> None:
        item = self.model.selection
        self.tree.blockSignals(True)
        self.tree.setCurrentItem(self.items.get(item))
        self.tree.blockSignals(False)
        scene = self.model.scene
        if item is None:
            self._build(None, [])
            self.title.setText("Select an object, a light or the background in the tree, "
                               "or click an object in the 3D pane.")
            return
        specs = _specs(scene, item)
        if self._shown != (item, [s[0] for s in specs]):
            self._build(item, specs)
        # The item's file form, only if a field needs it: a mesh's would hold every vertex.
        value = checked_edits.form(scene, item) if any(map(_in_form, specs)) else {}
        for spec in specs:
            self.fields[spec[0]].set_value(_get(value, spec, scene, item))
        kind = item[0]
        what = _type_name(scene.objects[item[1]]) if kind == "object" else kind
        extra = _mesh_note(scene.objects[item[1]]) if kind == "object" else ""
        self.title.setText(f"<b>{html.escape(_shortened(checked_edits.name_of(scene, item)))}</b> — "
                           f"{html.escape(what + extra)}")

    def _build(self, item, specs) -> None:
        while self.form.rowCount():
            self.form.removeRow(0)
        self.fields = {}
        self._shown = (item, [s[0] for s in specs])
        for key, kind, tip in specs:
            if key == "material.color" or key == "color":
                field = _ColorField(tip, f"Colour of {checked_edits.name_of(self.model.scene, item)}")
            elif key == "name":
                field = _NameField(tip=tip)
            else:
                field = _Field(COMPONENTS.get(kind, ""), tip)
            if kind == "mesh position":
                field.edited.connect(lambda v, i=item: self.move_requested.emit(i, v))
            else:
                field.edited.connect(lambda v, i=item, k=key: self.field_edited.emit(i, k, v))
            if key.startswith("material.") and not any(k.startswith("material.") for k in self.fields):
                self.form.addRow(QLabel("<b>Material</b>"))
            name = QLabel(label(key))
            name.setToolTip(tip)
            self.form.addRow(name, field)
            self.form.addRow(field.problem)
            self.fields[key] = field

    def show_problem(self, key: str, text: str) -> None:
        """Show ``text`` (the loader's message) in red beside field ``key`` of the form."""
        self.fields[key].show_problem(text)

    def problem(self, key: str) -> str:
        """The message shown beside field ``key`` ("" if none)."""
        field = self.fields[key]
        return field.problem.text() if field.problem.isVisibleTo(self) else ""


# --- what each kind of item shows ---------------------------------------------------


def _type_name(obj) -> str:
    if not isinstance(obj, Mesh):
        return "sphere"
    return (obj.source or {}).get("type", "mesh")


#: The most of a name the fields' title shows: one without spaces cannot wrap, and longer it widened
#: the fields beyond the dock (the name's own box holds it whole).
TITLE_NAME_CHARS = 40


def _shortened(name: str) -> str:
    """``name``, cut to :data:`TITLE_NAME_CHARS` characters with "…" where it is longer."""
    return name if len(name) <= TITLE_NAME_CHARS else name[:TITLE_NAME_CHARS - 1] + "…"


def _mesh_note(obj) -> str:
    if not isinstance(obj, Mesh):
        return ""
    path = (obj.source or {}).get("path")
    return f", {counted(len(obj.triangles), 'triangle')}" + (f" from {path}" if path else "")


def _specs(scene, item) -> list[tuple[str, str, str]]:
    """The item's fields: ``(key, kind, tooltip)``, in the order of the README's tables."""
    kind, index = item
    if kind == "background":
        return [("color", "color", "colour of pixels no object covers, linear RGB, each in [0, 1]")]
    name = ("name", "name", "what the tree and the edits call it")
    if kind == "light":
        return [name, ("position", "point", "position of the point light, scene units"),
                ("color", "color", "colour of its light, linear RGB, each in [0, 1]"),
                ("intensity", "length", "brightness factor, >= 0")]
    obj = scene.objects[index]
    type_name = _type_name(obj)
    if type_name == "sphere":
        params = [("center", "point", "centre, scene units"), ("radius", "length", "radius, > 0")]
    elif type_name in shapes.PRIMITIVES:
        params = [(p.name, p.kind, f"{p.doc} ({KIND_TIPS.get(p.kind, f'{p.minimum} to {p.maximum}')})")
                  for p in shapes.PRIMITIVES[type_name].params]
    else:
        params = [("position", "mesh position", "centre of its bounding box; moving it moves every "
                                                "vertex (a mesh from a file is then saved inline)")]
    material = [(f"material.{k}", "color" if k == "color" else "number", tip)
                for k, tip in MATERIAL_TIPS.items()]
    return [name, *params, *material]


def _in_form(spec) -> bool:
    """Whether a field's value is read from the item's file form (see :func:`_get`)."""
    key, kind, _ = spec
    return key != "name" and not key.startswith("material.") and kind != "mesh position"


def _get(value: dict, spec, scene, item):
    key, kind, _ = spec
    if key == "name":
        return checked_edits.name_of(scene, item)
    if kind == "mesh position":
        return checked_edits.position_of(scene, item).tolist()
    if key.startswith("material."):
        return getattr(scene.objects[item[1]].material, key.split(".", 1)[1])
    return value[key]
