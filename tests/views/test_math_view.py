"""Long formulas stay readable: broken into lines at their wide spaces, never shrunk past a limit."""

import pytest
from PySide6.QtGui import QFont

from core.lessons import shipped_lessons
from views.lesson_panel import LessonPanel
from views.math_view import MIN_SHRINK, MathView, split_formula

SPHERE = r"$c = (x_1-l)^2 + (y_1-m)^2 + (z_1-n)^2 - r^2,\quad \Delta = b^2 - 4ac$"


def test_a_formula_breaks_only_at_wide_spaces_between_its_parts():
    assert split_formula(SPHERE) == [r"$c = (x_1-l)^2 + (y_1-m)^2 + (z_1-n)^2 - r^2,$",
                                     r"$\Delta = b^2 - 4ac$"]
    assert split_formula(r"$a,\ \ b\qquad c$") == ["$a,$", "$b$", "$c$"]
    assert split_formula(r"$\mathrm{no\ \ hit}\ d$") == [r"$\mathrm{no\ \ hit}\ d$"]  # inside braces
    assert split_formula(r"text\quad more") == [r"text\quad more"]  # outside the math
    assert split_formula(r"$x\quadrature$") == [r"$x\quadrature$"]  # another command


def _shown(qtbot, formula, width, scale):
    view = MathView(formula)
    qtbot.addWidget(view)
    font = QFont(view.font())
    font.setPointSizeF(15.0)
    view.setFont(font)
    view.set_scale(scale)
    view.resize(width, view.heightForWidth(width))
    view.show()
    qtbot.waitExposed(view)
    return view


@pytest.mark.parametrize("scale", [1.0, 1.5, 2.0])
def test_a_long_formula_in_a_narrow_pane_breaks_into_lines_at_a_readable_size(qtbot, scale):
    full = _shown(qtbot, SPHERE, 5000, scale)
    one_line = full.pixmap().deviceIndependentSize()
    view = _shown(qtbot, SPHERE, int(one_line.width() * 0.7), scale)
    lines, size = view.shown_lines()
    assert len(lines) == 2
    assert size >= MIN_SHRINK * view.size_pt()
    shown = view.pixmap().deviceIndependentSize()
    assert shown.height() > 1.5 * one_line.height() * size / view.size_pt()  # two lines, stacked
    assert view.height() >= shown.height() - 1  # the label is as tall as both lines


def test_a_formula_without_breaks_stops_shrinking_and_asks_for_its_width(qtbot):
    formula = r"$\mathbf{o} + t\,\mathbf{d} = \alpha A + \beta B + (1-\alpha-\beta)\,C$"
    view = _shown(qtbot, formula, 60, 1.5)
    assert view.shown_lines()[1] == pytest.approx(MIN_SHRINK * view.size_pt())
    assert view.minimumSizeHint().width() >= view.pixmap().deviceIndependentSize().width() - 1


def test_in_a_narrow_lesson_panel_at_twice_the_text_every_formula_stays_readable(qtbot):
    panel = LessonPanel(shipped_lessons())
    qtbot.addWidget(panel)
    font = QFont(panel.font())
    font.setPointSizeF(2 * (font.pointSizeF() or 10.0))
    panel.setFont(font)
    panel.resize(320, 900)
    panel.show()
    qtbot.waitExposed(panel)
    for row, lesson in enumerate(panel.lessons()):
        for k in range(len(lesson.steps)):
            panel.select(row, k)
            for view in panel.formula_views():
                qtbot.waitUntil(lambda v=view: v.width() > 0)
                assert view.shown_lines()[1] >= MIN_SHRINK * view.size_pt() - 1e-9, (lesson.id, k)
