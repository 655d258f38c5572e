"""Spheres the loader accepts but too small to have any area (radius 1e-300, 5e-324) go through
every pipeline and export picture without an exception (issue 35).  Tessellated for the
z-buffer, all their triangles have zero area, so nothing of them is drawn: every picture is the
background alone, and they have no outlines.  (Before issue 35 the four views and the cost sweep's
visible surface ended in IndexError.)"""

from __future__ import annotations

import numpy as np
import pytest

from app.picture_sheet import four_views
from core import scene_file
from core.accuracy.tessellation import tessellated
from core.accuracy.visible_surface import rasterized_surface, traced_surface
from core.compare import compare
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.object_order.outlines import feature_edges
from core.object_order.pipeline import render_raster

TINY = scene_file.from_dict({
    "camera": {"eye": [3, 4, 6], "target": [0, 0, 0], "width": 32, "height": 24},
    "lights": [{"position": [5, 5, 5]}],
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1e-300},
                {"type": "sphere", "center": [1, 0, 0], "radius": 5e-324}],
})


def test_a_sphere_without_area_has_no_outline():
    mesh = tessellated(TINY, 16, 32).objects[0]
    assert len(mesh.triangles) > 0
    assert feature_edges(mesh, TINY.camera).shape == (0, 2, 3)


def test_the_z_buffer_draws_nothing_of_them_and_says_so():
    result = render_raster(TINY)
    background = np.broadcast_to(TINY.background, result.color.shape)
    assert np.allclose(result.color, background)
    assert np.isinf(result.depth).all()
    assert (rasterized_surface(TINY).object_index == -1).all()


@pytest.mark.parametrize("mode", ["raycast", "raytrace"])
def test_rays_miss_them(mode):
    result = render_trace(TINY, TraceSettings(mode=mode))
    assert (result.object_index == -1).all()
    assert (traced_surface(TINY).object_index == -1).all()


@pytest.mark.parametrize("pipeline", ["raster", "raytrace"])
def test_the_four_views_sheet_is_drawn(pipeline):
    traced = None if pipeline == "raster" else (lambda view: render_trace(view, TraceSettings()).color)
    sheet = four_views(TINY, pipeline, traced)
    assert sheet.ndim == 3 and np.isfinite(sheet).all()


@pytest.mark.parametrize("a, b", [("orthographic", "raytrace"), ("perspective", "raycast")])
def test_a_comparison_of_them_finds_no_difference(a, b):
    # Both outputs are the background alone, so they agree exactly.
    result = compare(TINY, a, b, TraceSettings())
    assert result.difference.magnitude.max() == 0.0
    assert result.explanation
