"""Spheres the loader accepts but too small to have any area (radius 1e-300, 5e-324) go through
every pipeline without an exception (issue 35).  Tessellated for the
z-buffer, all their triangles have zero area, so nothing of them is drawn: every picture is the
background alone, and they have no outlines.  (Before issue 35 the cost sweep's visible surface ended in
IndexError; the export pictures are tested in ``tests/app/export/test_degenerate_sheet.py``.)"""

from __future__ import annotations

import numpy as np
import pytest
from degenerate_scenes import TINY

from core.accuracy.tessellation import tessellated
from core.accuracy.visible_surface import rasterized_surface, traced_surface
from core.compare import compare
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.object_order.outlines import feature_edges
from core.object_order.pipeline import render_raster


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


@pytest.mark.parametrize("a, b", [("orthographic", "raytrace"), ("perspective", "raycast")])
def test_a_comparison_of_them_finds_no_difference(a, b):
    # Both outputs are the background alone, so they agree exactly.
    result = compare(TINY, a, b, TraceSettings())
    assert result.difference.magnitude.max() == 0.0
    assert result.explanation
