"""The 3D scene pane: the objects, the observer and its viewing pyramid.

It shows the scene from the outside, from a free overview camera the user
can rotate with the mouse, so the observer's own camera appears as an object:
a small camera glyph at the eye, a marker at the target it looks at, the
frustum (translucent, with its edges), and the screen rectangle on the near
plane.

The observer can be moved here too: drag the camera glyph to move the eye
(the target stays), drag the target marker to look elsewhere (the eye
stays), and scroll over the glyph to widen or narrow the viewing angle.  A
drag moves the point in the plane through it that faces the overview camera.

The pane follows the model (:class:`app.window.state.SceneModel`): when the camera
changes, the observer's actors keep their identity and only their points or
transform change, and several changes within one frame are drawn once
(:data:`FRAME_MS`), so moving the observer never queues up renders.  While
it moves, the pane is drawn without anti-aliasing and the frustum by its
edges only (its translucent faces cover much of the pane and cost a
software OpenGL more than the rest of the scene together); once it rests
for :data:`SMOOTH_AFTER_MS`, it is drawn once more with both.  VTK draws
off screen and the pane paints the picture (:mod:`views.scene3d.image_plotter`),
so a draw never makes Qt compose the whole window through OpenGL.
"""

from __future__ import annotations

import contextlib
import functools
import itertools
import time

import numpy as np
import pyvista as pv
from PySide6.QtCore import QEvent, QObject, QPointF, Qt, QTimer
from PySide6.QtWidgets import QVBoxLayout, QWidget
from vtkmodules.vtkCommonCore import VTK_FONT_FILE
from vtkmodules.vtkRenderingCore import vtkActor2D, vtkPolyDataMapper, vtkTextRenderer
from vtkmodules.vtkRenderingLabel import vtkLabeledDataMapper

from core.camera import Camera
from core.scene import Scene, Sphere
from views.scene3d import vtk_convert
from views.scene3d.framing import MARGIN, fit_view, label_bounds
from views.scene3d.image_plotter import ImagePlotter
from views.scene3d.label_placement import GAP_PX, broken, in_pane, place_nearest, uncross
from views.scene3d.projector_lines import PROJECTOR_OVERLAY
from views.scene3d.scene_colors import FRUSTUM_COLOR, SCREEN_COLOR
from views.scene3d.scene_overlays import label_font_file

TARGET_COLOR = "#ff8c42"
FRAME_MS = 33
"""Shortest time between two draws of the pane (about 30 per second)."""
SMOOTH_AFTER_MS = 300
"""After this long without a change the pane is drawn again with anti-aliasing (FXAA) and the
frustum's translucent faces."""
GRAB_RADIUS_PX = 14
"""How close (pixels) the mouse must be to the eye or target to grab it."""
FOV_STEP_DEG = 2.0
"""Viewing-angle change per mouse-wheel notch over the glyph."""
LIGHT_MARKER = 0.18
"""Radius (scene units) of the sphere that shows a light in the 3D pane (and that a click selects)."""
FOV_RANGE_DEG = (1.0, 179.0)
FRAMED_OVERLAYS = ("frustum",)
"""Overlays the pane's framing keeps inside it, their labels whole (what a lesson talks about)."""
HIGHLIGHT_OVERLAY = "lesson"
"""The overlay that marks what a lesson step talks about (see :meth:`SceneView.look_from`)."""
SHOWN_WITH = {PROJECTOR_OVERLAY: "frustum"}
"""Overlays shown exactly when another is (:meth:`SceneView.show_overlays_only` names that one)."""
HELD_MS = 10
"""How long after :meth:`SceneView.held` ends the changes it held are made: a timer's turn of the event
loop, after the one that lays out and paints what else changed."""
ENCLOSING_OPACITY = 0.25
"""A sphere the observer stands inside (as in the lecture's exercise) is drawn this translucent,
so that the observer and its rays inside stay visible."""

def _unit_glyph() -> pv.PolyData:
    """The camera glyph in the observer's own frame, size 1: a box with a lens cone along -z."""
    body = pv.Cube(center=(0.0, 0.0, 0.0), x_length=1.0, y_length=1.0, z_length=1.0)
    lens = pv.Cone(center=(0.0, 0.0, -0.9), direction=(0.0, 0.0, 1.0), height=0.8, radius=0.45,
                   resolution=24)
    return body.merge(lens)


def glyph_size(camera: Camera) -> float:
    """Edge of the camera glyph's box, scene units: a fixed share of the eye–target distance."""
    return 0.07 * max(camera.distance, 1.0)


def _held(change):
    """A change of the pane that waits, in order, while :meth:`SceneView.held` holds changes or others
    wait."""
    @functools.wraps(change)
    def make_or_wait(self, *args):
        if (self._holding or self._waiting) and not self._catching_up:
            self._waiting.append((change, args))
        else:
            change(self, *args)
    return make_or_wait


def _current(question):
    """A question about the pane: the changes that wait are made before it is answered."""
    @functools.wraps(question)
    def answer(self, *args):
        self.catch_up()
        return question(self, *args)
    return answer


