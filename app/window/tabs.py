"""The main window's tabs: each knows how to render the scene for its view, off the GUI thread.

A tab is any object with

- ``title`` : the tab's label; the window finds it by name,
  ``window.tab("image order")`` (case does not matter);
- optionally ``short_title`` : its label when the tab bar is too narrow for the titles
  (:mod:`views.text.tab_titles`);
- ``widget`` : the QWidget shown under the tab;
- ``overlays`` : names of the 3D-pane overlays that belong to it (shown only
  while it is visible; see :mod:`views.scene3d.scene_overlays`);
- ``job(scene, preview)`` : a job for :class:`app.renders.Renderer` that
  renders ``scene`` for this tab, or ``None`` if the tab has nothing to
  render (a panel that computes on its own, like Hard cases: then its ``idle``
  text says where the work happens, in the progress bar).  With
  ``preview`` true the job is a coarse, quick one, shown
  while the observer moves (about a quarter of the pixels, upscaled, marked
  "preview"); otherwise it is the full render;
- ``show(result) -> str`` : show a finished job's result; returns the status line;
- optionally ``shutdown()`` : stop the tab's own background work (the window is closing);
- optionally ``changes`` : signals after which the tab's image is out of date (its own
  settings changed); it renders again when visible;
- optionally ``show_progress(partial)`` : show a partial result while a job runs;
- optionally ``warning(scene) -> str | None`` : a word before a very long full render;
- optionally ``pictures()`` : what File → Export offers for this tab, instead of
  every image pane of ``widget`` (see :mod:`app.export.pane_pictures`).
- optionally ``cost(scene, preview)`` : what ``job(scene, preview)`` will cost, a
  :class:`core.budget.Estimate`; a job over the memory budget never starts
  (see :mod:`app.render_budget`).

Adding a tab is one line: append its class to :data:`TABS` (it is built as
``cls(model)`` with the window's :class:`app.window.state.SceneModel`).

Images are converted for display (:func:`views.images.image_view.display_image`)
inside the jobs, on the worker thread, so the GUI thread only paints.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from app.export.compare_pictures import comparison_pictures
from app.renders import Renderer, Waiting
from core import budget
from core.accuracy.supersampling import trace_adaptive
from core.accuracy.sweep import ADAPTIVE_N
from core.camera import Camera
from core.compare import compare
from core.first_look import first_look
from core.image_order import ray_tracing
from core.image_order.ray_tracing import TraceSettings, merge_band_stats, render_trace
from core.in_words import counted
from core.object_order import four_views, pipeline
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Mesh, Scene
from views.images.image_grid import ImageGrid
from views.images.image_view import display_image
from views.images.step_picture import step_picture
from views.panels.compare_panel import ComparePanel, ComparisonImages
from views.panels.cost_panel import CostPanel
from views.panels.hard_cases_panel import HardCasesPanel
from views.panels.image_order_panel import ImageOrderPanel
from views.panels.object_order_panel import ObjectOrderPanel
from views.scene3d.scene_overlays import IMAGE_ORDER_OVERLAYS, OBJECT_ORDER_OVERLAYS

BAND_ROWS = 32
PREVIEW_STEP = 2
"""Previews render one pixel in every PREVIEW_STEP x PREVIEW_STEP block: a quarter of the pixels."""
PREVIEW = "preview"
FIRST_LOOK = "first look: numpy, no shadows or mirrors, while the renderer compiles"
COMPILING = "compiling the {}'s kernels"
WHY_COMPILING = "once per machine and version of the code; a minute or two"
SLOW_TESTS = 2e9
"""Ray–object tests above which a full render without acceleration gets a warning (minutes here)."""
ADAPTIVE_SEED = 0
"""The seed of adaptive supersampling's jitter: the same scene and settings give the same image."""
BAND_TESTS = 5e7
"""Without acceleration, a band holds at most about this many ray–object tests (a fraction of a
second), so that a newer camera or Cancel stops the render soon."""


def _tests_per_row(scene: Scene) -> int:
    """Ray–object tests one image row costs when every ray tests every primitive."""
    primitives = sum(len(o.triangles) if isinstance(o, Mesh) else 1 for o in scene.objects)
    return scene.camera.width * max(primitives, 1) * (1 + len(scene.lights))


