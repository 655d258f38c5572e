"""Transparency: opaque first, transparent far to near, c0 = a cs + (1 - a) cd."""

from __future__ import annotations

import numpy as np

from core import presets
from core.object_order import blending
from core.object_order.pipeline import RasterSettings, render_raster


def test_blend_over_is_the_lecture_formula():
    cs, cd = np.array([0.9, 0.2, 0.1]), np.array([0.1, 0.5, 0.7])
    assert np.allclose(blending.blend_over(0.4, cs, cd), [0.4 * 0.9 + 0.6 * 0.1, 0.4 * 0.2 + 0.6 * 0.5,
                                                         0.4 * 0.1 + 0.6 * 0.7])
    assert np.array_equal(blending.blend_over(1.0, cs, cd), cs)  # opaque replaces
    assert np.array_equal(blending.blend_over(0.0, cs, cd), cd)  # fully clear leaves as is


def test_draw_order_puts_opaque_first_and_sorts_transparent_far_to_near():
    transparent = np.array([True, False, True, True, False])
    depth = np.array([2.0, 9.0, 7.0, 2.0, 1.0])
    assert blending.draw_order(transparent, depth).tolist() == [1, 4, 2, 0, 3]  # ties keep order
    assert blending.draw_order(transparent, depth, sort=False).tolist() == [1, 4, 0, 2, 3]


def _pane_colours(scene):
    return {o.name: (np.asarray(o.material.color), o.material.opacity) for o in scene.objects}


def test_blend_terms_at_a_pixel_behind_three_panes_match_the_hand_computation():
    scene = presets.transparent_panes()
    result = render_raster(scene, RasterSettings(record_steps=True))
    names = [o.name for o in scene.objects]
    history = result.history
    # Find a pixel every pane and the box cover.
    for y, x in np.argwhere(np.isfinite(result.depth)):
        events = history.pixel_history(int(x), int(y))
        if {names[e.object_index] for e in events} == set(names):
            break
    else:
        raise AssertionError("no pixel behind all three panes")
    assert [names[e.object_index] for e in events] == ["opaque box", "blue pane", "green pane", "red pane"]
    assert all(e.passed for e in events)
    box_colour = events[0].color_after
    c = box_colour
    for e in events[1:]:  # far to near, each blended over what is there
        cs, alpha = e.blend.source, e.blend.alpha
        assert alpha == 0.5
        assert np.array_equal(e.blend.destination, c)
        c = alpha * cs + (1 - alpha) * c
        assert np.allclose(e.blend.result, c, atol=1e-15)
    assert np.allclose(result.color[y, x], c, atol=1e-15)
    assert result.stats["blends"] == int(result.draw.passed[result.draw.transparent].sum()) > 0


def test_sorting_matters_where_panes_overlap_and_nowhere_else():
    scene = presets.transparent_panes()
    names = [o.name for o in scene.objects]
    assert names[:3] == ["red pane", "green pane", "blue pane"]  # listed nearest first
    sorted_ = render_raster(scene, RasterSettings(record_steps=True))
    unsorted = render_raster(scene, RasterSettings(sort_transparent=False))
    assert [names[i] for i in sorted_.draw.object_index[-6:]][::2] == ["blue pane", "green pane", "red pane"]
    assert [names[i] for i in unsorted.draw.object_index[-6:]][::2] == ["red pane", "green pane", "blue pane"]
    differs = np.any(np.abs(sorted_.color - unsorted.color) > 1e-12, axis=-1)
    assert differs.sum() > 500
    panes_at = np.zeros(differs.shape, int)
    for p in np.flatnonzero(sorted_.draw.transparent):
        cols, rows, _, _ = sorted_.history.polygon_fragments(p)
        panes_at[rows, cols] += 1
    assert np.all(panes_at[differs] >= 2)  # only where two or more panes overlap
    # Unsorted, the nearest pane is drawn first and writes its depth: panes behind it fail.
    assert unsorted.stats["fragments_failed"] > sorted_.stats["fragments_failed"]
