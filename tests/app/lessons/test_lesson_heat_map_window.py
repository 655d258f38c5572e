"""A lesson step that turns the heat map on shows it over the traced image; a step that says
nothing of it (and follows none that does) turns it off."""

import numpy as np
from window_helpers import RENDER_TIMEOUT_MS

from core.lessons.lesson_file import shipped_lessons

LESSONS = shipped_lessons()


def test_the_acceleration_lessons_heat_map_step_shows_primitive_tests_over_the_grids_image(window, qtbot):
    k = next(i for i, lesson in enumerate(LESSONS) if lesson.id == "acceleration")
    step = next(i for i, s in enumerate(LESSONS[k].steps) if s.heat_map == "primitive tests")
    panel = window.tab("image order").widget
    window.lesson_panel.select(k, step)
    assert panel.heat.currentText() == "Primitive tests"

    def shown():
        result = window.last_result
        return (window.showing_full("image order") and isinstance(result, tuple)
                and result[1]["accel"]["method"] == "grid")

    qtbot.waitUntil(shown, timeout=RENDER_TIMEOUT_MS)
    image, stats, heat, _ = window.last_result
    assert panel.heat_scale.isVisible() and not np.array_equal(panel.image.rgb, image.rgb)
    assert f"{stats['accel']['prim_tests']:,} in all" in panel.heat_scale.units.text()

    window.lesson_panel.select(k, 0)  # an earlier step: no heat map
    assert panel.heat.currentText() == "Off" and not panel.heat_scale.isVisible()


def test_a_question_on_where_the_tests_go_shows_the_traced_image_without_its_heat_map_until_answered(
        window, qtbot):
    # "Before the heat map shows it: click a pixel whose primary ray hits nothing, yet is tested..."
    # The heat map colours exactly those pixels: shown, it would be the answer.
    from window_helpers import ask_exercise

    lesson = next(lesson for lesson in LESSONS if lesson.id == "acceleration")
    k = next(i for i, e in enumerate(lesson.exercises) if e.question.startswith("Before the heat map"))
    panel = window.tab("image order").widget
    exercises = ask_exercise(qtbot, window, "acceleration", lesson.exercises[k].step, k)
    assert panel.heat.currentText() == "Primitive tests"  # the step's choice stays
    qtbot.waitUntil(lambda: window.showing_full("image order") and isinstance(window.last_result, tuple),
                    timeout=RENDER_TIMEOUT_MS)
    image = window.last_result[0]

    def traced_alone():
        assert panel.heat_withheld.isVisible() and not panel.heat_scale.isVisible()
        assert panel.heat_withheld.text() == f"Heat map hidden until exercise {k + 1} is answered"
        assert np.array_equal(panel.image.rgb, image.rgb)

    qtbot.waitUntil(traced_alone)
    exercises.reveal()

    def heat_map_over_it():
        assert panel.heat_scale.isVisible() and not panel.heat_withheld.isVisible()
        assert not np.array_equal(panel.image.rgb, image.rgb)

    qtbot.waitUntil(heat_map_over_it, timeout=RENDER_TIMEOUT_MS)


def test_presenting_at_x2_the_heat_maps_withheld_note_is_scrolled_into_the_settings_view(
        qtbot, monkeypatch):
    # Presenting at x2 the settings column is taller than its view, and the note under the heat map's
    # choice came where the view ends, cut after its first line.
    from window_helpers import ask_exercise, presenting_on_1280x720

    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    lesson = next(lesson for lesson in LESSONS if lesson.id == "acceleration")
    k = next(i for i, e in enumerate(lesson.exercises) if e.question.startswith("Before the heat map"))
    panel = window.tab("image order").widget
    ask_exercise(qtbot, window, "acceleration", lesson.exercises[k].step, k)
    note, view = panel.heat_withheld, panel.column.viewport()

    def in_view():
        assert note.isVisible() and note.height() >= note.heightForWidth(note.width())
        top = note.mapTo(view, note.rect().topLeft()).y()
        assert top >= 0 and top + note.height() <= view.height(), (top, note.height(), view.height())
        return True

    qtbot.waitUntil(in_view, timeout=RENDER_TIMEOUT_MS)
    window.editor.stack.setClean()
    window.presentation.set_presenting(False)
