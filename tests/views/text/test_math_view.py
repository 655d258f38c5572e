"""Long formulas stay readable: broken into lines at their wide spaces, never shrunk past a limit."""

import pytest
from PySide6.QtGui import QFont
from PySide6.QtWidgets import QApplication

from core.lessons.lesson_file import shipped_lessons
from views.panels.lesson_panel import LessonPanel
from views.text.math_view import MIN_SHRINK, MathView, join_parts, split_formula


@pytest.fixture
def parsed_on_gui_thread(monkeypatch, tmp_path):
    """For each formula typeset from now on (nothing kept from an earlier run is reused), whether the GUI
    thread asked for it (and waited for it)."""
    import threading

    from views.text import math_view, typesetting_process

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    math_view._typeset.cache_clear()
    parsed, typeset = [], typesetting_process.typeset

    def watched(*args):
        parsed.append(threading.current_thread() is threading.main_thread())
        return typeset(*args)

    monkeypatch.setattr(typesetting_process, "typeset", watched)
    yield parsed
    math_view._typeset.cache_clear()


SPHERE = r"$c = (x_1-l)^2 + (y_1-m)^2 + (z_1-n)^2 - r^2,\quad \Delta = b^2 - 4ac$"


def test_a_formula_splits_only_at_spaces_between_its_parts_and_joins_back():
    parts = split_formula(SPHERE)
    assert parts == [(r"c = (x_1-l)^2 + (y_1-m)^2 + (z_1-n)^2 - r^2,", r"\quad "),
                     (r"\Delta = b^2 - 4ac", "")]
    assert join_parts(parts) == SPHERE and join_parts(parts[1:]) == r"$\Delta = b^2 - 4ac$"
    assert [p for p, _ in split_formula(r"$a,\ \ b\qquad c\ d$")] == ["a,", "b", "c", "d"]
    for whole in (r"$\mathrm{no\ \ hit}$",  # inside braces
                  r"$\left( a,\ b \right)$",  # inside \left ... \right
                  r"text\quad $x$ more",  # not one stretch of math
                  r"$x\quadrature$"):  # another command
        assert split_formula(whole) == [(whole, "")], whole


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


def test_words_joined_by_spaces_fill_lines_like_text(qtbot):
    formula = (r"$\mathrm{object\ order:}\ \mathbf{for}\ \mathrm{object}\ "
               r"\mathbf{for}\ \mathrm{pixel\ it\ covers}$")
    one_line = _shown(qtbot, formula, 5000, 2.0).pixmap().deviceIndependentSize().width()
    view = _shown(qtbot, formula, int(one_line * 0.45), 2.0)
    lines, size = view.shown_lines()
    assert 2 <= len(lines) <= 4 and size >= MIN_SHRINK * view.size_pt()
    assert lines[0].startswith(r"$\mathrm{object\ order:}")  # the words stay in their order
    assert view.pixmap().deviceIndependentSize().width() <= view.width() + 1  # nothing cut off


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
            qtbot.waitUntil(lambda: not panel.typesetting())
            for _ in range(3):  # the posted layout requests (a wrapped formula asks for more height)
                QApplication.processEvents()
            for view in panel.formula_views():
                assert view.width() > 0
                assert view.shown_lines()[1] >= MIN_SHRINK * view.size_pt() - 1e-9, (lesson.id, k)
                # As tall as its lines at its width: no line is clipped.
                assert view.height() >= view.heightForWidth(view.width()) - 1, (lesson.id, k)


def test_a_later_view_typesets_once_per_restyle_and_shows_a_formula_set_again(qtbot, monkeypatch):
    # A restyle (presentation mode, text size) sends each view a font, a palette and a style change;
    # each started a typesetting of the same formula, and the GUI thread waited on them for the GIL.
    from PySide6.QtWidgets import QWidget

    from views.text import math_view

    parent = QWidget()
    qtbot.addWidget(parent)
    view = MathView(SPHERE, parent, later=True)
    parent.show()
    qtbot.waitUntil(lambda: not view.pending)
    jobs = []
    job = math_view._TypesetJob
    monkeypatch.setattr(math_view, "_TypesetJob", lambda *args: (jobs.append(args[1][0]), job(*args))[1])
    parent.setStyleSheet("QWidget { font-size: 20pt; color: #123456; }")
    qtbot.waitUntil(lambda: not view.pending)
    assert jobs == [(SPHERE, view.size_pt())]  # one typesetting, at the new size
    assert view.sizeHint().height() > 0 and not view.pixmap().isNull()
    view.set_formula(r"$x$")
    view.set_formula(SPHERE)  # the formula it showed before, set again: shown again
    qtbot.waitUntil(lambda: not view.pending)
    assert not view.pixmap().isNull() and view.shown_lines()[0]


