"""The four views' export sheet of spheres too small to have any area: drawn, the background alone
(before issue 35 it ended in IndexError)."""

import numpy as np
import pytest
from degenerate_scenes import TINY

from app.export.picture_sheet import four_views
from core.image_order.ray_tracing import TraceSettings, render_trace


@pytest.mark.parametrize("pipeline", ["raster", "raytrace"])
def test_the_four_views_sheet_is_drawn(pipeline):
    traced = None if pipeline == "raster" else (lambda view: render_trace(view, TraceSettings()).color)
    sheet = four_views(TINY, pipeline, traced)
    assert sheet.ndim == 3 and np.isfinite(sheet).all()
