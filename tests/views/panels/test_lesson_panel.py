"""The lesson panel: lessons in order, the step's text and formulas, stepping, opening a file."""

import json
import threading

import pytest
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QMessageBox, QSpinBox, QVBoxLayout, QWidget
from qt_fixtures import shown_widget

from core.lessons.lesson_file import LessonStep, shipped_lessons
from views.panels.lesson_panel import ClickerKeys, LessonPanel, lesson_label
from views.text import formula_cache
from views.text.math_view import MathView, _typeset

LESSONS = shipped_lessons()


@pytest.fixture
def panel(qtbot):
    return shown_widget(qtbot, LessonPanel(), 600, 800)


def _index(lesson_id: str) -> int:
    return next(i for i, lesson in enumerate(LESSONS) if lesson.id == lesson_id)


def test_the_list_shows_the_lessons_in_the_lectures_order_with_their_figures(panel):
    shown = [panel.list.item(i).text() for i in range(panel.list.count())]
    assert shown == [lesson_label(lesson) for lesson in LESSONS]
    assert "Fig. VII.5" in shown[_index("zbuffer")] and "Q6" in shown[_index("ray_sphere")]
    assert panel.list.currentRow() == 0 and panel.step_index() == (0, 0)


def test_every_step_of_every_lesson_shows_its_text_and_typesets_its_formulas(panel, qtbot):
    for k, lesson in enumerate(panel.lessons()):
        for s, step in enumerate(lesson.steps):
            with qtbot.waitSignal(panel.step_selected) as signal:
                panel.select(k, s)
            assert signal.args[0] is step and isinstance(step, LessonStep)
            assert panel.lesson_title.text() == lesson.title and panel.step_title.text() == step.title
            assert panel.text.text() == step.text
            assert panel.position.text() == f"step {s + 1} of {len(lesson.steps)}"
            views = panel.formula_views()
            assert [v.formula() for v in views] == list(step.formulas)
            qtbot.waitUntil(lambda: not panel.typesetting())
            for view in views:
                assert isinstance(view, MathView)
                assert view.error is None, (lesson.id, view.formula(), view.error)
                assert not view.pixmap().isNull()


def test_clicking_a_lesson_opens_its_first_step(panel, qtbot):
    k = _index("zbuffer")
    with qtbot.waitSignal(panel.step_selected) as signal:
        panel.list.setCurrentRow(k)
    assert signal.args[0] is panel.lessons()[k].steps[0] and panel.step_index() == (k, 0)


def test_page_down_steps_through_the_zbuffer_lesson_then_into_the_next(panel, qtbot):
    k = _index("zbuffer")
    panel.select(k, 0)
    panel.setFocus()
    steps = []
    for _ in range(len(LESSONS[k].steps)):
        with qtbot.waitSignal(panel.step_selected) as signal:
            qtbot.keyClick(panel, Qt.Key.Key_PageDown)
        steps.append(signal.args[0])
    assert [s.zbuffer_step for s in steps[:3]] == [1, 2, 3]
    assert panel.step_title.text() == LESSONS[k + 1].steps[0].title and panel.step_index() == (k + 1, 0)
    qtbot.keyClick(panel, Qt.Key.Key_Left)
    assert panel.step_index() == (k, 3) and panel.position.text() == "step 4 of 4"
    qtbot.keyClick(panel, Qt.Key.Key_PageUp)
    assert panel.step_index() == (k, 2)


def test_the_ends_of_the_course_stop_stepping(panel):
    assert not panel.previous() and not panel.previous_button.isEnabled()
    panel.select(len(LESSONS) - 1, len(LESSONS[-1].steps) - 1)
    assert not panel.next() and not panel.next_button.isEnabled()


def test_page_keys_step_from_any_widget_and_do_nothing_else(panel, qtbot):
    host = QWidget()
    qtbot.addWidget(host)
    spin = QSpinBox()
    spin.setRange(0, 100)
    spin.setValue(50)
    QVBoxLayout(host).addWidget(spin)
    host.show()
    host.activateWindow()
    qtbot.waitUntil(host.isActiveWindow)  # keys go to the active window's focused widget, as a user's do
    keys = ClickerKeys(panel)
    keys.install()
    try:
        spin.setFocus()
        assert keys._focus.watched() is spin  # the filter sits on the focused widget, not on the application
        with qtbot.waitSignal(panel.step_selected) as first:
            qtbot.keyClick(spin, Qt.Key.Key_PageDown)
        assert panel.step_index() == (0, 0) and first.args[0] is panel.lessons()[0].steps[0]  # shown
        qtbot.keyClick(spin, Qt.Key.Key_PageDown)
        assert panel.step_index() == (0, 1)
        qtbot.keyClick(spin, Qt.Key.Key_PageUp)
        assert panel.step_index() == (0, 0)
        assert spin.value() == 50  # the spin box did not take PageUp/PageDown as +-10
        qtbot.keyClick(spin, Qt.Key.Key_Up)  # arrows stay the widget's outside presentation mode
        assert spin.value() == 51 and panel.step_index() == (0, 0)
    finally:
        keys.remove()


