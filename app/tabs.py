"""The main window's tabs: each knows how to render the scene for its view, off the GUI thread.

A tab builds a *job* for the current scene (see :mod:`app.workers`), and
shows the job's result in its widget.  The main window runs only the visible
tab's job and marks the others stale until they are shown.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from core.image_order.ray_tracing import TraceSettings, merge_band_stats, render_trace
from core.object_order import three_views
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Scene
from views.image_grid import ImageGrid
from views.image_order_panel import ImageOrderPanel
from views.object_order_panel import ObjectOrderPanel

BAND_ROWS = 32


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms"


class ImageOrderTab:
    """What the observer sees, traced in image order: a coarse image at once, then band by band."""

    title = "Image order"
    COARSE_STEP = 4

    def __init__(self):
        self.widget = ImageOrderPanel()

    def job(self, scene: Scene):
        settings = self.widget.settings

        def run(cancelled, progress):
            cam = scene.camera
            coarse = render_trace(scene, settings, step=self.COARSE_STEP)
            color = coarse.color.copy()
            progress(0, color.copy())
            bands = []
            for first in range(0, cam.height, BAND_ROWS):
                if cancelled.is_set():
                    return None
                band = render_trace(scene, settings, rows=(first, min(first + BAND_ROWS, cam.height)))
                color[first:first + len(band.color)] = band.color
                bands.append(band)
                progress(round(100 * (first + len(band.color)) / cam.height), color.copy())
            return color, merge_band_stats([b.stats for b in bands])

        return run

    def show_progress(self, percent, partial) -> None:
        self.widget.image.set_image(partial)

    def show(self, result) -> str:
        color, stats = result
        self.widget.image.set_image(color)
        self.widget.show_stats(stats)
        w, h = stats["size"]
        times = stats["times"]
        return (f"{w} × {h} pixels · {stats['rays']['total']:,} rays · "
                + " · ".join(f"{k} {_ms(v)}" for k, v in times.items() if k != "total")
                + f" · total {_ms(times['total'])}")


class ObjectOrderTab:
    """Object order step by step: the recorded z-buffer render of the observer's view."""

    title = "Object order"

    def __init__(self):
        self.widget = ObjectOrderPanel()

    def job(self, scene: Scene):
        settings = self.widget.settings

        def run(cancelled, progress):
            return scene, render_raster(scene, settings)

        return run

    def show(self, result) -> str:
        scene, raster = result
        self.widget.show_result(raster, scene)
        s = raster.stats
        return (f"{len(raster.draw)} polygons drawn · {s.get('fragments_generated', 0):,} fragments · "
                f"total {_ms(sum(s['times'].values()))}")


class FourViewsTab:
    """The lecture's four views: front, side and top orthographic, and the observer's perspective."""

    title = "Four views"
    PANES = [("front", "Front view (orthographic)"), ("side", "Side view (orthographic)"),
             ("top", "Top view (orthographic)"), ("observer", "Observer's view")]

    def __init__(self):
        self.widget = ImageGrid(self.PANES, columns=2)

    def job(self, scene: Scene):
        cam = scene.camera
        cameras = {**three_views.orthographic_views(scene, cam.width, cam.height), "observer": cam}

        def run(cancelled, progress):
            images = {}
            for i, (key, camera) in enumerate(cameras.items()):
                if cancelled.is_set():
                    return None
                raster = render_raster(replace(scene, camera=camera), RasterSettings())
                images[key] = (raster.color, sum(raster.stats["times"].values()))
                progress(round(100 * (i + 1) / len(cameras)), None)
            return images

        return run

    def show(self, images) -> str:
        for key, (rgb, seconds) in images.items():
            self.widget.set_image(key, rgb, f"z-buffer render in {_ms(seconds)}")
        return "front, side and top: parallel projection along the axes"


class CompareTab:
    """Orthographic, perspective and ray-traced images of the same scene, with their cost."""

    title = "Compare"
    PANES = [("orthographic", "Orthographic (z-buffer)"), ("perspective", "Perspective (z-buffer)"),
             ("traced", "Ray traced (image order)")]

    def __init__(self):
        self.widget = ImageGrid(self.PANES, columns=2)

    def job(self, scene: Scene):
        cam = scene.camera
        ortho_height = 2 * cam.distance * np.tan(np.radians(cam.fov_y_deg) / 2)

        def run(cancelled, progress):
            out = {}
            for key, projection in (("orthographic", "orthographic"), ("perspective", "perspective")):
                camera = cam.replace(projection=projection, ortho_height=ortho_height)
                raster = render_raster(replace(scene, camera=camera), RasterSettings())
                out[key] = (raster.color, sum(raster.stats["times"].values()), "z-buffer")
                progress(33 if key == "orthographic" else 66, None)
                if cancelled.is_set():
                    return None
            traced = render_trace(replace(scene, camera=cam.replace(projection="perspective")),
                                  TraceSettings())
            rays = traced.stats["rays"]["total"]
            out["traced"] = (traced.color, traced.stats["times"]["total"], f"ray tracing, {rays:,} rays,")
            return out

        return run

    def show(self, images) -> str:
        for key, (rgb, seconds, method) in images.items():
            self.widget.set_image(key, rgb, f"{method} in {_ms(seconds)}")
        return "the same scene and observer, three ways"
