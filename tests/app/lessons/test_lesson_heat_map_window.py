"""A lesson step that turns the heat map on shows it over the traced image; a step that says
nothing of it (and follows none that does) turns it off."""

import numpy as np
from window_helpers import RENDER_TIMEOUT_MS

from core.files.lesson_file import shipped_lessons

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
