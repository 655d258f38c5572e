"""The heat maps in the window: tests a pixel over the traced image, fragments a pixel over image memory."""

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
    image, stats, heat = window.last_result
    return image, stats, heat


def test_heat_map_over_the_traced_image_adds_up_to_the_counters(qtbot, window):
    panel = window.tab("image order").widget
    image, stats, heat = _heat_shown(qtbot, window, panel, "bvh")
    assert np.array_equal(panel.image.rgb, image.rgb)  # off: the traced image as it is
    assert not panel.heat_scale.isVisible()

    _choose(panel.heat, "prim")
    assert panel.heat_scale.isVisible()
    assert not np.array_equal(panel.image.rgb, image.rgb)
    assert heat[..., 0].sum() == stats["accel"]["prim_tests"] > 0
    assert panel.heat_scale.high.text() == f"{heat[..., 0].max():,}"
    assert f"{stats['accel']['prim_tests']:,} in all" in panel.heat_scale.units.text()
    bvh_mean = heat[..., 0].mean()

    _choose(panel.heat, "bounds")
    assert f"{stats['accel']['bounds_tests']:,} in all" in panel.heat_scale.units.text()

    _, stats, heat = _heat_shown(qtbot, window, panel, "none")  # the heat map stays chosen
    assert panel.heat_scale.isVisible() and heat[..., 0].sum() == stats["accel"]["prim_tests"]
    assert heat[..., 0].mean() > bvh_mean  # without acceleration every ray tests every primitive

    _choose(panel.heat, "off")
    assert np.array_equal(panel.image.rgb, window.last_result[0].rgb)
    assert not panel.heat_scale.isVisible()


def test_overdraw_heat_map_in_the_object_order_pane_follows_the_steps(qtbot, window):
    window.model.set_scene(vs.pane_over_box())
    window.show_tab("object order")
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    plain = panel.image.rgb.copy()
    panel.overdraw.setChecked(True)
    assert panel.overdraw_scale.isVisible() and not np.array_equal(panel.image.rgb, plain)
    # From straight above, the box shows only its top (its sides and bottom are back faces, culled)
    # and the pane lies over it: at most 2 fragments reach a pixel.
    assert panel.overdraw_scale.high.text() == "2"
    total = panel.result.stats["fragments_generated"]
    assert f"{total:,} in all" in panel.overdraw_scale.units.text()
    panel.scrubber.set_step(0)
    assert panel.overdraw_scale.high.text() == "0"
    panel.overdraw.setChecked(False)
    panel.scrubber.last()
    assert np.array_equal(panel.image.rgb, plain) and not panel.overdraw_scale.isVisible()
