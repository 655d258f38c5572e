"""The ray colours' legend: every kind of ray whole, as many to a line as the width holds."""

import pytest
from PySide6.QtWidgets import QLabel

from views.panels.raytree_view import BLOCKED_COLOR, KIND_COLORS, RayKindLegend

KINDS = [*KIND_COLORS, "blocked shadow"]


def _lines(legend) -> list[list[str]]:
    """The names the legend shows, line by line (by where each label is), left to right."""
    labels = [label for label in legend.findChildren(QLabel) if label.text()]
    rows = sorted({label.y() for label in labels})
    return [[label.text() for label in sorted(labels, key=lambda label: label.x()) if label.y() == y]
            for y in rows]


@pytest.mark.parametrize(("width", "most"), [(10_000, 3), (None, 1)], ids=["wide", "one name wide"])
def test_the_legend_puts_as_many_kinds_to_a_line_as_fit_and_shows_every_name_whole(qtbot, width, most):
    legend = RayKindLegend(per_line=3)
    qtbot.addWidget(legend)
    legend.show()
    least = legend.minimumSizeHint().width()
    legend.resize(width or least, 400)

    def arranged():
        lines = _lines(legend)
        assert [name for line in lines for name in line] == KINDS  # each kind once, in order
        assert max(len(line) for line in lines) == most
        for label in legend.findChildren(QLabel):
            if label.text():  # a name is never cut: as wide as it asks, inside the legend
                assert label.width() >= label.sizeHint().width() and label.geometry().right() < legend.width()

    qtbot.waitUntil(arranged)
    assert least < legend.sizeHint().width()  # narrower than three to a line: it may take more lines
    swatches = [label.styleSheet() for label in legend.findChildren(QLabel) if not label.text()]
    colors = [s.split("background: ")[1].split(";")[0] for s in swatches]
    assert colors == [*KIND_COLORS.values(), BLOCKED_COLOR]


def test_a_larger_text_puts_fewer_kinds_to_a_line_and_the_normal_text_all_three_again(qtbot):
    legend = RayKindLegend(per_line=3)
    qtbot.addWidget(legend)
    legend.show()
    legend.resize(legend.sizeHint().width(), 400)  # just three to a line at this text size
    qtbot.waitUntil(lambda: max(len(line) for line in _lines(legend)) == 3)
    width = legend.width()
    normal = legend.font()
    larger = legend.font()
    larger.setPointSizeF(2 * normal.pointSizeF())
    legend.setFont(larger)
    qtbot.waitUntil(lambda: max(len(line) for line in _lines(legend)) < 3)
    assert legend.width() == width  # the same width: the text alone decides
    legend.setFont(normal)
    qtbot.waitUntil(lambda: max(len(line) for line in _lines(legend)) == 3)