@dataclass(frozen=True)
class Preview:
    """A preview job's result: the coarse image (marked "preview"), its camera and what it cost."""

    image: object  # views.images.image_view.DisplayImage
    camera: Camera
    seconds: float
    rays: int = 0


def _ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f} ms"


def _trace_caption(stats: dict) -> str:
    """Size, rays and total time of a traced image, then the stages that took a millisecond or more
    (the Counts and times table lists them all): short enough for two lines at a lecture-hall size."""
    w, h = stats["size"]
    times = stats["times"]
    stages = " · ".join(f"{k} {v * 1000:.0f}" for k, v in times.items() if k != "total" and v >= 0.0005)
    return (f"{w} × {h} pixels · {stats['rays']['total']:,} rays · total {_ms(times['total'])}"
            + (f" ({stages} ms)" if stages else ""))


def preview_camera(camera: Camera) -> Camera:
    """The same observer with PREVIEW_STEP times fewer pixels each way."""
    return camera.replace(width=max(1, -(-camera.width // PREVIEW_STEP)),
                          height=max(1, -(-camera.height // PREVIEW_STEP)))


def upscale(rgb: np.ndarray, width: int, height: int) -> np.ndarray:
    """A coarse image repeated block by block to ``width`` x ``height`` (nearest neighbour)."""
    rows = np.minimum(np.arange(height) // PREVIEW_STEP, rgb.shape[0] - 1)
    cols = np.minimum(np.arange(width) // PREVIEW_STEP, rgb.shape[1] - 1)
    return rgb[rows][:, cols]


def _raster_preview(scene: Scene) -> tuple[np.ndarray, float]:
    """A quick z-buffer image of ``scene`` from a quarter of the pixels, at full size; and its time."""
    cam = scene.camera
    raster = render_raster(replace(scene, camera=preview_camera(cam)), RasterSettings())
    return upscale(raster.color, cam.width, cam.height), sum(raster.stats["times"].values())


def _cost(scene: Scene, preview: bool, runs, shown_images: int) -> budget.Estimate:
    """The cost of ``runs`` (``(mode, accel, max_depth)`` renders made one after another, of a
    quarter of the pixels for a preview) whose results fill ``shown_images`` full-size images."""
    view = replace(scene, camera=preview_camera(scene.camera)) if preview else scene
    cam = scene.camera
    return budget.combined([budget.estimate(view, *run) for run in runs], cam.width * cam.height,
                           shown_images)


def say_if_compiling(progress, scene: Scene, renderer: str, ready: bool, picture: bool = True) -> None:
    """Before a job's first render: if its kernels are not compiled on this machine yet (``ready``
    false), say in the progress bar that they compile, and show a first look at ``scene`` meanwhile."""
    if not ready:
        image = display_image(first_look(scene), FIRST_LOOK) if picture else None
        progress(0, Waiting(COMPILING.format(renderer), WHY_COMPILING, image))


def preview_trace_settings(settings: TraceSettings) -> TraceSettings:
    """Previews never go without acceleration: the image is the same, the wait is not."""
    return settings if settings.accel != "none" else replace(settings, accel="bvh")


class ImageOrderTab:
    """What the observer sees, traced in image order: a coarse image at once, then band by band;
    with adaptive supersampling on, then the supersampled image.

    A full render's result is ``(image, stats, heat, adaptive)``: the image shown, the counts of
    the rays through the pixel centres, their tests per pixel (H, W, 2), and the
    :class:`core.accuracy.supersampling.AdaptiveImage` (``None`` while adaptive supersampling is off).
    """

    title = "Image order"
    short_title = "Image"
    overlays = IMAGE_ORDER_OVERLAYS

    def __init__(self, model):
        self.model = model
        self.widget = ImageOrderPanel(model)
        self.changes = (self.widget.adaptive_changed,)
        self._preview: Preview | None = None  # the last preview shown, a start for the full render

    def warning(self, scene: Scene) -> str | None:
        settings = self.model.trace_settings
        if settings.accel != "none":
            return None
        triangles = sum(len(o.triangles) if isinstance(o, Mesh) else 1 for o in scene.objects)
        tests = scene.camera.height * _tests_per_row(scene)
        if tests < SLOW_TESTS:
            return None
        return (f"Acceleration 'None': every ray tests all {triangles:,} triangles, about "
                f"{tests:.1e} tests; this render may take minutes (Esc cancels; previews use the BVH)")

    def cost(self, scene: Scene, preview: bool) -> budget.Estimate:
        s = preview_trace_settings(self.model.trace_settings) if preview else self.model.trace_settings
        return _cost(scene, preview, [(s.mode, s.accel, s.max_depth)], 1)

    def job(self, scene: Scene, preview: bool):
        settings = self.model.trace_settings
        cam = scene.camera
        if preview:
            def run(cancelled, progress):
                quick = preview_trace_settings(settings)
                say_if_compiling(progress, scene, "tracer", ray_tracing.compiled_for(quick.accel))
                coarse = render_trace(scene, quick, step=PREVIEW_STEP)
                return Preview(display_image(coarse.color, PREVIEW), cam, coarse.stats["times"]["total"],
                               coarse.stats["rays"]["total"])

            return run
        shown = self._preview if self._preview is not None and self._preview.camera == cam else None
        threshold = self.widget.adaptive_threshold
        rows = BAND_ROWS
        if settings.accel == "none":
            rows = max(1, min(BAND_ROWS, int(BAND_TESTS // _tests_per_row(scene))))

        def run(cancelled, progress):
            say_if_compiling(progress, scene, "tracer", shown is not None or all(
                ray_tracing.compiled_for(s.accel) for s in (settings, preview_trace_settings(settings))))
            if shown is not None:  # the bands replace the preview already on screen
                color = shown.image.rgb.copy()
            else:
                color = render_trace(scene, preview_trace_settings(settings), step=2 * PREVIEW_STEP).color
                progress(0, display_image(color, PREVIEW))
            bands = []
            for first in range(0, cam.height, rows):
                if cancelled.is_set():
                    return None
                band = render_trace(scene, settings, rows=(first, min(first + rows, cam.height)), heat=True)
                color[first:first + len(band.color)] = band.color
                bands.append(band)
                done = first + len(band.color)
                progress(round(100 * done / cam.height),
                         display_image(color.copy(), "" if done == cam.height else "rendering…"))
            adaptive = None
            if threshold is not None:
                progress(100, display_image(color.copy(), "adaptive supersampling…"))
                adaptive = trace_adaptive(scene, settings, threshold, ADAPTIVE_N,
                                          np.random.default_rng(ADAPTIVE_SEED))
                color = adaptive.color
            return (display_image(color), merge_band_stats([b.stats for b in bands]),
                    np.concatenate([b.heat for b in bands]), adaptive)  # each pixel's tests, for the heat map

        return run

    def show_progress(self, partial) -> None:
        self.widget.show_traced(partial)

    def show(self, result) -> str:
        if isinstance(result, Preview):
            self._preview = result
            self.widget.show_traced(result.image)
            return f"preview: a quarter of the rays ({result.rays:,}) in {_ms(result.seconds)}"
        image, stats, heat, adaptive = result
        self.widget.show_traced(image, heat, adaptive)
        self.widget.show_stats(stats)
        if adaptive is None:
            return _trace_caption(stats)
        return (_trace_caption(stats) + f" · adaptive supersampling: {int(adaptive.refined.sum()):,} pixels "
                f"refined, {adaptive.traced:,} rays more")


class ObjectOrderTab:
    """Object order step by step: the recorded z-buffer render of the observer's view."""

    title = "Object order"
    short_title = "Object"
    overlays = OBJECT_ORDER_OVERLAYS

    def __init__(self, model):
        self.model = model
        self.widget = ObjectOrderPanel(model)

    def cost(self, scene: Scene, preview: bool) -> budget.Estimate:
        return _cost(scene, preview, [("raster",)], 1 if preview else 2)  # full: image and z-buffer

    def show_progress(self, partial) -> None:  # the first look while the rasterizer compiles
        self.widget.show_preview(partial)

    def job(self, scene: Scene, preview: bool):
        settings = self.model.raster_settings
        if preview:
            def run(cancelled, progress):
                say_if_compiling(progress, scene, "rasterizer", pipeline.ensure_compiled.ready())
                rgb, seconds = _raster_preview(scene)
                return Preview(display_image(rgb, PREVIEW), scene.camera, seconds)

            return run

        model = self.model

        def run(cancelled, progress):  # the step's picture too: the window only paints it
            say_if_compiling(progress, scene, "rasterizer", pipeline.ensure_compiled.ready())
            raster = render_raster(scene, settings)
            n = raster.history.n_steps
            # The model's step once rendered, not when asked: a lesson step sets its scene (which
            # starts this render) and then its step; a picture of another step is made again on
            # the GUI thread.  (An int read from the model: a worker may read it.)
            step = model.step
            return scene, raster, step_picture(raster, scene, n if step is None else min(step, n))

        return run

    def show(self, result) -> str:
        if isinstance(result, Preview):
            self.widget.show_preview(result.image)
            return f"preview: a quarter of the pixels, without steps, in {_ms(result.seconds)}"
        scene, raster, picture = result
        self.widget.show_result(raster, scene, picture)
        s = raster.stats
        return (f"{counted(len(raster.draw), 'polygon')} drawn · "
                f"{counted(s.get('fragments_generated', 0), 'fragment')} · "
                f"total {_ms(sum(s['times'].values()))}")


class FourViewsTab:
    """The lecture's four views: front, side and top orthographic, and the observer's perspective."""

    title = "Four views"
    short_title = "Views"
    overlays = ()
    PANES = list(four_views.PANES)

    def __init__(self, model):
        self.model = model
        self.widget = ImageGrid(self.PANES, columns=2)

    def cost(self, scene: Scene, preview: bool) -> budget.Estimate:
        views = 1 if preview else len(self.PANES)
        return _cost(scene, preview, [("raster",)] * views, views)

    def job(self, scene: Scene, preview: bool):
        cameras = four_views.four_cameras(scene)
        if preview:  # the three axis views do not depend on the observer
            cameras = {"observer": scene.camera}

        def run(cancelled, progress):
            say_if_compiling(progress, scene, "rasterizer", pipeline.ensure_compiled.ready(), picture=False)
            images = {}
            for i, (key, camera) in enumerate(cameras.items()):
                if cancelled.is_set():
                    return None
                view = replace(scene, camera=camera)
                if preview:
                    rgb, seconds = _raster_preview(view)
                    images[key] = (display_image(rgb, PREVIEW), seconds)
                else:
                    color, seconds = four_views.inked_view(scene, camera)
                    images[key] = (display_image(color), seconds)
                progress(round(100 * (i + 1) / len(cameras)), None)
            return images

        return run

    def show(self, images) -> str:
        for key, (image, seconds) in images.items():
            self.widget.set_image(key, image, f"z-buffer {image.note or 'render'} in {_ms(seconds)}")
        if set(images) == {"observer"}:
            return f"preview of the observer's view in {_ms(images['observer'][1])}"
        return "front, side and top: parallel projection along the axes, framed on the objects, edges inked"


class CompareTab:
    """Any two outputs of the scene side by side, their difference image, one pixel read in both."""

    title = "Compare"
    overlays = ()

    def __init__(self, model):
        self.model = model
        self.widget = ComparePanel()
        self.changes = (self.widget.pair_changed, model.trace_settings_changed)
        self._reader = Renderer(self.widget)  # reads a picked pixel in both outputs
        self._reader.finished.connect(self.widget.show_pixel)
        self.widget.pixel_picked.connect(self._read_pixel)

    def cost(self, scene: Scene, preview: bool) -> budget.Estimate:
        modes = {"orthographic": "raster", "perspective": "raster", "raycast": "raycast",
                 "raytrace": "raytrace"}
        settings = self._settings(preview)
        runs = [(modes[key], settings.accel, settings.max_depth) for key in self.widget.pair()]
        return _cost(scene, preview, runs, 3)  # A, B and their difference

    def _settings(self, preview: bool) -> TraceSettings:
        """The tracer's settings; a preview's with an acceleration, whose time no caption shows."""
        return preview_trace_settings(self.model.trace_settings) if preview else self.model.trace_settings

    def job(self, scene: Scene, preview: bool):
        a, b = self.widget.pair()
        settings = self._settings(preview)
        cam = scene.camera
        picked = self.widget.picked
        inside = picked is not None and picked[0] < cam.width and picked[1] < cam.height
        pixel = picked if inside and not preview else None
        rendered = replace(scene, camera=preview_camera(cam)) if preview else scene

        def run(cancelled, progress):
            ready = pipeline.ensure_compiled.ready() and ray_tracing.compiled_for(settings.accel)
            say_if_compiling(progress, scene, "renderers", ready, picture=False)

            def carry_on():  # output A is rendered
                progress(50, None)
                return not cancelled.is_set()

            comparison = compare(rendered, a, b, settings, carry_on=carry_on)  # as `export --what compare`
            if comparison is None:
                return None
            diff = comparison.difference
            images = {key: display_image(upscale(rgb, cam.width, cam.height) if preview else rgb,
                                         PREVIEW if preview else "")
                      for key, rgb in (("a", comparison.a.color), ("b", comparison.b.color),
                                       ("difference", diff.colored))}
            return ComparisonImages(comparison, images, display_image(diff.colorbar()), preview, pixel,
                                    None if pixel is None else comparison.pixel(*pixel))

        return run

    def show(self, shown) -> str:
        self._reader.cancel()  # a pixel read from the comparison this one replaces
        self.widget.show_comparison(shown)
        if not shown.preview and self.widget.picked not in (None, shown.pixel):
            self._read_pixel(*self.widget.picked)  # picked while this comparison rendered
        c = shown.comparison
        if shown.preview:
            return f"preview: {c.a.title} against {c.b.title}, a quarter of the pixels"
        return (f"{c.a.title} against {c.b.title}: they differ visibly at "
                f"{100 * c.difference.visible_fraction:.1f}% of the pixels, by at most "
                f"{c.difference.scale:.3f} (linear RGB)")

    def _read_pixel(self, x: int, y: int) -> None:
        shown = self.widget.shown
        if shown is None or shown.preview:
            return  # read when the full comparison arrives
        self._reader.submit(lambda cancelled, progress: ((x, y), shown.comparison.pixel(x, y)))

    def pictures(self):
        """File → Export: outputs A and B, the difference with its scale, the whole comparison."""
        return comparison_pictures(self.title, self.widget.shown)

    def shutdown(self) -> None:
        """Stop reading a pixel (the window is closing)."""
        self._reader.cancel()


class _SelfComputingTab:
    """A tab whose panel computes on its own (its own controls start it): the window renders nothing
    for it, and it shows no overlays."""

    overlays = ()

    def job(self, scene: Scene, preview: bool):
        return None

    def show(self, result) -> str:
        return ""


class HardCasesTab(_SelfComputingTab):
    """Where the formulas meet finite precision: each case computes in its own panel, on first show
    (the cases do not depend on the scene)."""

    title = "Hard cases"
    idle = "Hard cases: pick a case and move its slider; the panel works it out at once"

    def __init__(self, model):
        self.model = model
        self.widget = HardCasesPanel()

    def shutdown(self) -> None:
        """Stop the panel's background computations (the window is closing)."""
        self.widget.shutdown()


class CostTab(_SelfComputingTab):
    """What a knob (resolution, objects, lights, depth) costs each order; it sweeps the model's scene
    (a sweep starts from the panel's Run button)."""

    title = "Cost"
    idle = "Cost: choose a knob and press Run; the sweep shows its progress in the panel"

    def __init__(self, model):
        self.model = model
        self.widget = CostPanel()
        self.widget.memory_limit = model.memory_limit
        self.widget.set_scene(model.scene)
        model.scene_changed.connect(self.widget.set_scene)

    def shutdown(self) -> None:
        """Cancel a running sweep (the window is closing)."""
        self.widget.cancel()


TABS = (ImageOrderTab, ObjectOrderTab, FourViewsTab, CompareTab, HardCasesTab, CostTab)
"""The window's tabs, in order; each is built as ``cls(model)``."""
