"""The Hard cases panel: selecting each case shows its numbers, verdict, pictures and explanation."""

import html
import threading

import pytest
from PySide6.QtCore import Qt, QThreadPool
from qt_fixtures import shown_widget, wheel_over

from core import hard_cases
from views.panels.hard_cases_panel import (
    HardCasesPanel,
    highlight_digits,
    slider_position,
    slider_steps,
    slider_value,
)

TIMEOUT = 120_000  # ms; the first case may compile the raster kernels


@pytest.fixture
def panel(qtbot):
    widget = shown_widget(qtbot, HardCasesPanel(), 1280, 720)
    yield widget
    widget.shutdown()


def _show(qtbot, panel, name):
    if panel.result is not None and panel.result.name == name and panel.case_name == name:
        return
    with qtbot.waitSignal(panel.result_shown, timeout=TIMEOUT,
                          check_params_cb=lambda shown: shown == name):
        panel.select(name)


def test_every_case_shows_its_title_numbers_verdict_and_explanation(qtbot, panel):
    for name in hard_cases.CASES:
        _show(qtbot, panel, name)
        r = panel.result
        assert r.name == name
        assert panel.title.text() == r.title
        assert len(panel.table_cells) == len(r.rows)
        assert panel.table_cells[0][0].text() == html.escape(r.rows[0].label)
        assert "passes" in panel.verdict.text() and r.error_unit in panel.verdict.text()
        assert panel.explanation.text() == r.explanation
        assert panel.image_box.isVisibleTo(panel) == bool(r.images)
        if r.images:
            assert panel.naive_image.rgb.shape == r.images[0].naive.shape
        assert panel.slider.isVisibleTo(panel) == (r.parameter is not None)
        assert panel.option.isVisibleTo(panel) == (name == "shadow_acne")


def test_the_methods_stand_side_by_side_where_they_fit_and_one_under_another_where_not(qtbot, panel):
    _show(qtbot, panel, "tangent")

    def arrangement() -> set[str]:  # how each row's three values stand to one another
        tops = [{cell.mapTo(panel, cell.rect().topLeft()).y() for cell in cells[1:]}
                for cells in panel.table_cells]
        return {"side by side" if len(row) == 1 else "stacked" for row in tops}

    qtbot.waitUntil(lambda: arrangement() == {"side by side"})
    row = panel.result.rows[2]  # ray outside by offset: its difference, a long number
    assert [cell.text() for cell in panel.table_cells[2][1:]] == [
        highlight_digits(row.naive, row.exact), highlight_digits(row.robust, row.exact), repr(row.exact)]
    panel.resize(560, 720)  # too narrow for the long values side by side
    qtbot.waitUntil(lambda: arrangement() == {"stacked"})
    for cells in panel.table_cells:  # each value under the last, after its method's name
        for name, cell in zip(("textbook", "robust", "reference"), cells[1:], strict=True):
            assert cell.text().startswith(f'<span style="color:#8a93a6">{name}:</span> ')
        tops = [cell.mapTo(panel, cell.rect().topLeft()).y() for cell in cells]
        assert tops == sorted(tops)
    panel.resize(1280, 720)
    qtbot.waitUntil(lambda: arrangement() == {"side by side"})


def test_list_marks_each_case_once_its_robust_method_passed(qtbot, panel):
    def all_marked():
        return all(panel.cases.item(i).text().startswith("✓") for i in range(panel.cases.count()))

    qtbot.waitUntil(all_marked, timeout=TIMEOUT)
    assert panel.cases.item(0).text() == "✓ " + hard_cases.run_case("tangent").title


def test_a_result_for_the_old_slider_position_never_moves_the_slider_back(qtbot):
    # The user drags on while the last position computes.  Its result came in the pause before the
    # new position's computation started, was shown, and put the slider back under the user's hand.
    # The panel's one thread is held here until the drag has moved on, so that result comes then.
    pool = QThreadPool()
    pool.setMaxThreadCount(1)
    panel = shown_widget(qtbot, HardCasesPanel(pool=pool), 1280, 720)
    gate = threading.Event()
    try:
        _show(qtbot, panel, "far_sphere")
        pool.waitForDone()  # the first computation of every case is done
        pool.start(lambda: gate.wait(TIMEOUT / 1000))
        top = panel.slider.maximum()
        panel.slider.setValue(top - 1)
        qtbot.waitUntil(lambda: panel.status.text() == "computing…")  # waits behind the held thread
        panel.slider.setValue(top)
        shown = []
        panel.result_shown.connect(
            lambda _: shown.append((panel.result.parameter.value, panel.slider.value())))
        gate.set()  # the old position's result comes now, in the pause
        qtbot.waitUntil(lambda: bool(shown), timeout=TIMEOUT)
        assert shown == [(pytest.approx(1e9), top)]
    finally:
        gate.set()
        panel.shutdown()


