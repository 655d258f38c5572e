"""A pixel's ray tree, drawn in 3D and listed as an expandable tree.

Segments are coloured by the kind of ray in the Okabe–Ito palette, which
viewers with the common colour-vision deficiencies can tell apart; blocked
shadow rays are drawn thin and grey.  The list shows every node's numbers and
the second stage of ray tracing: each ray's colour computed from its hit's
local colour and its children's colours, from the last hits back to the first.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from PySide6.QtCore import QEvent, QSize, Qt, QTimer, Signal
from PySide6.QtGui import QColor
from PySide6.QtWidgets import (
    QGridLayout,
    QHeaderView,
    QLabel,
    QLayout,
    QSplitter,
    QTreeWidget,
    QTreeWidgetItem,
    QWidget,
)

from core.image_order.ray_tree import RayNode
from core.in_words import counted

if TYPE_CHECKING:
    import pyvista as pv

# Okabe & Ito (2008), "Color Universal Design": distinguishable with colour-vision deficiencies.
KIND_COLORS = {
    "primary": "#56B4E9",  # sky blue
    "shadow": "#F0E442",  # yellow
    "reflection": "#E69F00",  # orange
    "refraction": "#CC79A7",  # reddish purple
}
BLOCKED_COLOR = "#8a8a8a"
SWATCH_SIZE = (22, 8)
"""A ray kind's swatch in the legend, pixels."""
COLUMNS = ["ray", "hit", "t", "weight", "returns colour"]
SPARE_COLUMNS = (2, 3)
"""The columns (t and weight) a tree too narrow for all of them leaves out, its returned colours whole."""
MOST_OF_SPLITTER = 0.8
"""The most of a splitter's width the tree takes to show every column whole; the rest stays beside it."""


def _segment_end(node: RayNode, miss_length: float) -> np.ndarray:
    if node.t is not None:
        length = node.t
    elif np.isfinite(node.t_max):
        length = node.t_max
    else:
        length = miss_length
    return node.origin + node.direction * length


def ray_tree_parts(root: RayNode, miss_length: float) -> list[tuple[pv.PolyData, dict]]:
    """Line segments of every traced ray, one part per style, for ``SceneView.set_overlay``."""
    import pyvista as pv  # loaded with the 3D pane, not with the window (views.scene3d.deferred_scene_view)

    segments: dict[str, list] = {}
    for node in root.walk():
        if not node.traced:
            continue
        style = node.kind
        if node.kind == "shadow" and node.hit is not None:
            style = "blocked"
        segments.setdefault(style, []).append((node.origin, _segment_end(node, miss_length)))
    parts = []
    for style, pairs in segments.items():
        points = np.array([p for pair in pairs for p in pair])
        lines = np.hstack([[2, 2 * i, 2 * i + 1] for i in range(len(pairs))])
        color = BLOCKED_COLOR if style == "blocked" else KIND_COLORS[style]
        width = 2 if style in ("blocked", "shadow") else 5
        parts.append((pv.PolyData(points, lines=lines), {"color": color, "line_width": width}))
    hits = [n.point for n in root.walk() if n.traced and n.point is not None and n.kind != "shadow"]
    if hits:
        parts.append((pv.PolyData(np.array(hits)),
                      {"color": "white", "point_size": 10, "render_points_as_spheres": True}))
    return parts


