"""Why this pixel, in the window: a picked pixel's verdict stands above its tables in every image pane.

The scenes and their worked answers are in ``tests/verdict_scenes.py``.
"""

import verdict_scenes as vs
from PySide6.QtCore import Qt
from window_helpers import RENDER_TIMEOUT_MS


def _show(qtbot, window, scene, tab: str):
    window.model.set_scene(scene)
    window.show_tab(tab)
    qtbot.waitUntil(lambda: window.showing_full(tab), timeout=RENDER_TIMEOUT_MS)
    return window.tab(tab).widget


def _click(qtbot, view, x: int, y: int) -> None:
    qtbot.mouseClick(view, Qt.MouseButton.LeftButton, pos=view.widget_pos(x, y).toPoint())


def _raster_pick(qtbot, window, scene):
    panel = _show(qtbot, window, scene, "object order")
    _click(qtbot, panel.image, *vs.PIXEL)
    assert panel.picked == vs.PIXEL  # the 40 x 30 image is shown larger than its pixels
    assert panel.verdict.isVisible()
    return panel


def test_object_order_pane_says_what_decided_the_picked_pixel(qtbot, window):
    panel = _raster_pick(qtbot, window, vs.back_face_only())
    assert panel.verdict.shown.verdict == "culled"
    assert "Culled: only back faces cover this pixel (triangle 1 of ground)" in panel.verdict.text()
    assert panel.history.rowCount() == 0  # nothing was drawn there: the table is empty, the sentence says why
    assert panel.history_caption.text() == "Pixel (22, 14): 0 fragments up to step 0."  # none drawn

    panel = _raster_pick(qtbot, window, vs.before_near_plane())
    assert (panel.verdict.shown.verdict, panel.verdict.shown.fragments[0].plane) == ("clipped", "near")
    assert "near plane" in panel.verdict.text()

    panel = _raster_pick(qtbot, window, vs.beyond_far_plane())
    assert (panel.verdict.shown.verdict, panel.verdict.shown.fragments[0].plane) == ("frustum-culled", "far")
    assert "Why pixel (22, 14): Culled by the frustum at the far plane" in panel.verdict.text()
    assert "clipped" not in panel.verdict.text().lower()

    panel = _raster_pick(qtbot, window, vs.pane_over_box())
    verdict = panel.verdict.shown
    assert (verdict.verdict, verdict.object) == ("blended", "pane")
    assert sorted((f.object, f.fate) for f in verdict.fragments) == [
        ("box", "culled"), ("box", "kept"), ("pane", "blended")]
    assert panel.history.rowCount() == 2  # the drawn ones: the box's top face and the pane
    assert panel.history_caption.text().startswith("Pixel (22, 14): 2 fragments up to step ")
    assert "Why pixel (22, 14):" in panel.verdict.text() and "Blended" in panel.verdict.text()


def test_one_fragment_is_one_fragment(qtbot, window):
    # The rasterization lesson's picked pixel (3, 7): the triangle's one fragment ("1 fragments" before).
    from core.lessons.lesson_file import shipped_lessons

    k = [lesson.id for lesson in shipped_lessons()].index("rasterization")
    window.lesson_panel.select(k, 0)
    panel = window.tab("object order").widget
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    caption = panel.history_caption
    qtbot.waitUntil(lambda: caption.text().startswith("Pixel (3, 7)"), timeout=RENDER_TIMEOUT_MS)
    assert panel.history_caption.text() == "Pixel (3, 7): 1 fragment up to step 1."
    assert panel.history.rowCount() == 1
    # and the tab's status line: one triangle drawn ("1 polygons drawn" before)
    status = window.renders.status(window.tab("object order"))[2]
    assert status.startswith("1 polygon drawn · ") and " fragments · total " in status


def test_object_order_verdict_follows_the_step_scrubber(qtbot, window):
    panel = _raster_pick(qtbot, window, vs.two_quads(near_first=False))
    assert (panel.verdict.shown.verdict, panel.verdict.shown.object) == ("visible", "near")
    panel.scrubber.set_step(2)  # only the far quad's two triangles drawn so far
    assert panel.verdict.shown.object == "far" and "After 2 polygons" in panel.verdict.text()
    panel.scrubber.last()
    assert panel.verdict.shown.object == "near"
    window.model.set_buffer_pixel(None)
    assert not panel.verdict.isVisible()


def _traced_pick(qtbot, window, scene, pixel=(20, 15)):
    panel = _show(qtbot, window, scene, "image order")
    with qtbot.waitSignal(window._tree_renderer.finished, timeout=RENDER_TIMEOUT_MS):
        _click(qtbot, panel.image, *pixel)
    assert panel.image.picked == pixel
    assert panel.verdict.isVisible()
    return panel.verdict.shown


def test_image_order_pane_says_what_decided_the_picked_pixel(qtbot, window):
    verdict = _traced_pick(qtbot, window, vs.ball_shadow())
    assert (verdict.verdict, verdict.object) == ("hit", "floor")
    assert [(light.name, light.lit, light.blocked_by) for light in verdict.lights] == [
        ("sun", False, "ball"), ("fill", True, None)]

    verdict = _traced_pick(qtbot, window, vs.mirror_ball())
    assert verdict.object == "mirror" and "reflected ray, which hits wall" in verdict.sentence

    verdict = _traced_pick(qtbot, window, vs.glass_ball())
    assert verdict.object == "glass" and "R = 0.04" in verdict.sentence and "T = 0.96" in verdict.sentence


def test_compare_tab_puts_both_sentences_side_by_side_and_says_why_they_differ(qtbot, window):
    panel = _show(qtbot, window, vs.ball_shadow(), "compare")
    for combo, key in zip(panel.selectors, ("perspective", "raycast"), strict=True):
        combo.setCurrentIndex(combo.findData(key))
    qtbot.waitUntil(lambda: window.showing_full("compare") and panel.boxes["b"].title() == "B: ray cast",
                    timeout=RENDER_TIMEOUT_MS)
    _click(qtbot, panel.views["a"], 20, 15)
    qtbot.waitUntil(lambda: panel.readout[0].rgb is not None, timeout=RENDER_TIMEOUT_MS)
    assert panel.views["a"].picked == (20, 15)
    zbuffer, tracer, why = (row.found.text() for row in panel.readout)
    assert "of floor is kept by the z-buffer" in zbuffer
    assert "in the shadow of ball for sun" in tracer
    assert "a shadow only the tracer computes (ball blocks sun)" in why
