"""The heat maps in the window: tests a pixel over the traced image, fragments a pixel over image memory."""

import threading

import heat_scenes as hs
import numpy as np
import verdict_scenes as vs
from window_helpers import RENDER_TIMEOUT_MS


def _choose(combo, key):
    combo.setCurrentIndex(combo.findData(key))


def _heat_shown(qtbot, window, panel, accel):
    _choose(panel.accel, accel)

    def shown():
        result = window.last_result
        return (window.showing_full("image order") and isinstance(result, tuple)
                and result[1]["accel"]["method"] == accel)

    qtbot.waitUntil(shown, timeout=RENDER_TIMEOUT_MS)
    image, stats, heat, adaptive = window.last_result
    assert adaptive is None  # adaptive supersampling is off
    return image, stats, heat


def test_heat_map_over_the_traced_image_adds_up_to_the_counters(qtbot, window):
    panel = window.tab("image order").widget
    image, stats, heat = _heat_shown(qtbot, window, panel, "bvh")
    assert np.array_equal(panel.image.rgb, image.rgb)  # off: the traced image as it is
    assert not panel.heat_scale.isVisible()

    _choose(panel.heat, "prim")
    qtbot.waitUntil(lambda: window.showing_full("image order") and panel.heat_scale.isVisible())
    assert not np.array_equal(panel.image.rgb, image.rgb)
    assert heat[..., 0].sum() == stats["accel"]["prim_tests"] > 0
    assert panel.heat_scale.high.text() == f"{heat[..., 0].max():,}"
    assert f"{stats['accel']['prim_tests']:,} in all" in panel.heat_scale.units.text()
    bvh_mean = heat[..., 0].mean()

    _choose(panel.heat, "bounds")
    qtbot.waitUntil(lambda: f"{stats['accel']['bounds_tests']:,} in all" in panel.heat_scale.units.text())

    _, stats, heat = _heat_shown(qtbot, window, panel, "none")  # the heat map stays chosen
    assert panel.heat_scale.isVisible() and heat[..., 0].sum() == stats["accel"]["prim_tests"]
    assert heat[..., 0].mean() > bvh_mean  # without acceleration every ray tests every primitive

    _choose(panel.heat, "off")
    assert np.array_equal(panel.image.rgb, window.last_result[0].rgb)
    assert not panel.heat_scale.isVisible()


def test_a_chosen_heat_map_is_laid_over_the_image_off_the_gui_thread(qtbot, window, monkeypatch):
    # Colouring the tests and laying them over the image held the GUI thread a quarter of a second
    # at the lesson step that turns the heat map on.
    from views.images import color_scale

    panel = window.tab("image order").widget
    image, stats, heat = _heat_shown(qtbot, window, panel, "bvh")
    on_gui_thread, real = [], color_scale.heat_map
    monkeypatch.setattr(color_scale, "heat_map", lambda counts, what: on_gui_thread.append(
        threading.current_thread() is threading.main_thread()) or real(counts, what))
    _choose(panel.heat, "prim")
    qtbot.waitUntil(lambda: panel.heat_scale.isVisible() and window.showing_full("image order"))
    assert on_gui_thread == [False]
    assert panel.heat_scale.high.text() == f"{heat[..., 0].max():,}"
    assert not np.array_equal(panel.image.rgb, image.rgb)
    assert f"{stats['accel']['prim_tests']:,} in all" in panel.heat_scale.units.text()


def _heats(panel):
    return [panel.heat.itemText(i) for i in range(panel.heat.count())]


def test_adaptive_supersamplings_samples_per_pixel_in_the_heat_map(qtbot, window):
    panel = window.tab("image order").widget
    window.model.set_scene(hs.flat_edge())
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    assert "Samples per pixel" not in _heats(panel)  # adaptive supersampling is off
    plain = panel.image.rgb.copy()
    assert np.all(plain[:, :24] == 1.0) and np.all(plain[:, 25:] == 0.0)  # one ray through each centre

    panel.adaptive.setChecked(True)  # the image is out of date: it renders again
    assert _heats(panel)[-1] == "Samples per pixel"
    qtbot.waitUntil(lambda: window.showing_full("image order") and window.last_result[3] is not None,
                    timeout=RENDER_TIMEOUT_MS)
    adaptive = window.last_result[3]
    assert np.array_equal(adaptive.samples, hs.flat_edge_samples())  # worked in the scene's docstring
    assert np.all((panel.image.rgb[:, 24] > 0) & (panel.image.rgb[:, 24] < 1))  # the edge's pixels mixed
    assert np.array_equal(panel.image.rgb[:, :24], plain[:, :24])  # flat: the corners' own colour
    assert "adaptive supersampling: 30 pixels refined, 1,751 rays more" in window.status_caption.text()

    _choose(panel.heat, "samples")
    qtbot.waitUntil(lambda: window.showing_full("image order") and panel.heat_scale.isVisible())
    assert (panel.heat_scale.low.text(), panel.heat_scale.high.text()) == ("0", "17")
    assert "30 pixels refined, 1,751 rays traced" in panel.heat_scale.units.text()
    shown = panel.image.rgb
    # Over the edge the heat's brightest colour, elsewhere the colour for 1 sample: two colours a row.
    assert all(len({tuple(c) for c in row[:24]}) == 1 and len({tuple(c) for c in row[25:]}) == 1
               for row in shown)
    assert not np.array_equal(shown[:, 24], adaptive.color[:, 24])

    panel.adaptive.setChecked(False)  # the choice goes with it: the heat map is off
    assert "Samples per pixel" not in _heats(panel)
    assert panel.heat.currentData() == "off" and not panel.heat_scale.isVisible()
    qtbot.waitUntil(lambda: window.showing_full("image order") and window.last_result[3] is None,
                    timeout=RENDER_TIMEOUT_MS)
    assert np.array_equal(panel.image.rgb, plain)


def test_overdraw_heat_map_in_the_object_order_pane_follows_the_steps(qtbot, window):
    window.model.set_scene(vs.pane_over_box())
    window.show_tab("object order")
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    plain = panel.image.rgb.copy()
    panel.overdraw.setChecked(True)
    qtbot.waitUntil(panel.overdraw_scale.isVisible)
    assert not np.array_equal(panel.image.rgb, plain)
    # From straight above, the box shows only its top (its sides and bottom are back faces, culled)
    # and the pane lies over it: at most 2 fragments reach a pixel.
    assert panel.overdraw_scale.high.text() == "2"
    total = panel.result.stats["fragments_generated"]
    assert f"{total:,} in all" in panel.overdraw_scale.units.text()
    panel.scrubber.set_step(0)
    qtbot.waitUntil(lambda: panel.overdraw_scale.high.text() == "0")
    panel.overdraw.setChecked(False)
    panel.scrubber.last()
    qtbot.waitUntil(lambda: not panel.overdraw_scale.isVisible())
    assert np.array_equal(panel.image.rgb, plain)
