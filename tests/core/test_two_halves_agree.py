"""Object order and image order tell the same story: the same surfaces at the same depths."""

from dataclasses import replace

import numpy as np
import pytest

from core import presets
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.object_order.pipeline import SPHERE_RINGS, render_raster
from core.presets_trace import PRESETS_TRACE
from core.scene import Sphere

SCENES = {**{k: b for k, (_, b) in presets.PRESETS.items()},
          "mirror_and_glass": PRESETS_TRACE["mirror_and_glass"][1]}


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
@pytest.mark.parametrize("preset", ["lecture", "culling_notched", "frustum_cases", "mirror_and_glass"])
def test_first_hit_depth_equals_the_z_buffer_depth(preset, projection):
    scene = SCENES[preset]()
    scene = replace(scene, camera=scene.camera.replace(projection=projection, width=160, height=120))
    raster = render_raster(scene)
    traced = render_trace(scene, TraceSettings(mode="raycast"))
    seen_r, seen_t = np.isfinite(raster.depth), np.isfinite(traced.depth)
    assert seen_r.any()
    assert np.mean(seen_r == seen_t) > 0.99  # coverage: only pixels on silhouettes may differ
    both = seen_r & seen_t
    hit = traced.object_index
    on_sphere = np.zeros_like(both)
    for i, obj in enumerate(scene.objects):
        if isinstance(obj, Sphere):
            on_sphere |= hit == i
    flat = both & ~on_sphere
    rel = np.abs(raster.depth[flat] - traced.depth[flat]) / raster.depth[flat]
    assert np.quantile(rel, 0.99) < 1e-9  # planar faces: the same plane, the same depth
    # Object order draws an analytic sphere as polygons inscribed in it, rings pi / RINGS apart:
    # their sag r (1 - cos(pi / RINGS)) bounds the difference, away from silhouettes.
    for i, obj in enumerate(scene.objects):
        pixels = both & (hit == i)
        if isinstance(obj, Sphere) and pixels.sum() > 20:
            sag = obj.radius * (1 - np.cos(np.pi / SPHERE_RINGS))
            diff = np.abs(raster.depth[pixels] - traced.depth[pixels])
            assert np.quantile(diff, 0.9) <= sag * 1.5