class RayKindLegend(QWidget):
    """One coloured swatch per kind of ray, as many to a line as its width holds, ``per_line`` at most.

    Its least width is one swatch and its name: in a narrow settings column, or at a large text
    size, the swatches take more lines rather than widening the column (three to a line, at text
    x2 on a 1280 x 720 screen, left the traced image beside the column a quarter of the pane).
    """

    def __init__(self, per_line: int = 3, parent: QWidget | None = None):
        super().__init__(parent)
        self._most, self._per_line = per_line, 0
        self._grid = QGridLayout(self)
        self._grid.setContentsMargins(0, 0, 0, 0)
        # The grid of the moment sets no least size: the widget's own (one swatch wide) holds.
        self._grid.setSizeConstraint(QLayout.SizeConstraint.SetNoConstraint)
        self._items = []
        for kind, color in [*KIND_COLORS.items(), ("blocked shadow", BLOCKED_COLOR)]:
            swatch = QLabel()
            swatch.setFixedSize(*SWATCH_SIZE)
            swatch.setStyleSheet(f"background: {color}; border: 1px solid #333;")
            self._items.append((swatch, QLabel(kind)))
        self._arrange(per_line)

    def _width_of(self, per_line: int) -> int:
        """The width the swatches take ``per_line`` to a line: each column as wide as its longest name."""
        spacing = self._grid.horizontalSpacing()
        names = [label.sizeHint().width() for _, label in self._items]
        columns = [max(names[c::per_line]) for c in range(min(per_line, len(names)))]
        return sum(SWATCH_SIZE[0] + spacing + name for name in columns) + (len(columns) - 1) * spacing

    def _arrange(self, per_line: int) -> None:
        if per_line == self._per_line:
            return
        self._per_line = per_line
        while self._grid.count():
            self._grid.takeAt(0)
        for column in range(self._grid.columnCount()):
            self._grid.setColumnStretch(column, 0)
        for i, (swatch, label) in enumerate(self._items):
            row, column = divmod(i, per_line)
            self._grid.addWidget(swatch, row, 2 * column)
            self._grid.addWidget(label, row, 2 * column + 1)
        self._grid.setColumnStretch(2 * per_line, 1)
        self.updateGeometry()  # another height

    def sizeHint(self) -> QSize:
        return QSize(self._width_of(self._most), self._grid.sizeHint().height())

    def minimumSizeHint(self) -> QSize:
        return QSize(self._width_of(1), self._grid.minimumSize().height())

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self._fit(event.size().width())

    def changeEvent(self, event) -> None:
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:  # other names' widths in the same width
            self._fit(self.width())

    def _fit(self, width: int) -> None:
        fits = [n for n in range(1, self._most + 1) if self._width_of(n) <= width]
        self._arrange(max(fits, default=1))


def _rgb(c) -> str:
    return "(" + ", ".join(f"{v:.3f}" for v in c) + ")"


def _returned(c) -> str:
    """A returned colour as the list shows it: linear r g b to 2 decimals, so that at text x2 on
    1920x1080 every column fits beside the second stage (its tooltip and the second stage give 3)."""
    return " ".join(f"{v:.2f}" for v in c)