class SceneView(QWidget):
    """A pyvista view of the model's scene with its observer, which the mouse can move.

    Attributes
    ----------
    frustum : the drawn viewing pyramid (8 points, near then far plane, as
        :meth:`core.camera.Camera.frustum_corners` orders them).
    screen : the drawn screen rectangle on the near plane.
    """

    def __init__(self, model, parent: QWidget | None = None, plotter: ImagePlotter | None = None):
        super().__init__(parent)
        self.model = model
        self.plotter = ImagePlotter(self) if plotter is None else plotter  # made beforehand, or here
        # Translucent surfaces are blended in drawing order: VTK's order-independent
        # translucency costs a software OpenGL extra passes over the whole pane (nearly half
        # of a draw), and the few translucent surfaces here barely overlap.
        self.plotter.renderer.SetUseOIT(False)
        self.plotter.set_background("#1d2230", top="#3a4358")
        self.line_scale = 1.0  # lines, points, labels and axes drawn this many times their width
        self._add_axes()
        layout = QVBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        layout.addWidget(self.plotter)
        self._object_actors: list = []  # the scene's objects', then its lights' actors, in order
        self._kept: list[tuple] = []  # (key, object or light, actor) of what _object_actors draw
        self._overlays: dict[str, list] = {}  # name -> [(polydata, actor, style)]
        self._visible_overlays: set[str] | None = None  # None: all
        self._scene: Scene | None = None
        self._framed_at = None  # the overview camera _frame chose, until the user moves it
        self._eye = None  # where the observer's eye was drawn last (world space)
        self._labels_placed_for = None  # the camera, pane and labels _place_labels placed for
        self._framings = 0  # how many times _frame has framed the scene
        self._labels_small_for = None  # the framing, pane and labels the labels shrank for (_place_labels)
        self._view: dict | None = None  # the overview camera look_from was given, if any
        self._holding = 0  # held() blocks entered and not left
        self._waiting: list[tuple] = []  # (change, its arguments) held, in the order asked
        self._catching_up = False  # catch_up is making them
        self._render_timer = QTimer(self)
        self._render_timer.setSingleShot(True)
        self._render_timer.setInterval(FRAME_MS)
        self._render_timer.timeout.connect(self._draw_if_changed)
        self._last_draw = -1.0
        self._changed = False  # something changed since the last frame was drawn
        self.plotter.ren_win.AddObserver("EndEvent", self._drawn)
        self.plotter.renderer.AddObserver("StartEvent", self._place_labels)
        self._smooth_timer = QTimer(self)
        self._smooth_timer.setSingleShot(True)
        self._smooth_timer.setInterval(SMOOTH_AFTER_MS)
        self._smooth_timer.timeout.connect(self._smooth)
        self._build_observer()
        self._mouse = _MouseGrip(self)
        self.plotter.installEventFilter(self._mouse)
        model.camera_changed.connect(self.set_camera)
        model.scene_changed.connect(self.set_scene)
        self.set_scene(model.scene)

    # ----------------------------------------------------------- drawing
    def _build_observer(self) -> None:
        """Create the observer's actors once; :meth:`set_camera` only moves them."""
        eight, four = np.zeros((8, 3)), np.zeros((4, 3))
        self.frustum = vtk_convert.frustum_polydata(eight.copy())
        self._frustum_edges = vtk_convert.frustum_edges_polydata(eight.copy())
        self.screen = pv.PolyData(four.copy(), np.array([4, 0, 1, 2, 3]))
        self._screen_edges = pv.PolyData(four.copy(),
                                         lines=vtk_convert.line_cells([(0, 1), (1, 2), (2, 3), (3, 0)]))
        self._sight = pv.PolyData(np.zeros((2, 3)), lines=np.array([2, 0, 1]))
        add = self.plotter.add_mesh
        self._frustum_faces = add(self.frustum, color=FRUSTUM_COLOR, opacity=0.07, name="frustum",
                                  render=False)
        add(self._frustum_edges, color=FRUSTUM_COLOR, line_width=2, name="frustum-edges", render=False)
        add(self.screen, color=SCREEN_COLOR, opacity=0.35, name="screen", render=False)
        add(self._screen_edges, color=SCREEN_COLOR, line_width=3, name="screen-edges", render=False)
        add(self._sight, color="white", line_width=1, name="sight-line", render=False)
        self._glyph = add(_unit_glyph(), color="#e8e8e8", name="observer", render=False)
        self._target = add(pv.Sphere(radius=0.25, theta_resolution=16, phi_resolution=12),
                           color=TARGET_COLOR, name="target", render=False)

    def request_render(self) -> None:
        """Draw the pane soon, at most once per FRAME_MS; requests meanwhile share one draw."""
        self._changed = True
        self.plotter.renderer.SetUseFXAA(False)
        self._frustum_faces.SetVisibility(False)
        self._smooth_timer.start()
        if self._render_timer.isActive():
            if self._render_timer.interval() == 0:  # drawn at once: after this turn's last change
                self._render_timer.start(0)
            return
        wait_ms = FRAME_MS - (time.perf_counter() - self._last_draw) * 1000.0
        # At once (after the changes queued in this turn of the event loop) if the last
        # frame is old enough, else when it is.
        self._render_timer.start(max(0, int(wait_ms) + 1))

    @contextlib.contextmanager
    def held(self):
        """Within this block the pane's changes (a new scene, its overlays, the overview camera, the
        line scale) wait, in order, and are made :data:`HELD_MS` after it, in a turn of the event loop
        of their own: a lesson step built the 3D actors of its scene and marks, 17-23 ms, in the turn
        that also laid out and painted its words and panes.  A question about the pane (an
        overlay's parts, where a point is drawn, ...) has them made first, so it is always answered
        for what was asked."""
        self._holding += 1
        try:
            yield
        finally:
            self._holding -= 1
            if not self._holding and self._waiting:
                QTimer.singleShot(HELD_MS, self, self.catch_up)

    def catch_up(self) -> None:
        """Make the changes that wait (see :meth:`held`) now, in order."""
        if self._catching_up or not self._waiting:  # asked before each draw: mostly nothing waits
            return
        waiting, self._waiting, self._catching_up = self._waiting, [], True
        try:
            for change, args in waiting:  # what each calls of the others is made at once
                change(self, *args)
        finally:
            self._catching_up = False

    def _draw(self) -> None:
        self._last_draw = time.perf_counter()
        self.plotter.render()

    def _draw_if_changed(self) -> None:
        if self._changed and not self._frozen(self._render_timer):
            self._draw()

    def _frozen(self, timer: QTimer) -> bool:
        """Whether the window paints nothing now (a new text size or presentation mode is being laid
        out, to be painted once at its end); ``timer`` then tries again a frame later.  A draw then
        was never seen, and it lengthened the turns of that change (``bench gui``).  Nor is it drawn
        while changes wait (:meth:`held`): once made, they ask for a draw."""
        if self._waiting:
            return True
        if self.window().updatesEnabled():
            return False
        timer.start(FRAME_MS)
        return True

    def _drawn(self, *_) -> None:
        self._changed = False

    def _smooth(self) -> None:
        if self._frozen(self._smooth_timer):
            return
        self.plotter.renderer.SetUseFXAA(True)
        self._frustum_faces.SetVisibility(True)
        self._draw()

    @_current
    def picture(self, scale: int) -> np.ndarray:
        """The pane as it looks at rest (anti-aliased, the frustum's see-through faces drawn), at
        ``scale`` × its size: (H, W, 3) uint8 sRGB levels.  Taken while the pane waits to be drawn
        smooth (a change since), it has the faces all the same."""
        fxaa, faces = self.plotter.renderer.GetUseFXAA(), self._frustum_faces.GetVisibility()
        self.plotter.renderer.SetUseFXAA(True)
        self._frustum_faces.SetVisibility(True)
        try:
            return self.plotter.picture_at(scale)
        finally:
            self.plotter.renderer.SetUseFXAA(fxaa)
            self._frustum_faces.SetVisibility(faces)

    @_held
    def set_scene(self, scene: Scene) -> None:
        """Draw every object and light, then the observer; frame the whole.

        An object or light equal to one in the scene drawn before keeps its actor (an edit
        replaces only what it changes; the next lesson step often loads the same scene again);
        only the others are built.
        """
        before: dict[tuple, list] = {}
        for key, thing, actor in self._kept:
            before.setdefault(key, []).append((thing, actor))
        self._kept, self._object_actors = [], []
        drawn = [(obj, False) for obj in scene.objects] + [(light, True) for light in scene.lights]
        for thing, is_light in drawn:
            eye_inside = isinstance(thing, Sphere) and np.linalg.norm(
                np.subtract(scene.camera.eye, thing.center)) < thing.radius
            key = (type(thing), getattr(thing, "name", ""), eye_inside)
            same = next((k for k, (old, _) in enumerate(before.get(key, ())) if _same(old, thing)), None)
            if same is not None:
                # The thing drawn before is kept with its actor: the actor's name holds its id.
                thing, actor = before[key].pop(same)
            elif is_light:
                actor = self._add_surface(vtk_convert.placed_sphere(thing.position, LIGHT_MARKER, 30, 30),
                                          f"light:{id(thing)}", color="#fff6a0", lighting=False)
            else:
                actor = self._add_object(thing, eye_inside)
            self._kept.append((key, thing, actor))
            self._object_actors.append(actor)
        for left in before.values():
            for _, actor in left:
                self.plotter.remove_actor(actor, render=False)
        self._scene = scene
        self.set_camera(scene.camera)
        if self._framed_at is None or not self.model.scene_was_edited:  # an edit keeps the user's view
            self._view = None
            self._frame(scene)

    def _add_object(self, obj, eye_inside: bool):
        m = obj.material
        # The observer standing inside a sphere sees through it.
        opacity = min(m.opacity, ENCLOSING_OPACITY) if eye_inside else m.opacity
        return self._add_surface(vtk_convert.object_polydata(obj), f"object:{id(obj)}", color=m.color,
                                 opacity=opacity, specular=m.specular)

    def _add_surface(self, poly: pv.PolyData, name: str, **look):
        """Add ``poly`` (faces, lines or points) with flat faces and the look ``look`` (pyvista Property
        fields: ``color``, ``opacity``, ``line_width``, ``style``, ...).

        What ``add_mesh(poly, smooth_shading=False, show_edges=False, **look)`` draws, pixel for pixel,
        in a fifth of its time: a lesson step builds every object of its scene, and its overlays, on the
        GUI thread (add_mesh made a matplotlib colour map for each, 20-40 ms).
        """
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(poly)
        mapper.ScalarVisibilityOff()
        prop = pv.Property(theme=self.plotter.theme, interpolation="flat", show_edges=False, **look)
        actor = pv.Actor(mapper=mapper, prop=prop)
        self.plotter.add_actor(actor, name=name, render=False, reset_camera=False)
        return actor

    @_current
    def actor_of(self, item):
        """The actor that draws ``item`` of the scene (``("object", i)`` or ``("light", i)``), or None."""
        if self._scene is None or item is None or item[0] not in ("object", "light"):
            return None
        index = item[1] + (len(self._scene.objects) if item[0] == "light" else 0)
        return self._object_actors[index] if index < len(self._object_actors) else None

    def resizeEvent(self, event):
        super().resizeEvent(event)
        self._frame_new_shape()

    @_held
    def _frame_new_shape(self) -> None:
        """Frame the scene again for the pane's new shape, unless the user has moved the view (after
        the changes that wait: a lesson step that shows the pane anew frames its own scene)."""
        if self._scene is not None and self.plotter.camera_position == self._framed_at:
            self._frame(self._scene)
            self.request_render()

    @_held
    def set_camera(self, camera: Camera) -> None:
        """Move the observer, its frustum, its screen and its target marker to ``camera``; an eye
        that walks out of the pane (orbiting with the arrow keys) is followed (:meth:`_follow_eye`)."""
        eye = np.asarray(camera.eye, float)
        walked = self._eye is not None and not np.array_equal(eye, self._eye) \
            and self._in_pane(self._eye, inset=0)
        self._eye = eye
        if walked and not self._in_pane(eye):
            self._follow_eye(camera)
        corners = camera.frustum_corners()
        self.frustum.points = corners
        self._frustum_edges.points = corners.copy()
        screen = camera.screen_corners()
        self.screen.points = screen
        self._screen_edges.points = screen.copy()
        self._sight.points = np.array([camera.eye, camera.target], float)
        size = glyph_size(camera)
        self._glyph.user_matrix = camera.world_from_view @ np.diag([size, size, size, 1.0])
        target = np.eye(4)
        target[:3, :3] *= size
        target[:3, 3] = camera.target
        self._target.user_matrix = target
        self.request_render()

    def _in_pane(self, point, inset: float = GRAB_RADIUS_PX) -> bool:
        """Whether the world point ``point`` is drawn inside the pane, ``inset`` pixels clear of its
        edges (by default the glyph's grab radius: the camera glyph stays whole and can be grabbed)."""
        at = self.widget_pos(point)
        return (inset <= at.x() <= self.plotter.width() - inset
                and inset <= at.y() <= self.plotter.height() - inset)

    def _follow_eye(self, camera: Camera) -> None:
        """Step the overview camera back along its line of sight until the eye, the target and the
        objects are all in the pane again (the direction the user chose is kept)."""
        view = self.plotter.camera
        points = [camera.eye, camera.target]
        for obj in self._scene.objects if self._scene is not None else ():
            points += list(_box_corners(obj))
        aspect = max(self.plotter.width(), 1) / max(self.plotter.height(), 1)
        self.plotter.camera_position = [tuple(v) for v in fit_view(
            points, view.direction, view.up, view.view_angle, aspect)]
        self.plotter.reset_camera_clipping_range()

    @_held
    def set_overlay(self, name: str, parts: list[tuple[pv.PolyData, dict]]) -> None:
        """Show extra geometry under ``name`` (replacing what was there), e.g. a ray tree.

        ``parts`` are ``(polydata, add_mesh keyword arguments)`` pairs; an empty
        list removes the overlay.  When the parts have the same styles as
        before, the existing actors keep their identity and take the new points.
        """
        parts = [(poly, style) for poly, style in parts if poly.n_points]
        old = self._overlays.get(name, [])
        if len(old) == len(parts) and all(o[2] == style for o, (_, style) in zip(old, parts, strict=True)):
            for (drawn, _, _), (poly, _) in zip(old, parts, strict=True):
                drawn.copy_from(poly)
        else:
            for _, actor, _ in old:
                self.plotter.remove_actor(getattr(actor, "_leader_actor", actor), render=False)
                self.plotter.remove_actor(actor, render=False)
            drawn = []
            for i, (poly, style) in enumerate(parts):
                drawn.append((poly, self._add_part(f"{name}:{i}", poly, style), style))
            self._overlays[name] = drawn
            self._apply_visibility(name)
        self.request_render()

    def _add_part(self, name: str, poly: pv.PolyData, style: dict):
        """An overlay part's actor: ``poly`` drawn with ``style``, or its points labelled with the
        strings of its ``"labels"`` point array when ``style`` has ``"label_size"`` (points)."""
        if "label_size" not in style:
            actor = self._add_surface(poly, name, **style)
        else:
            placed = vtk_convert.set_labels(pv.PolyData(poly.points.copy()),  # where they go: _place_labels
                                            poly.point_data["labels"])
            mapper = vtkLabeledDataMapper()
            mapper.SetInputData(placed)
            mapper.SetLabelModeToLabelFieldData()
            mapper.SetFieldDataName("labels")
            text = mapper.GetLabelTextProperty()
            text.SetColor(pv.Color(style.get("color", "white")).float_rgb)
            font = label_font_file()
            if font is not None:
                text.SetFontFamily(VTK_FONT_FILE)
                text.SetFontFile(font)
            text.SetBold(True)
            text.SetShadow(True)
            text.SetJustificationToCentered()  # centred above the point: a label at a pane's edge shows
            text.SetVerticalJustificationToBottom()
            actor = vtkActor2D()
            actor.SetMapper(mapper)
            actor._anchors, actor._placed = poly, placed
            self.plotter.add_actor(actor, name=name, render=False)
            actor._leader = pv.PolyData()
            actor._leader.points = poly.points[:1]  # no lines yet; pyvista draws no empty mesh
            actor._leader_actor = self.plotter.add_mesh(
                actor._leader, color=style.get("color", "white"), line_width=1, name=f"{name}:leader",
                render=False)
            self._scale_actor(actor._leader_actor)
        self._scale_actor(actor, style)
        return actor

    def _scale_actor(self, actor, style: dict | None = None) -> None:
        """Widen ``actor``'s lines and points (or enlarge its labels) by :attr:`line_scale`."""
        if not hasattr(actor, "_unscaled"):
            if isinstance(actor, vtkActor2D):
                if style is None:
                    return  # not an overlay's label: nothing of ours to scale
                actor._unscaled = ("label", style["label_size"])
            else:
                prop = actor.GetProperty()
                actor._unscaled = ("lines", prop.GetLineWidth(), prop.GetPointSize())
        if actor._unscaled[0] == "label":
            size = actor._unscaled[1] * label_scale(self.line_scale)
            actor.GetMapper().GetLabelTextProperty().SetFontSize(round(size))
        else:
            actor.GetProperty().SetLineWidth(actor._unscaled[1] * self.line_scale)
            actor.GetProperty().SetPointSize(actor._unscaled[2] * self.line_scale)

    @_held
    def set_line_scale(self, scale: float) -> None:
        """Draw every line, point and the axes ``scale`` times as large, the labels :func:`label_scale`
        times (presentation mode)."""
        self.line_scale = float(scale)
        for actor in self.plotter.renderer.actors.values():
            self._scale_actor(actor)
        self._add_axes()
        if self._scene is not None and self.plotter.camera_position == self._framed_at:
            self._frame(self._scene)  # larger labels need more room
        self.request_render()

    def _add_axes(self) -> None:
        """The axes marker in the lower left corner, at :attr:`line_scale` (made once, then updated:
        a new marker took a tenth of a second of the GUI thread at each text size)."""
        side = _axes_side(self.line_scale)
        renderer = self.plotter.renderer
        if renderer.axes_widget is None:
            self.plotter.add_axes(line_width=round(3 * self.line_scale), labels_off=False,
                                  viewport=(0.0, 0.0, side, side))
            return
        axes = renderer.axes_actor
        for shaft in (axes.GetXAxisShaftProperty(), axes.GetYAxisShaftProperty(),
                      axes.GetZAxisShaftProperty()):
            shaft.SetLineWidth(round(3 * self.line_scale))
        renderer.axes_widget.SetViewport(0.0, 0.0, side, side)

    @_held
    def show_overlays_only(self, names) -> None:
        """Show only the overlays in ``names`` (the others are kept, hidden); ``None`` shows all."""
        self._visible_overlays = None if names is None else set(names)
        for name in self._overlays:
            self._apply_visibility(name)
        self.request_render()

    def _shown(self, name: str) -> bool:
        return self._visible_overlays is None or SHOWN_WITH.get(name, name) in self._visible_overlays

    def _apply_visibility(self, name: str) -> None:
        shown = self._shown(name)
        for _, actor, _ in self._overlays.get(name, []):
            actor.SetVisibility(shown)
            getattr(actor, "_leader_actor", actor).SetVisibility(shown)

    @_current
    def overlay_names(self) -> list[str]:
        """Names of the overlays currently shown (with at least one part)."""
        return [name for name, parts in self._overlays.items() if parts and self._shown(name)]

    @_current
    def overlay_parts(self, name: str) -> list[pv.PolyData]:
        """The polydata drawn for overlay ``name`` (empty if none)."""
        return [poly for poly, _, _ in self._overlays.get(name, [])]

    # ----------------------------------------------------- mouse helpers
    @_current
    def widget_pos(self, point) -> QPointF:
        """Where the world point ``point`` appears in the pane (widget coordinates)."""
        renderer = self.plotter.renderer
        renderer.SetWorldPoint(*np.asarray(point, float), 1.0)
        renderer.WorldToDisplay()
        x, y, _ = renderer.GetDisplayPoint()
        ratio = self.plotter.devicePixelRatioF()
        height = self.plotter.ren_win.GetSize()[1]
        return QPointF(x / ratio, (height - y) / ratio)

    @_current
    def ray_under(self, pos: QPointF) -> tuple[np.ndarray, np.ndarray]:
        """The overview camera's ray through widget position ``pos``: origin on the near
        plane and direction to the far plane (world space)."""
        renderer = self.plotter.renderer
        ratio = self.plotter.devicePixelRatioF()
        x, y = pos.x() * ratio, self.plotter.ren_win.GetSize()[1] - pos.y() * ratio
        ends = []
        for depth in (0.0, 1.0):
            renderer.SetDisplayPoint(x, y, depth)
            renderer.DisplayToWorld()
            w = np.array(renderer.GetWorldPoint())
            ends.append(w[:3] / w[3])
        return ends[0], ends[1] - ends[0]

    def world_point_under(self, pos: QPointF, anchor) -> np.ndarray:
        """The point under widget position ``pos`` in the plane through ``anchor`` facing the view."""
        origin, direction = self.ray_under(pos)
        normal = np.asarray(self.plotter.camera.direction, float)
        t = np.dot(np.asarray(anchor, float) - origin, normal) / np.dot(direction, normal)
        return origin + t * direction

    def grabbable_at(self, pos: QPointF) -> str | None:
        """``"eye"`` or ``"target"`` if the mouse at ``pos`` is on one of them, else ``None``."""
        cam = self.model.camera
        for name, point in (("eye", cam.eye), ("target", cam.target)):
            p = self.widget_pos(point)
            if np.hypot(p.x() - pos.x(), p.y() - pos.y()) <= GRAB_RADIUS_PX:
                return name
        return None

    @_held
    def look_from(self, view) -> None:
        """Place the overview camera: ``view`` maps ``position``, ``focal_point`` and ``up``
        (world space, scene units); without them, the pane frames the scene and observer itself.
        While a :data:`FRAMED_OVERLAYS` overlay (the frustum) is shown, the camera looks the
        way ``view`` says but stands where that overlay and its labels fit in the pane.
        ``view["frame"] == "highlight"`` frames instead what the :data:`HIGHLIGHT_OVERLAY`
        shows, the eye and the screen (with the labels of what lies no deeper), as large
        as they fit."""
        self._view = dict(view) if view else None
        if self._scene is not None:
            self._frame(self._scene)
        self.request_render()

    def _frame(self, scene: Scene) -> None:
        """Place the overview camera as :meth:`look_from` was told, or beside the observer.

        Beside the observer, it sees the eye, the screen rectangle and the
        objects, and the frustum with its labels when that overlay is shown;
        the rest of the frustum may leave the view.
        """
        for _, actor, style in itertools.chain(*self._overlays.values()):
            if "label_size" in style:  # framed for the labels at full size (the last frame may have
                self._scale_actor(actor)  # drawn them smaller, _place_labels)
        view = self._view or {}
        framed = [name for name in FRAMED_OVERLAYS if name in self.overlay_names()]
        subject = [poly for poly, _, _ in self._overlays.get(HIGHLIGHT_OVERLAY, [])]
        on_subject = view.get("frame") == "highlight" and bool(subject) \
            and HIGHLIGHT_OVERLAY in self.overlay_names()
        if "position" in view and not framed and not on_subject:
            self.plotter.camera_position = [tuple(view["position"]), tuple(view["focal_point"]),
                                            tuple(view.get("up", (0.0, 1.0, 0.0)))]
        else:
            cam = scene.camera
            if "position" in view:
                direction = np.subtract(view["focal_point"], view["position"])
                up = view.get("up", (0.0, 1.0, 0.0))
            else:
                side = np.cross(cam.forward, (0.0, 1.0, 0.0))
                side = side / (np.linalg.norm(side) or 1.0)
                direction = cam.forward * 0.6 - side - np.array([0.0, 0.7, 0.0])
                up = (0.0, 1.0, 0.0)
            points = [cam.eye, *cam.screen_corners()]
            forward = cam.forward  # worked out anew at each use: once here
            if on_subject:
                points += [p for poly in subject for p in poly.points]
                deepest = float(np.max((np.asarray(points, float) - cam.eye) @ forward))
            else:
                points.append(cam.target)
                for obj in scene.objects:
                    points += list(_box_corners(obj))
            bounds = [[[-1 + MARGIN, 1 - MARGIN]] * 2] * len(points)
            for name in framed:
                for poly, actor, style in self._overlays[name]:
                    keep = np.ones(poly.n_points, bool) if not on_subject else \
                        (poly.points - cam.eye) @ forward <= deepest + 1e-9
                    if "label_size" in style:
                        bounds += [b for b, k in zip(self._label_bounds(poly, actor), keep, strict=True) if k]
                        points += list(poly.points[keep])
                    elif not on_subject:
                        points += list(poly.points)
                        bounds += [bounds[0]] * poly.n_points
            self.plotter.camera.view_angle = 30.0
            aspect = max(self.plotter.width(), 1) / max(self.plotter.height(), 1)
            self.plotter.camera_position = [tuple(v) for v in fit_view(
                points, direction, up, 30.0, aspect, bounds)]
        self.plotter.reset_camera_clipping_range()
        self._framed_at = self.plotter.camera_position
        self._framings += 1

    def _label_bounds(self, poly: pv.PolyData, actor) -> list:
        """Where each label of ``poly`` (drawn by ``actor``) may be anchored, whole in the pane."""
        ratio = self.plotter.devicePixelRatioF()
        pane = (max(self.plotter.width(), 1) * ratio, max(self.plotter.height(), 1) * ratio)
        text = actor.GetMapper().GetLabelTextProperty()
        measure, box = vtkTextRenderer(), [0, 0, 0, 0]
        bounds = []
        for label in poly.point_data["labels"]:
            measure.GetBoundingBox(text, str(label), box, self.plotter.ren_win.GetDPI())
            bounds.append(label_bounds(box[1] - box[0] + 4, box[3] - box[2] + 4, pane).tolist())
        return bounds

    def _place_labels(self, *_) -> None:
        """Before each draw: move every shown label beside the point it names, clear of its
        overlay's lines, the observer's frustum and the labels placed before it (the widest
        first); a thin leader line joins a label set farther off to its point."""
        names = [name for name in self.overlay_names()
                 if any("label_size" in style for _, _, style in self._overlays[name])]
        width, height = self.plotter.ren_win.GetSize()
        if not names or width < 2 or height < 2:
            return
        matrix = pv.array_from_vtkmatrix(self.plotter.renderer.GetActiveCamera()
                                         .GetCompositeProjectionTransformMatrix(width / height, -1, 1))
        key = (matrix.tobytes(), width, height, self.line_scale,
               [(p.points.tobytes(), list(p.point_data.get("labels", []))) for n in names
                for p, _, _ in self._overlays[n]])
        if key == self._labels_placed_for:
            return
        self._labels_placed_for = key
        label_actors = [actor for n in names for _, actor, style in self._overlays[n]
                        if "label_size" in style]
        # Presenting in a pane too small for the labels at their size, they are drawn smaller, as at
        # text x1.  While the camera is turned by hand from the same framing they stay so: turning
        # it, they grew and shrank by turns, and each frame placed them twice.
        framing, full = (self._framings, *key[1:]), label_scale(self.line_scale)
        for scale in dict.fromkeys((1.0,) if framing == self._labels_small_for else (full, 1.0)):
            for actor in label_actors:
                actor.GetMapper().GetLabelTextProperty().SetFontSize(round(actor._unscaled[1] * scale))
            if self._placed_apart(names, width, height, matrix):
                break
        self._labels_small_for = framing if scale < full else None

    def _placed_apart(self, names: list[str], width: int, height: int, matrix) -> bool:
        """Place the labels of overlays ``names`` (:meth:`_place_labels`) in a pane ``width`` x ``height``
        seen through ``matrix``; whether every label of a point in view found a spot clear of the others."""
        apart = True
        to_pixels = np.array([width / 2, height / 2])

        def project(points):
            h = np.c_[np.asarray(points, float), np.ones(len(points))] @ matrix.T
            return h, (h[:, :2] / h[:, 3:] + 1) * to_pixels

        own = [(self._frustum_edges, 2.0), (self._screen_edges, 3.0)]
        measure, box, dpi = vtkTextRenderer(), [0, 0, 0, 0], self.plotter.ren_win.GetDPI()

        def measured(text, words) -> tuple[float, float, list]:
            measure.GetBoundingBox(text, words, box, dpi)
            return box[1] - box[0], box[3] - box[2], list(box)

        side = _axes_side(self.line_scale) * np.array([width, height])
        square = side.min()  # the axes marker: a square, centred in its corner's viewport
        taken = [(*(side - square) / 2, *(side + square) / 2)]
        actors, wanted = [], []  # each label actor with its points; each label to place
        for name in names:
            parts = self._overlays[name]
            ends, halves = [], []
            for poly, line_width in own + [(poly, style.get("line_width", 1.0)) for poly, _, style in parts
                                           if "label_size" not in style]:
                h, xy = project(poly.points)
                for a, b in _edges(poly):
                    if h[a, 3] > 0 and h[b, 3] > 0:  # both ends in front of the overview camera
                        ends.append((xy[a], xy[b]))
                        halves.append(line_width * self.line_scale / 2)
            ends = np.array(ends).reshape(-1, 2, 2)
            segments = (ends[:, 0], ends[:, 1], np.array(halves))
            for _, actor, style in parts:
                if "label_size" not in style:
                    continue
                h, xy = project(actor._anchors.points)
                shown = [str(label) for label in actor._anchors.point_data["labels"]]
                actors.append((actor, h, xy, np.array(h), shown))
                text = actor.GetMapper().GetLabelTextProperty()
                wanted += [(measured(text, label)[0], len(actors) - 1, k, segments, text)
                           for k, label in enumerate(shown)]
        # The widest first, while the pane has room for it; each clear of the lines and the labels
        # placed before it, on one line or broken into lines where that is nearer its point; in a pane
        # too small for that (presenting on a small screen), clear of the labels only, across a line.
        # Then two whose leader lines cross change places where each fits the other's.
        order = []  # each label placed: its actor and number, its text's edges, its lines (None: none)
        for _, a, k, segments, text in sorted(wanted, key=lambda item: -item[0]):
            actor, h, xy, spots, shown = actors[a]
            label = shown[k]
            ways = list(dict.fromkeys((label, broken(label))))  # one line first
            sizes = [measured(text, words) for words in ways]
            for lines in (segments, _NO_LINES):
                found = place_nearest(xy[k], [size[:2] for size in sizes], lines, (width, height), taken,
                                      GAP_PX * self.line_scale)
                if found is not None:
                    break
            if found is not None:
                spot, words, (w, t, edges) = found[1], ways[found[0]], sizes[found[0]]
            else:  # nowhere clear: on one line, centred above the point
                lines = None
                words = label
                w, t, edges = measured(text, words)
                spot = xy[k][0], xy[k][1] + GAP_PX * self.line_scale
                if 0 <= xy[k][0] <= width and 0 <= xy[k][1] <= height:  # its point in view: it too
                    spot = in_pane(*spot, (w, t), (width, height))
                    apart = False
            cx, bottom = spot
            shown[k] = words
            taken.append((cx - w / 2, bottom, cx + w / 2, bottom + t))
            order.append((a, k, edges, lines))
        marker = taken[:1]  # the axes marker's corner
        boxes = uncross([actors[a][2][k] for a, k, _, _ in order], taken[1:], [lines for *_, lines in order],
                        (width, height), marker, GAP_PX * self.line_scale)
        for (a, k, edges, _), (x0, bottom, x1, _) in zip(order, boxes, strict=True):
            _, h, _, spots, _ = actors[a]
            at = np.array([(x0 + x1) / 2 - (edges[0] + edges[1]) / 2, bottom - edges[2]])
            spots[k, :2] = (at / to_pixels - 1) * h[k, 3]  # same depth, moved on the pane
        for actor, _, xy, spots, shown in actors:
            anchors, placed = actor._anchors, actor._placed
            world = spots @ np.linalg.inv(matrix).T
            placed.points = world[:, :3] / world[:, 3:]
            vtk_convert.set_labels(placed, shown)
            far = np.hypot(*(project(placed.points)[1] - xy).T) > 3 * GAP_PX * self.line_scale
            actor._leader.copy_from(_leaders(anchors.points[far], placed.points[far]))
        return apart

    def close(self) -> bool:
        self._render_timer.stop()
        self._smooth_timer.stop()
        self.plotter.close()
        return super().close()