def test_a_formula_on_a_hidden_page_is_typeset_only_once_its_page_is_shown(qtbot, parsed_on_gui_thread):
    # After every lesson, a new text size had some 150 formulas of hidden panes typeset, and the GUI
    # thread laid each out again as it came back: a lecturer changing the size waited for all of them.
    from PySide6.QtWidgets import QTabWidget

    shown, hidden = r"$\alpha_{shown} = 1$", r"$\beta_{hidden} = 2$"
    tabs = QTabWidget()
    qtbot.addWidget(tabs)
    views = {}
    for formula in (shown, hidden):
        views[formula] = MathView(formula, later=True)
        tabs.addTab(views[formula], formula)
    tabs.show()
    qtbot.waitExposed(tabs)
    qtbot.waitUntil(lambda: not views[shown].pending and not views[shown].pixmap().isNull())
    font = QFont(tabs.font())
    font.setPointSizeF(font.pointSizeF() * 1.5)
    tabs.setFont(font)  # a new text size: the shown page's formula is typeset again at it
    qtbot.waitUntil(lambda: not views[shown].pending)
    assert len(parsed_on_gui_thread) >= 2 and not views[hidden].pending
    assert views[hidden].pixmap().isNull() and views[hidden].shown_lines()[0] == []  # nothing typeset
    count = len(parsed_on_gui_thread)
    tabs.setCurrentIndex(1)
    assert views[hidden].pending  # asked for as its page shows, at the size it is now
    qtbot.waitUntil(lambda: not views[hidden].pending)
    assert not views[hidden].pixmap().isNull() and views[hidden].shown_lines() == ([hidden],
                                                                                 views[hidden].size_pt())
    assert len(parsed_on_gui_thread) > count and not any(parsed_on_gui_thread)


def test_a_later_view_wraps_its_formula_without_typesetting_on_the_gui_thread(qtbot, parsed_on_gui_thread):
    # A lesson step's formula, narrower than its line, is wrapped by trying runs of its parts on one
    # line; those were typeset on the GUI thread (a quarter of a second in a lesson step).
    from PySide6.QtWidgets import QVBoxLayout, QWidget


    formula = (r"$\mathrm{object\ order:}\ \mathbf{for}\ \mathrm{object}\ "
               r"\mathbf{for}\ \mathrm{pixel\ it\ covers}$")
    parent = QWidget()
    qtbot.addWidget(parent)
    QVBoxLayout(parent).addWidget(view := MathView(formula, parent, later=True))
    parent.resize(160, 400)
    parent.show()
    qtbot.waitExposed(parent)
    qtbot.waitUntil(lambda: not view.pending and view.pixmap() is not None and not view.pixmap().isNull())
    for _ in range(3):  # the posted layout requests (a wrapped formula asks for more height)
        QApplication.processEvents()
    lines, _ = view.shown_lines()
    assert len(lines) >= 2  # wrapped
    assert parsed_on_gui_thread and not any(parsed_on_gui_thread)  # all typeset, none on the GUI thread


def test_a_formula_replaced_before_its_turn_is_never_typeset_and_the_new_one_shows(qtbot, monkeypatch):
    # Stepping through a lesson asks for each step's formulas; the ones of a step already left waited
    # in the typesetter's queue ahead of the step shown (and a closed window's kept it busy).
    import threading

    from PySide6.QtCore import QRunnable
    from PySide6.QtWidgets import QWidget

    from views.text import math_view

    typeset = []
    real = math_view._typeset
    monkeypatch.setattr(math_view, "_typeset",
                        lambda text, *args: (typeset.append(text), real(text, *args))[1])
    asked = []
    job = math_view._TypesetJob
    monkeypatch.setattr(math_view, "_TypesetJob", lambda *args: (asked.append(args[1][0]), job(*args))[1])
    busy, release = threading.Event(), threading.Event()

    class Busy(QRunnable):  # holds the typesetter's one thread, as a long formula being typeset does
        def run(self):
            busy.set()
            release.wait(30)

    math_view._typesetter().start(Busy())
    assert busy.wait(30)
    parent = QWidget()
    qtbot.addWidget(parent)
    view = MathView(r"$x_{left} = 1$", parent, later=True)
    parent.show()
    qtbot.waitUntil(lambda: len(asked) == 1)  # asked for, waiting behind the busy thread
    view.set_formula(r"$y_{shown} = 2$")
    qtbot.waitUntil(lambda: len(asked) == 2)  # the new formula asked for, behind the old one
    release.set()
    qtbot.waitUntil(lambda: not view.pending)
    assert not any("left" in text for text in typeset)
    assert any("shown" in text for text in typeset) and not view.pixmap().isNull()


