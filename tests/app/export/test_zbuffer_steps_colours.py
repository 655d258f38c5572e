"""The z-buffer steps' frames mark each step's polygon without hiding its colour."""

import numpy as np

from app.export.animation_frames import PASSED_TINT, zbuffer_steps
from app.export.picture_sheet import MARGIN, TITLE_ROW
from core.object_order.pipeline import RasterSettings, render_raster
from core.presets import zbuffer_three_polygons


def test_each_steps_polygon_keeps_its_own_colour_inside_its_outline():
    # The lecture's figure: three polygons drawn green, blue and yellow.  Their fragments were
    # filled half magenta, so no polygon ever showed its own colour in the animation.
    scene = zbuffer_three_polygons()
    settings = RasterSettings(record_steps=True)
    history = render_raster(scene, settings).history
    count, frames = zbuffer_steps(scene, settings)
    frames = list(frames)
    assert count == len(frames) == history.n_steps + 1
    w, h = scene.camera.width, scene.camera.height
    x, y = MARGIN, MARGIN + TITLE_ROW  # the image memory panel, top left of each frame
    for k in range(1, count):
        shown = frames[k][y:y + h, x:x + w]
        drawn, _ = history.buffers(k)  # the image memory after k polygons, unmarked
        cols, rows, _, passed = history.polygon_fragments(k - 1)
        mask = np.zeros((h, w), bool)
        mask[rows[passed], cols[passed]] = True
        padded = np.pad(mask, 1)
        inside = mask & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
        assert inside.sum() > 0, k
        # (the sheet holds 8-bit sRGB levels: a colour moves by at most half a level)
        assert np.allclose(shown[inside], drawn[inside], atol=0.01), k  # the polygon's own colour
        edge = mask & ~inside
        assert np.allclose(shown[edge], PASSED_TINT, atol=0.01), k  # outlined, so the step is seen
