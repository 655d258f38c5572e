"""The window's state, in one place, with a signal per part that changes.

Everything the window shows follows from this model: the scene and its
camera, the image-order settings (:class:`TraceSettings`) and object-order
settings (:class:`RasterSettings`), the pixel picked in the traced image, the
pixel picked in the object-order buffers, the object-order step shown, and
which 3D overlays are switched on.  Panels write to it through its setters;
views subscribe to its signals; no widget keeps a copy of its own.

Every setter compares the new value with the current one and fires its
signal only when it really changed (napari's ``_check_if_differ``).  When a
new scene arrives, the parts that belong to the old scene (both picks and the
step) are cleared, so no view is left pointing at a pixel the new image
does not have.
"""

from __future__ import annotations

from dataclasses import replace

from PySide6.QtCore import QObject, Signal

from core.camera import Camera, camera_problems
from core.image_order.flat_scene import TraceSettings
from core.object_order.pipeline import RasterSettings
from core.scene import Scene

OVERLAYS = ("spheres", "grid", "walk", "frustum")
"""3D overlays a user switches on: bounding spheres, grid cells, the cells the picked ray walks,
the frustum's planes filled and labelled."""

Pixel = tuple[int, int]


class SceneModel(QObject):
    """The window's state, observable part by part.

    Signals
    -------
    camera_changed(Camera) : the observer moved or its lens changed.
    camera_refused(str) : a requested camera was unusable; the message says why
        (the current camera stays, and panels show it again).
    scene_changed(Scene) : a new scene (objects, lights, background and its own
        camera); listeners of the camera read it from the scene: ``camera_changed``
        does not fire too.
    trace_settings_changed(TraceSettings) : how the image-order tab renders.
    raster_settings_changed(RasterSettings) : which object-order stages run.
    ray_pixel_changed(object) : the pixel ``(x, y)`` whose ray tree is shown, or ``None``.
    buffer_pixel_changed(object) : the pixel ``(x, y)`` whose fragment history is
        shown in the object-order buffers, or ``None``.
    step_changed(object) : the object-order step shown (polygons drawn so far),
        or ``None`` for "the last step of the current render".
    overlays_changed(frozenset) : the names (from :data:`OVERLAYS`) switched on.
    selection_changed(object) : the scene item selected for editing, ``("object", i)``,
        ``("light", i)``, ``("background", 0)``, or ``None``.

    Attributes
    ----------
    memory_limit : renders estimated to need more memory than this many bytes
        are refused (:mod:`app.render_budget`); ``None``: half of the memory
        available when each would start.
    """

    camera_changed = Signal(object)
    camera_refused = Signal(str)
    scene_changed = Signal(object)
    trace_settings_changed = Signal(object)
    raster_settings_changed = Signal(object)
    ray_pixel_changed = Signal(object)
    buffer_pixel_changed = Signal(object)
    step_changed = Signal(object)
    overlays_changed = Signal(frozenset)
    selection_changed = Signal(object)

    def __init__(self, scene: Scene, parent: QObject | None = None, memory_limit: int | None = None):
        super().__init__(parent)
        self.memory_limit = memory_limit
        self._scene = scene
        self._trace = TraceSettings()
        self._raster = RasterSettings(record_steps=True)
        self._ray_pixel: Pixel | None = None
        self._buffer_pixel: Pixel | None = None
        self._step: int | None = None
        self._overlays: frozenset[str] = frozenset()
        self._selection: tuple[str, int] | None = None
        self.scene_was_edited = False
        """Whether the last new scene was an edit of the one before (:meth:`set_scene`)."""

    # ------------------------------------------------------------ scene
    @property
    def scene(self) -> Scene:
        return self._scene

    @property
    def camera(self) -> Camera:
        return self._scene.camera

    def set_camera(self, camera: Camera) -> bool:
        """Use ``camera`` if it is valid and different; return whether it was taken."""
        if camera == self._scene.camera:
            return False
        problems = camera_problems(camera)
        if problems:
            self.camera_refused.emit("; ".join(f"{field}: {message}" for field, message in problems))
            return False
        self._scene = replace(self._scene, camera=camera)
        self._clamp_picks()
        self.camera_changed.emit(camera)
        return True

    def update_camera(self, **changes) -> bool:
        """Change some camera fields (see :meth:`core.camera.Camera.replace`)."""
        return self.set_camera(self.camera.replace(**changes))

    def set_scene(self, scene: Scene, edit: bool = False) -> None:
        """Replace the whole scene; picks and step are cleared.

        ``edit`` says it is the same scene changed by the editor (the 3D pane keeps its
        view, a selection that still exists stays); otherwise it is a new scene (a file,
        an example, a lesson step) and the selection is cleared too.
        """
        if scene == self._scene:
            return
        self._scene = scene
        self.scene_was_edited = edit
        if not edit or not self._exists(self._selection):
            self.set_selection(None)
        self.set_ray_pixel(None)
        self.set_buffer_pixel(None)
        self.set_step(None)
        self.scene_changed.emit(scene)

    # --------------------------------------------------------- settings
    @property
    def trace_settings(self) -> TraceSettings:
        return self._trace

    def set_trace_settings(self, settings: TraceSettings) -> None:
        if settings != self._trace:
            self._trace = settings
            self.trace_settings_changed.emit(settings)

    @property
    def raster_settings(self) -> RasterSettings:
        return self._raster

    def set_raster_settings(self, settings: RasterSettings) -> None:
        if settings != self._raster:
            self._raster = settings
            self.raster_settings_changed.emit(settings)

    # ------------------------------------------------------------ picks
    @property
    def ray_pixel(self) -> Pixel | None:
        return self._ray_pixel

    def set_ray_pixel(self, pixel: Pixel | None) -> None:
        """Pick the traced image's pixel ``(x, y)`` (``None``, or outside the image: no pick)."""
        pixel = self._inside(pixel)
        if pixel != self._ray_pixel:
            self._ray_pixel = pixel
            self.ray_pixel_changed.emit(pixel)

    @property
    def buffer_pixel(self) -> Pixel | None:
        return self._buffer_pixel

    def set_buffer_pixel(self, pixel: Pixel | None) -> None:
        """Pick the object-order buffers' pixel ``(x, y)`` (``None``, or outside the image: no pick)."""
        pixel = self._inside(pixel)
        if pixel != self._buffer_pixel:
            self._buffer_pixel = pixel
            self.buffer_pixel_changed.emit(pixel)

    @property
    def step(self) -> int | None:
        return self._step

    def set_step(self, step: int | None) -> None:
        """Show the object-order buffers after ``step`` polygons (``None``: after the last)."""
        step = None if step is None else max(0, int(step))
        if step != self._step:
            self._step = step
            self.step_changed.emit(step)

    # --------------------------------------------------------- overlays
    @property
    def overlays(self) -> frozenset[str]:
        return self._overlays

    def set_overlay(self, name: str, shown: bool) -> None:
        """Switch the 3D overlay ``name`` (one of :data:`OVERLAYS`) on or off."""
        if name not in OVERLAYS:
            raise ValueError(f"overlay must be one of {list(OVERLAYS)}, got {name!r}")
        overlays = self._overlays | {name} if shown else self._overlays - {name}
        if overlays != self._overlays:
            self._overlays = overlays
            self.overlays_changed.emit(overlays)

    # -------------------------------------------------------- selection
    @property
    def selection(self) -> tuple[str, int] | None:
        return self._selection

    def set_selection(self, item: tuple[str, int] | None) -> None:
        """Select ``item`` (see ``selection_changed``) for editing; a missing one selects nothing."""
        item = item if self._exists(item) else None
        if item != self._selection:
            self._selection = item
            self.selection_changed.emit(item)

    def _exists(self, item) -> bool:
        if item is None:
            return False
        kind, index = item
        if kind == "background":
            return index == 0
        items = {"object": self._scene.objects, "light": self._scene.lights}.get(kind, ())
        return 0 <= index < len(items)

    # ------------------------------------------------------------ helpers
    def _inside(self, pixel: Pixel | None) -> Pixel | None:
        if pixel is None:
            return None
        x, y = int(pixel[0]), int(pixel[1])
        cam = self.camera
        return (x, y) if 0 <= x < cam.width and 0 <= y < cam.height else None

    def _clamp_picks(self) -> None:
        """A new image size drops picks that fell outside it."""
        self.set_ray_pixel(self._ray_pixel)
        self.set_buffer_pixel(self._buffer_pixel)