def test_moving_the_slider_recomputes_at_the_new_value(qtbot, panel):
    _show(qtbot, panel, "far_sphere")
    assert panel.result.parameter.value == pytest.approx(1e8)
    with qtbot.waitSignal(panel.result_shown, timeout=TIMEOUT):
        panel.slider.setValue(panel.slider.maximum())
    assert panel.result.parameter.value == pytest.approx(1e9)
    # At 10^9 the textbook discriminant has lost every digit (b² ≈ 4e18 is rounded to multiples of 512).
    assert panel.result.naive_error >= 0.1 and panel.result.passed


def test_the_epsilon_choice_reaches_the_shadow_acne_case(qtbot, panel):
    _show(qtbot, panel, "shadow_acne")
    assert panel.result.naive_method == "fixed ε = 1e-06"
    with qtbot.waitSignal(panel.result_shown, timeout=TIMEOUT):
        panel.option.setCurrentIndex(panel.option.findText("0.01"))
    # At 10^11 a coordinate's rounding is about 1e-5, far below ε = 0.01: no acne left.
    assert panel.result.naive_method == "fixed ε = 0.01" and panel.result.naive_error == 0


def test_digits_after_the_first_difference_are_red():
    assert highlight_digits(3.0000001, 3.0000002) == '3.000000<span style="color:#ff5c5c">1</span>'
    assert highlight_digits(0.5, 0.5) == "0.5"
    assert "#6fd08c" in highlight_digits("misses", "misses") and "#ff5c5c" in highlight_digits("hit", "miss")


def test_slider_positions_map_onto_the_parameter_range_in_decades():
    parameter = hard_cases.run_case("far_sphere").parameter  # 1 .. 1e9, log
    assert slider_steps(parameter) == 9 * 20
    assert slider_value(parameter, 0) == 1.0 and slider_value(parameter, 180) == 1e9
    assert slider_value(parameter, slider_position(parameter)) == pytest.approx(1e8)


def test_a_panel_not_yet_shown_computes_nothing_then_shows_its_first_case(qtbot):
    widget = HardCasesPanel()  # as in the window: a tab behind the visible one
    qtbot.addWidget(widget)
    assert widget.result is None and widget.status.text() != "computing…"
    first = next(iter(hard_cases.CASES))
    with qtbot.waitSignal(widget.result_shown, timeout=TIMEOUT, check_params_cb=lambda shown: shown == first):
        widget.show()
    assert widget.result.name == first
    widget.shutdown()


def test_the_cases_are_worked_out_in_a_process_of_their_own(qtbot, panel, monkeypatch):
    # Most of a case is Python working number by number (exact rationals, one ray and triangle at a
    # time): on a thread of the window's process it held Python's lock in turns with the window's
    # thread, which then waited 110-180 ms at a time when "Rays through shared edges" was chosen.
    from core import helper_process

    here = []
    monkeypatch.setattr(hard_cases, "run_case", lambda *args, **kwargs: here.append(args))
    _show(qtbot, panel, "shared_edges")
    _show(qtbot, panel, "tangent")
    assert panel.result.name == "tangent" and "passes" in panel.verdict.text()
    assert here == []  # nothing was worked out in this process ...
    helper = helper_process._helpers.get(hard_cases.__name__)
    assert helper is not None and helper.process.poll() is None  # ... but in the cases' own process


def test_the_two_pictures_leave_the_wheel_to_the_details_scrolling_and_zoom_together_with_ctrl(qtbot, panel):
    _show(qtbot, panel, "shadow_acne")
    naive, robust = panel.naive_image, panel.robust_image
    qtbot.waitUntil(lambda: naive.qimage is not None and robust.qimage is not None)
    at = naive.rect().center()
    assert not wheel_over(naive, at, 1) and naive.zoom == 1.0  # left to the details, which scroll
    assert wheel_over(naive, at, 2, Qt.KeyboardModifier.ControlModifier)
    assert naive.zoom > 1 and robust.zoom == naive.zoom and robust.focus == naive.focus