_NO_LINES = (np.empty((0, 2)), np.empty((0, 2)), np.empty(0))
"""No lines for a label to keep clear of (:func:`views.scene3d.label_placement.place_label`'s segments)."""


def label_scale(line_scale: float) -> float:
    """How much larger the 3D pane's labels are drawn while everything else is ``line_scale`` times
    as large: its square root (x1.41 at x2).  The pane does not grow with the text, so labels at the
    body's x2 (26 pt, "near plane (the screen), n = 0.5" 470 px wide) crowded it and covered the
    frustum's edges; at the square root they stay larger than at x1 and find room beside the lines."""
    return float(np.sqrt(max(line_scale, 1.0)))


def _axes_side(line_scale: float) -> float:
    """The axes marker's share of the pane's width and height (its labels follow its size)."""
    return min(0.2 * line_scale, 0.4)


def _leaders(starts, ends) -> pv.PolyData:
    """Lines from each of ``starts`` to the same row of ``ends``."""
    n = len(starts)
    lines = np.c_[np.full(n, 2), 2 * np.arange(n), 2 * np.arange(n) + 1].ravel()
    return pv.PolyData(np.vstack([starts, ends]).reshape(2, n, 3).transpose(1, 0, 2).reshape(-1, 3)
                       if n else np.zeros((0, 3)), lines=lines if n else None)


