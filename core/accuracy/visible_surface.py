"""The visible surface: which object each pixel centre sees, and how far away.

Both pipelines answer the lecture's visibility question at the pixel
centres: the tracer by the first hit of the primary ray, the rasterizer by
the fragment that passed the z-test last.  Comparing these maps between two
renders shows silhouettes that moved and surfaces put in the wrong order.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tracing import render_trace
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Scene


@dataclass(frozen=True, eq=False)
class VisibleSurface:
    """What each pixel centre sees.

    Attributes
    ----------
    object_index : (H, W) int64, index into ``scene.objects``, -1 for background.
    depth : (H, W) float64, distance along the viewing axis (scene units), ``inf`` for background.
    """

    object_index: np.ndarray
    depth: np.ndarray


def traced_surface(scene: Scene, settings: TraceSettings = TraceSettings(mode="raycast")) -> VisibleSurface:
    """The first hits of the primary rays through the pixel centres."""
    result = render_trace(scene, settings)
    return VisibleSurface(result.object_index, result.depth)


def rasterized_surface(scene: Scene, settings: RasterSettings | None = None) -> VisibleSurface:
    """The object of the last fragment that passed the z-test at each pixel centre."""
    result = render_raster(scene, replace(settings or RasterSettings(), record_steps=True))
    history = result.history
    fragments = history.fragments
    polygon = np.repeat(np.arange(history.n_steps), np.diff(history.offsets))
    passed = np.flatnonzero(fragments.passed)
    last = np.full(history.width * history.height, -1, dtype=np.int64)
    np.maximum.at(last, fragments.pixel[passed].astype(np.int64), passed)
    objects = np.full(last.shape, -1, dtype=np.int64)  # no fragment passed (nothing drawn): background
    objects[last >= 0] = history.object_index[polygon[last[last >= 0]]]
    return VisibleSurface(objects.reshape(history.height, history.width), result.depth)
