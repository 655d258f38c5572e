"""bench gui's actions: each row does what it names, the timer sees a stall it is handed, and --cold
prints a first-run table and a warm one.  (No figure of the window's own stalls is asserted: that is
what the benchmark measures.)"""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest
from checkout import ROOT

from app.bench import gui

STALL_S = 0.3


def _stall():
    time.sleep(STALL_S)


@pytest.mark.gui
def test_an_actions_row_counts_a_deliberate_stall_and_names_where_it_was(qapp):
    row = gui._bench_action(qapp, None, "a deliberate stall", [(_stall, lambda: True)] * 2, why=True)
    assert row["tab"] == "a deliberate stall" and row["count"] == 2
    # The timer should tick every TICK_MS; across the sleep it could not, so one tick came that late.
    assert row["longest"] >= 1000 * STALL_S - gui.TICK_MS
    assert row["p99"] <= row["longest"]
    assert [line.split()[-1] for line in row["why"][1:]] == ["_stall"]  # the stack, cut at the bench's loop


def _record(signal) -> list:
    seen = []
    signal.connect(seen.append)
    return seen


@pytest.mark.gui
def test_the_new_rows_edit_export_present_and_resize_the_text_and_leave_the_window_as_it_was(qapp, window,
                                                                                           monkeypatch):
    monkeypatch.setattr(gui, "AFTER_S", 0.05)  # what is checked is what each step did, not its stalls
    scene, editor = window.model.scene, window.editor
    scenes = _record(window.model.scene_changed)
    row = gui._bench_action(qapp, window, "scene edits", gui._scene_edits(window), why=False)
    # Moved, coloured, a sphere added then deleted, and the four undone, each shown in full.
    assert row["count"] == 8 and len(scenes) == 8
    n = len(scene.objects)
    assert [len(s.objects) for s in scenes] == [n, n, n + 1, n, n + 1, n, n, n]
    assert scenes[0].objects[0] != scene.objects[0] and scenes[-1] == scene
    assert editor.stack.count() == 4 and editor.stack.index() == 0

    written = _record(window.exports.exported)
    row = gui._bench_action(qapp, window, "exports", gui._exports(window), why=False)
    assert row["count"] == 3
    assert [os.path.basename(path) for path in written] == ["pane.png", "3d.png", "steps.gif"]

    presenting = _record(window.presentation.presenting_changed)
    row = gui._bench_action(qapp, window, "presentation on/off", gui._presentation(window), why=False)
    assert row["count"] == 4 and presenting == [True, False, True, False]

    scales = _record(window.presentation.scale_changed)
    row = gui._bench_action(qapp, window, "text size", gui._text_sizes(window), why=False)
    assert row["count"] == 3 and scales == [1.5, 2.0, 1.0]
    assert not window.lesson_panel.typesetting()


@pytest.mark.gui
def test_the_picks_row_picks_pixels_in_both_pipelines_each_shown_in_turn(qapp, window, monkeypatch):
    monkeypatch.setattr(gui, "AFTER_S", 0.05)  # what is checked is what each step did, not its stalls
    traced, rasterized = _record(window.model.ray_pixel_changed), _record(window.model.buffer_pixel_changed)
    row = gui._bench_action(qapp, window, "picked pixels", gui._picks(window), why=False)
    assert row["count"] == 2 * gui.PICKS
    assert len(set(traced)) == len(set(rasterized)) == gui.PICKS  # 12 pixels of each image, all apart
    x, y = rasterized[-1]
    caption = window.tab("object order").widget.history_caption.text()
    assert caption.startswith(f"Pixel ({x}, {y}): ")  # its fragments' history shown
    assert window.ray_tree[:2] == traced[-1]
    cam = window.model.camera
    assert all(0 <= px < cam.width and 0 <= py < cam.height for px, py in [*traced, *rasterized])


@pytest.mark.gui
def test_the_lesson_row_steps_through_every_step_the_panel_holds_and_reads_no_file_meanwhile(window,
                                                                                        monkeypatch):
    # Reading the 16 lesson files on the GUI thread, inside the row's clock, was charged to the window.
    from core.lessons import lesson_file

    read = []
    monkeypatch.setattr(lesson_file, "load_lesson", lambda path: read.append(path))
    steps = list(gui._lesson_steps(window))
    assert read == []
    assert len(steps) == sum(len(lesson.steps) for lesson in window.lesson_panel.lessons()) == 35
    start, _ = steps[-1]
    start()
    last = len(window.lesson_panel.lessons()) - 1
    assert window.lesson_panel.step_index() == (last, len(window.lesson_panel.lessons()[last].steps) - 1)


@pytest.mark.gui
def test_cold_prints_the_actions_with_an_empty_formula_cache_then_warm():
    argv = ["bench", "gui", "--seconds", "0.2", "--size", "800x600", "--actions", "present,text", "--cold"]
    out = subprocess.run([sys.executable, "-m", "app", *argv], cwd=ROOT, capture_output=True, text=True,
                         timeout=600)
    assert out.returncode == 0 and "Traceback" not in out.stderr, out.stderr
    lines = out.stdout.splitlines()
    first = lines.index("first run (an empty formula cache):")
    warm = lines.index("warm (the formulas on disk):")
    for at in (first, warm):
        assert lines[at + 1].split() == ["action", "count", "longest", "stall", "p99", "stall"]
        rows = {line[:24].strip(): line[24:].split() for line in lines[at + 2:at + 4]}
        assert set(rows) == {"presentation on/off", "text size"}
        assert rows["presentation on/off"][0] == "4" and rows["text size"][0] == "3"
        for words in rows.values():  # count, longest stall, p99 stall
            assert words[2] == "ms" and words[4] == "ms" and float(words[1]) >= float(words[3]) >= 0


@pytest.mark.gui
def test_the_hard_cases_row_chooses_every_case_and_moves_its_slider_to_both_ends(qapp, window, monkeypatch):
    from core import hard_cases

    monkeypatch.setattr(gui, "AFTER_S", 0.05)  # what is checked is what each step did, not its stalls
    panel = window.tab("hard cases").widget
    shown = _record(panel.result_shown)
    row = gui._bench_action(qapp, window, "hard cases and sliders", gui._hard_cases(window), why=False)
    assert window.current.title == "Hard cases"
    assert set(shown) == set(hard_cases.CASES)  # every case on screen in turn
    with_slider = [name for name, case in hard_cases.CASES.items() if case.parameter is not None]
    assert 8 <= len(with_slider) < len(hard_cases.CASES)
    # Each case chosen once (the first is on screen already), and each slider taken to both ends
    # (where it does not start there).
    chosen = len(hard_cases.CASES) - 1
    assert chosen + len(with_slider) <= row["count"] <= chosen + 2 * len(with_slider)
    assert panel.result.name == list(hard_cases.CASES)[-1]
    assert panel.slider.value() == panel.slider.maximum()