def _edges(poly: pv.PolyData) -> list[tuple[int, int]]:
    """The point index pairs of ``poly``'s lines and of its polygons' sides."""
    pairs = []
    for cells, closed in ((poly.lines, False), (poly.faces, True)):
        k = 0
        while k < len(cells):
            n, ids = cells[k], cells[k + 1:k + 1 + cells[k]]
            pairs += list(zip(ids[:-1], ids[1:], strict=True))
            if closed and n > 2:
                pairs.append((ids[-1], ids[0]))
            k += n + 1
    return pairs


def _same(drawn, thing) -> bool:
    """Whether ``thing`` (an object or a light) is ``drawn`` or equal to it (an object made with an
    array for a vector, whose dataclass equality has no single answer, only when it is ``drawn``)."""
    if drawn is thing:
        return True
    try:
        return bool(drawn == thing)
    except ValueError:
        return False


def _box_corners(obj) -> np.ndarray:
    """The 8 corners of a box around ``obj``."""
    if isinstance(obj, Sphere):
        low, high = np.subtract(obj.center, obj.radius), np.add(obj.center, obj.radius)
    else:
        low, high = obj.vertices.min(axis=0), obj.vertices.max(axis=0)
    return np.array([[(low, high)[i >> k & 1][k] for k in range(3)] for i in range(8)])