class RayTreeWidget(QTreeWidget):
    """The ray tree as an expandable list, one row per ray with its numbers.

    Signals
    -------
    crowded_changed(bool) : whether the columns need more than :data:`MOST_OF_SPLITTER` of the
        splitter the tree is in, so that what is beside it should go elsewhere (at text x2 on a
        1280 x 720 screen, the tree beside the second stage cut its last columns).
    """

    crowded_changed = Signal(bool)

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.setColumnCount(len(COLUMNS))
        self.setHeaderLabels(COLUMNS)
        self.setAlternatingRowColors(True)
        # Columns as wide as their header or their widest entry, at every text scale; the last one
        # too (stretched to the view's edge, it was cut at large text and the header's length hid it).
        self.header().setStretchLastSection(False)
        self.setIndentation(14)  # a glass ball's tree is 5 deep: Qt's 20 px a level cost the colours
        self.header().setSectionResizeMode(QHeaderView.ResizeMode.ResizeToContents)
        # Whenever a column takes a new width (a new tree, a new text size), once it has it.
        self._widen = QTimer(self, singleShot=True, interval=0)
        self._widen.timeout.connect(self.widen_to_columns)
        self.header().sectionResized.connect(lambda *_: self.widen_soon())
        self._around_width = 0  # the splitter's width at the last resize
        self.crowded = False

    def resizeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        """A narrower splitter (the lesson dock widened as its formulas came in) gave the tree its share
        of less and cut the returned colours again: the tree takes back what its columns need.  A drag
        of the splitter's handle leaves the splitter's width as it was, and the tree as dragged."""
        super().resizeEvent(event)
        around = self.parentWidget().width() if self.parentWidget() is not None else 0
        if around < self._around_width:
            self.widen_soon()
        self._around_width = around

    def set_tree(self, root: RayNode) -> None:
        self.clear()
        self.addTopLevelItem(self._item(root))
        self.expandAll()

    def row_count(self) -> int:
        """The rays shown, one row each (the tree is shown whole)."""
        return sum(1 for _ in self._items())

    def widen_soon(self) -> None:
        """:meth:`widen_to_columns` once the layouts around took the sizes given them now."""
        self._widen.start()

    def widen_to_columns(self) -> None:
        """In a splitter, take the width every column needs (the last one, the returned colours,
        was cut off at large text), if that leaves the others a fifth of it; else say the tree is
        crowded (what is beside it goes elsewhere) and, alone and still too narrow, leave out the
        columns of :data:`SPARE_COLUMNS` (their numbers are in every row's tooltip) rather than cut
        the returned colours."""
        splitter = self.parentWidget()
        if not isinstance(splitter, QSplitter) or splitter.orientation() != Qt.Orientation.Horizontal:
            return
        header = self.header()
        columns = [max(self.sizeHintForColumn(c), header.sectionSizeHint(c)) for c in range(header.count())]
        chrome = 2 * self.frameWidth() + self.verticalScrollBar().sizeHint().width()
        need = sum(columns) + chrome
        sizes = splitter.sizes()
        index, total = splitter.indexOf(self), sum(sizes)
        if total <= 0:
            return
        crowded = need > total * MOST_OF_SPLITTER
        if crowded != self.crowded:
            self.crowded = crowded
            self.crowded_changed.emit(crowded)
            return  # the splitter takes other widgets, and this runs again at the tree's new width
        for column in SPARE_COLUMNS:
            self.setColumnHidden(column, crowded and need > sizes[index])
        if sizes[index] >= need or crowded:
            return
        others = [s for i, s in enumerate(sizes) if i != index]
        share = [(total - need) * s / max(sum(others), 1) for s in others]
        splitter.setSizes([need if i == index else round(share.pop(0)) for i in range(len(sizes))])

    def select_kind(self, kind: str | None) -> bool:
        """Select and show the first ray of ``kind`` (``None``: no selection); whether there was one."""
        self.clearSelection()
        if kind is None:
            return False
        for item in self._items():
            if item.data(0, Qt.ItemDataRole.UserRole) == kind:
                self.setCurrentItem(item)
                self.scrollToItem(item)
                return True
        return False

    def selected_kind(self) -> str | None:
        """The kind of the selected ray, or ``None``."""
        items = self.selectedItems()
        return items[0].data(0, Qt.ItemDataRole.UserRole) if items else None

    def _items(self):
        stack = [self.topLevelItem(i) for i in range(self.topLevelItemCount())]
        while stack:
            item = stack.pop(0)
            yield item
            stack[:0] = [item.child(i) for i in range(item.childCount())]

    def _item(self, node: RayNode) -> QTreeWidgetItem:
        label = node.kind if node.kind != "shadow" else f"shadow → light {node.light}"
        if node.hit_name:
            hit = node.hit_name
        elif not node.traced and node.kind == "shadow":
            # No shadow ray was sent, yet the light's share is known: the whole of it when nothing
            # can block the light, none when it is behind the surface.
            hit = "lit: no ray needed" if np.any(node.color > 0) else "unlit: light behind"
        elif not node.traced:
            hit = "not traced"
        else:
            hit = "reaches the light" if node.kind == "shadow" else "nothing (background)"
        t = f"{node.t:.4g}" if node.t is not None else ""
        item = QTreeWidgetItem([label, hit, t, f"{node.weight:.3g}",
                                _returned(node.color) if node.color is not None else ""])
        item.setForeground(0, QColor(KIND_COLORS[node.kind]).darker(130))
        item.setData(0, Qt.ItemDataRole.UserRole, node.kind)
        tips = [node.status + (f" at t = {t}" if t else ""), f"weight {node.weight:.3g}",
                f"origin {_rgb(node.origin)}", f"direction {_rgb(node.direction)}"]
        if node.color is not None:
            tips.append(f"returns colour {_rgb(node.color)}")
        if node.normal is not None:
            tips.append(f"normal {_rgb(node.normal)}")
        if node.local_color is not None:
            tips.append(f"local colour {_rgb(node.local_color)}")
        if node.fresnel is not None:
            tips.append(f"Fresnel R = {node.fresnel[0]:.3f}, T = {node.fresnel[1]:.3f}"
                        + (" (total internal reflection)" if node.total_internal_reflection else ""))
        tips.append(f"{counted(node.tests, 'intersection test')}, "
                    f"{counted(node.bounds_tests, 'box and sphere test')}")
        for col in range(len(COLUMNS)):
            item.setToolTip(col, "\n".join(tips))
        if node.color is not None:
            swatch = QColor.fromRgbF(*np.clip(node.color, 0, 1))
            item.setBackground(4, swatch)
            item.setForeground(4, QColor("black" if swatch.lightnessF() > 0.5 else "white"))
        for child in node.children:
            item.addChild(self._item(child))
        return item