def test_a_broken_lesson_file_is_reported_and_nothing_changes(panel, qtbot, tmp_path):
    panel.select(3, 1)
    before = (panel.step_index(), panel.list.count(), panel.text.text())
    path = tmp_path / "broken.json"
    path.write_text(json.dumps({"format": "render-explorer-lesson", "version": 1, "id": "x", "title": "X",
                                "steps": [{"title": "a", "text": "b", "scene": "lectur",
                                           "panes": ["zbufer"]}]}), encoding="utf-8")
    emitted = []
    panel.step_selected.connect(emitted.append)
    assert panel.open_lesson_file(path) is None
    box = panel.findChild(QMessageBox, "lesson_error")
    qtbot.waitUntil(lambda: box is not None and box.isVisible())
    assert "steps[0].scene: unknown preset 'lectur'" in box.informativeText()
    assert "steps[0].panes[0]: unknown pane 'zbufer'" in box.informativeText()
    box.close()
    assert (panel.step_index(), panel.list.count(), panel.text.text()) == before and emitted == []


def test_a_good_lesson_file_is_added_at_the_end_and_started(panel, qtbot, tmp_path):
    path = tmp_path / "mine.json"
    path.write_text(json.dumps({"format": "render-explorer-lesson", "version": 1, "id": "mine",
                                "title": "My own lesson", "figures": ["VII.5"],
                                "steps": [{"title": "First", "text": "Look at the green polygon.",
                                           "formulas": ["$z < Z$"], "scene": "zbuffer_three_polygons",
                                           "panes": ["object order"]}]}), encoding="utf-8")
    with qtbot.waitSignal(panel.step_selected) as signal:
        lesson = panel.open_lesson_file(path)
    assert lesson.title == "My own lesson" and signal.args[0] is lesson.steps[0]
    assert panel.list.count() == len(LESSONS) + 1 and panel.list.currentRow() == len(LESSONS)
    assert panel.text.text() == "Look at the green polygon."


def test_the_first_next_shows_the_step_the_panel_opened_on_then_moves_on(panel, qtbot):
    """The window opens on lesson 1 step 1 without applying it: the first Next applies it, not step 2."""
    with qtbot.waitSignal(panel.step_selected) as signal:
        assert panel.next()
    assert signal.args[0] is panel.lessons()[0].steps[0] and panel.step_index() == (0, 0)
    with qtbot.waitSignal(panel.step_selected) as signal:
        panel.next()
    assert signal.args[0] is panel.lessons()[0].steps[1] and panel.step_index() == (0, 1)


def test_leaving_a_step_replaces_its_words_and_next_shows_it_again(panel, qtbot):
    k = _index("zbuffer")
    panel.select(k, 1)
    step = panel.lessons()[k].steps[1]
    assert panel.text.text() == step.text and panel.formula_views()
    panel.leave_step("The window shows the example 'lecture' now.")
    assert step.text not in panel.text.text() and "example 'lecture'" in panel.text.text()
    qtbot.waitUntil(lambda: not panel.formula_views())
    with qtbot.waitSignal(panel.step_selected) as signal:
        panel.next()
    assert signal.args[0] is step and panel.text.text() == step.text and panel.step_index() == (k, 1)


def test_a_steps_formulas_are_read_and_typeset_off_the_gui_thread_and_never_stale(panel, qtbot, monkeypatch,
                                                                                tmp_path):
    # Reading a step's formulas from the formula cache held the GUI thread up to a second (bench gui
    # --why: lesson_panel._show -> MathView -> formula_cache.load) while other threads were busy.
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))  # an empty cache: typeset, then read back
    readers = []
    load = formula_cache.load
    monkeypatch.setattr(formula_cache, "load",
                        lambda *a: (readers.append(threading.current_thread()), load(*a))[1])
    steps = [(k, s) for k, lesson in enumerate(panel.lessons()) for s, step in enumerate(lesson.steps)
             if step.formulas][:3]
    qtbot.waitUntil(lambda: not panel.typesetting(), timeout=60_000)  # the step the panel opened on
    for first_run in (True, False):
        _typeset.cache_clear()  # as in a new process: from the disk cache the second time
        readers.clear()
        for k, s in steps:
            panel.select(k, s)
            views = panel.formula_views()
            # The new step's formulas at once, none of the former step's pictures meanwhile.
            assert [v.formula() for v in views] == list(panel.lessons()[k].steps[s].formulas)
            assert all(v.pending and v.pixmap().isNull() for v in views)
            qtbot.waitUntil(lambda: not panel.typesetting(), timeout=60_000)
            assert all(not v.pixmap().isNull() and v.error is None for v in views)
        assert readers, first_run  # the cache was read ...
        assert threading.main_thread() not in readers  # ... never on the GUI thread


def test_the_open_lesson_stays_in_view_when_the_list_gets_shorter(panel, qtbot):
    lessons = panel.lessons()
    panel.select(len(lessons) - 1, 0)  # the last lesson, at the bottom of the list
    row = panel.list.visualItemRect(panel.list.currentItem())
    qtbot.waitUntil(lambda: panel.list.viewport().rect().contains(
        panel.list.visualItemRect(panel.list.currentItem())))
    panel.list.setFixedHeight(3 * row.height())  # the left column gave the step's words more room

    def in_view():
        shown = panel.list.viewport().rect()
        item = panel.list.visualItemRect(panel.list.currentItem())
        assert shown.top() <= item.top() and item.bottom() <= shown.bottom(), (shown, item)

    qtbot.waitUntil(in_view, timeout=5000)