class _MouseGrip(QObject):
    """Mouse events on the 3D pane that grab the eye or the target; the rest go to VTK."""

    def __init__(self, view: SceneView):
        super().__init__(view)
        self.view = view
        self.drag: str | None = None
        self.anchor_offset = np.zeros(3)

    def eventFilter(self, obj, event):
        kind = event.type()
        view, model = self.view, self.view.model
        if kind == QEvent.Type.MouseButtonPress and event.button() == Qt.MouseButton.LeftButton:
            self.drag = view.grabbable_at(event.position())
            if self.drag is not None:
                point = getattr(model.camera, self.drag)
                self.anchor_offset = np.subtract(point, view.world_point_under(event.position(), point))
                return True
        elif kind == QEvent.Type.MouseMove and self.drag is not None:
            point = getattr(model.camera, self.drag)
            moved = view.world_point_under(event.position(), point) + self.anchor_offset
            model.update_camera(**{self.drag: moved})
            return True
        elif kind == QEvent.Type.MouseButtonRelease and self.drag is not None:
            self.drag = None
            return True
        elif kind == QEvent.Type.Wheel and view.grabbable_at(event.position()) == "eye":
            notches = event.angleDelta().y() / 120.0
            lo, hi = FOV_RANGE_DEG
            fov = min(hi, max(lo, model.camera.fov_y_deg - FOV_STEP_DEG * notches))
            model.update_camera(fov_y_deg=fov)
            return True
        return False