def test_a_view_deleted_while_its_formula_is_typeset_gets_no_more_of_it_and_the_next_view_shows(
        qtbot, monkeypatch):
    # Closing a window while its formulas were being typeset crashed the program: the typesetter's
    # thread read the deleted view's Qt objects. It now reads only what the view asked for.
    import threading

    import shiboken6
    from PySide6.QtWidgets import QWidget

    from views.text import math_view

    typeset, first, release = [], threading.Event(), threading.Event()
    real = math_view._typeset

    def held(text, *args):  # the deleted view's first formula is being typeset while it is deleted
        typeset.append(text)
        if "gone" in text:
            first.set()
            release.wait(30)
        return real(text, *args)

    monkeypatch.setattr(math_view, "_typeset", held)
    parents = [QWidget(), QWidget()]
    for parent in parents:
        qtbot.addWidget(parent)
    gone = MathView(r"$x_{gone} = 1,\quad y_{gone} = 2$", parents[0], later=True)
    parents[0].show()
    qtbot.waitUntil(first.is_set)
    kept = MathView(r"$z_{kept} = 3$", parents[1], later=True)
    parents[1].show()
    shiboken6.delete(parents[0])  # the window closed mid-typesetting
    release.set()
    qtbot.waitUntil(lambda: not kept.pending)
    assert sum("gone" in text for text in typeset) == 1  # none of its other parts or sizes
    assert not kept.pixmap().isNull() and kept.shown_lines()[0]
    assert not shiboken6.isValid(gone)


ENDS_MID_TYPESETTING = r"""
import sys
from PySide6.QtCore import QEventLoop
from PySide6.QtWidgets import QApplication, QWidget
from views.text import math_view
from views.text.math_view import MathView
app = QApplication(sys.argv[:1])
parent = QWidget()
views = [MathView(rf"$x_{{{k}}} = \frac{{{k}}}{{{k + 1}}},\quad y = \sqrt{{{k}}}$", parent, later=True)
         for k in range(40)]
parent.show()
while math_view._typesetter().activeThreadCount() == 0:
    app.processEvents(QEventLoop.ProcessEventsFlag.AllEvents, 10)
print("ending while typesetting", flush=True)
"""


@pytest.mark.gui
def test_a_process_that_ends_while_formulas_are_typeset_ends_cleanly(tmp_path):
    # A script or test process that ended mid-typesetting printed "Signal source has been deleted" for
    # every formula still queued: the interpreter's shutdown deleted the Qt objects they report to.
    import os
    import subprocess
    import sys

    from checkout import ROOT

    for run in range(3):
        env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path / str(run))}  # nothing typeset before
        out = subprocess.run([sys.executable, "-c", ENDS_MID_TYPESETTING], cwd=ROOT, capture_output=True,
                             text=True, env=env, timeout=300)
        assert out.returncode == 0 and "ending while typesetting" in out.stdout, out.stderr
        assert "Traceback" not in out.stderr and "Error" not in out.stderr, out.stderr


def test_a_formula_typeset_just_before_a_new_text_size_is_never_typeset_on_the_gui_thread(
        qtbot, parsed_on_gui_thread):
    # Changing the text size held the window up to 400 ms: the typesetter finished the old size just as
    # the new size was set, and the view showed it at once, at the new size, typesetting that on the
    # GUI thread.
    from PySide6.QtWidgets import QWidget

    parent = QWidget()
    qtbot.addWidget(parent)
    view = MathView(r"$y_{sized} = 3$", parent, later=True)
    parent.show()
    qtbot.waitUntil(lambda: not view.pending)
    small = view.pixmap().height()
    view.set_scale(2.0)  # the new size is asked for on the next turn of the event loop ...
    view._typeset_done(view._request)  # ... and the typesetter's notice of the old one arrives first
    qtbot.waitUntil(lambda: not view.pending and view.pixmap().height() > 1.5 * small)
    assert parsed_on_gui_thread and not any(parsed_on_gui_thread)  # typeset at both sizes, off it


def test_a_formula_typeset_in_a_disabled_pane_is_inked_as_in_an_enabled_one(qtbot):
    """A pane covered while an exercise waits is disabled; the formulas typeset then kept the
    disabled grey once it came back."""
    from PySide6.QtGui import QPalette

    from views.text.math_view import MathView

    view = MathView("x = 1")
    qtbot.addWidget(view)
    enabled = view._color_name()
    view.setEnabled(False)
    assert view.palette().color(view.foregroundRole()).name() != enabled  # Qt's disabled grey
    assert view._color_name() == enabled == view.palette().color(QPalette.ColorGroup.Active,
                                                                 QPalette.ColorRole.WindowText).name()
