"""The rasterization lesson's "Your turn" step shows a triangle not yet filled: its edges, dashed, over
the empty grid, so the student sees which pixel centres lie on which edge before working out what the
top-left rule gives them; scrubbed to the step that draws it, the edges are drawn solid."""

import numpy as np
from window_helpers import RENDER_TIMEOUT_MS

from core.lessons.lesson_file import shipped_lessons

LESSONS = shipped_lessons()


def test_the_triangle_to_come_is_drawn_dashed_over_the_empty_grid(window, qtbot):
    k = next(i for i, lesson in enumerate(LESSONS) if lesson.id == "rasterization")
    step = LESSONS[k].steps[2]
    assert "(2, 2), (12, 2) and (8, 10)" in step.text  # its corners, as its words give them
    window.lesson_panel.select(k, 2)
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: window.showing_full("object order") and panel.image.edges is not None,
                    timeout=RENDER_TIMEOUT_MS)
    assert window.model.step == 0 and not panel.image._highlight  # nothing drawn yet
    assert panel.image.grid_shown() and panel.image.edges_coming
    # Pixel (i, j)'s centre is at (i + 0.5, j + 0.5) in the image's pixel coordinates.
    expected = {(2.5, 2.5), (12.5, 2.5), (8.5, 10.5)}
    assert {tuple(np.round(c, 9)) for c in panel.image.edges} == expected
    window.model.set_step(1)  # scrubbed on: the triangle drawn, its edges solid
    qtbot.waitUntil(lambda: not panel.image.edges_coming and panel.image.edges is not None)
    assert {tuple(np.round(c, 9)) for c in panel.image.edges} == expected
