"""The lecture's four views of a scene, as the Four views tab and ``export --what four-views`` draw them.

The front, side and top orthographic views (framed on the objects, see
:mod:`core.object_order.three_views`) and the observer's own view, each
drawn by the z-buffer with its feature edges inked over it
(:mod:`core.object_order.outlines`), so a face seen edge-on stays visible.
The window's tab and the command line both draw each view with
:func:`inked_view`, so their pictures are the same.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from core.camera import Camera
from core.object_order import outlines
from core.object_order.pipeline import RasterSettings, render_raster
from core.object_order.three_views import orthographic_views
from core.scene import Scene

PANES = (("front", "Front view (orthographic)"), ("side", "Side view (orthographic)"),
         ("top", "Top view (orthographic)"), ("observer", "Observer's view"))
"""The views, by key and title, in the order they are laid out (row by row, two columns)."""


def four_cameras(scene: Scene) -> dict[str, Camera]:
    """The cameras of the four views, by the keys of :data:`PANES` (in that order)."""
    cam = scene.camera
    return {**orthographic_views(scene, cam.width, cam.height), "observer": cam}


def inked_view(scene: Scene, camera: Camera) -> tuple[np.ndarray, float]:
    """``scene`` seen by ``camera``, drawn by the z-buffer with its edges inked: (H, W, 3) linear
    RGB and the render's time in seconds."""
    raster = render_raster(replace(scene, camera=camera), RasterSettings())
    color = outlines.outlined(raster.color, raster.depth, raster.meshes, camera)
    return color, sum(raster.stats["times"].values())
