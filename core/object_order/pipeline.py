"""Object order rendering: polygon after polygon through the lecture's pipeline.

The first half of the lecture renders a scene by taking its polygons one at a
time and finding the pixels each one covers; a z-buffer decides which polygon
is seen at every pixel.  :func:`render_raster` runs these stages, each with its
own module, and keeps what every stage did in a :class:`RasterResult`:

1. transform: world -> view (camera) space -> clip space;
2. back-face culling by the faces' normals (:mod:`core.object_order.culling`);
3. frustum culling of whole objects by bounding spheres (:mod:`core.object_order.culling`);
4. clipping of the polygons that cross the frustum, in clip space
   (:mod:`core.object_order.clipping`);
5. projection: perspective divide and viewport mapping (:mod:`core.object_order.rasterization`);
6. flat shading of every polygon (:mod:`core.object_order.flat_shading`);
7. drawing order: opaque first, then transparent far to near (:mod:`core.object_order.blending`);
8. rasterization with the top-left rule and the z-buffer test
   (:mod:`core.object_order.rasterization`, :mod:`core.object_order.zbuffer`, run by
   :mod:`core.object_order.fragments`, compiled in :mod:`core.object_order.kernels.raster`),
   optionally recording every fragment (:mod:`core.object_order.step_history`).

Stages 2, 4 and 6 run compiled over all faces at once (:mod:`core.object_order.stages`).
Culling, clipping, sorting and the z-test itself can be switched off
(:class:`RasterSettings`) to see what each one is for, and the z-buffer's
number format chosen (:mod:`core.object_order.depth_formats`).  Analytic
spheres are tessellated first (``SPHERE_RINGS`` x ``SPHERE_SEGMENTS``).
Conventions: :mod:`core.projection`.
"""

from __future__ import annotations

import time
from dataclasses import asdict, dataclass

import numpy as np

from core import shapes
from core.compiling.warm_up import WarmUp
from core.object_order import (
    blending,
    culling,
    depth_formats,
    fragments,
    rasterization,
    stages,
)
from core.object_order.clipping import ClipResult, Polygons
from core.object_order.culling import ObjectCulling
from core.object_order.stages import FaceCulling
from core.object_order.step_history import StepHistory
from core.presets import zbuffer_piercing
from core.scene import Mesh, Scene, SceneObject, Sphere

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).

SPHERE_RINGS, SPHERE_SEGMENTS = 32, 64
"""Tessellation of an analytic sphere for object order: 4,032 triangles."""


@dataclass(frozen=True)
class RasterSettings:
    """Which optional stages run, and the z-buffer's number format.

    Attributes
    ----------
    back_face_culling : drop faces turned away from the observer.
    frustum_culling : drop objects whose bounding sphere is outside the frustum,
        and skip clipping for those entirely inside.
    clipping : clip polygons to the frustum before the divide; off, a polygon
        reaching behind the eye is projected mirrored.
    sort_transparent : draw transparent polygons from the farthest to the closest.
    record_steps : keep every fragment for step and pixel history.
    z_test : compare each fragment's depth with the z-buffer's; off, fragments
        are written in drawing order (the painter without sorting), so back-face
        culling alone decides what is seen.
    depth_format : the z-buffer's number format, one of
        :data:`core.object_order.depth_formats.DEPTH_FORMATS`.

    Raises
    ------
    ValueError
        For a ``depth_format`` that is not one of the formats (naming them).
    """

    back_face_culling: bool = True
    frustum_culling: bool = True
    clipping: bool = True
    sort_transparent: bool = True
    record_steps: bool = False
    z_test: bool = True
    depth_format: str = "float64"

    def __post_init__(self):
        depth_formats.format_code(self.depth_format)


STAGES = ("back_face_culling", "frustum_culling", "clipping", "sort_transparent", "z_test")
"""The stages a :class:`RasterSettings` switches on and off, in the order the pipeline runs them."""


@dataclass(frozen=True, eq=False)
class DrawList:
    """The polygons in the order they were drawn, and what each one did.

    Attributes
    ----------
    polygons : the (possibly clipped) polygons in drawing order; their world
        vertices are what the 3D view highlights at each step.
    object_index : (P,) int64, index into ``scene.objects``.
    triangle_index : (P,) int64, the face's triangle within the object's mesh
        (``RasterResult.meshes[object_index]``).
    transparent : (P,) bool, drawn with blending (alpha_s < 1).
    color : (P, 3) float64, flat colour.
    alpha : (P,) float64, opacity alpha_s.
    depth : (P,) float64, distance of the face's centroid along the viewing
        axis (scene units), the key transparent polygons are sorted by.
    generated, passed : (P,) int64, fragments per polygon.
    """

    polygons: Polygons
    object_index: np.ndarray
    triangle_index: np.ndarray
    transparent: np.ndarray
    color: np.ndarray
    alpha: np.ndarray
    depth: np.ndarray
    generated: np.ndarray
    passed: np.ndarray

    def __len__(self) -> int:
        return len(self.alpha)

    @property
    def failed(self) -> np.ndarray:
        """(P,) int64, fragments per polygon that failed the depth test."""
        return self.generated - self.passed


@dataclass(frozen=True, eq=False)
class RasterResult:
    """The rendered image and everything each stage did.

    Attributes
    ----------
    color : (H, W, 3) float64, image memory, RGB in [0, 1].
    depth : (H, W) float64, distance along the viewing axis (scene units,
        positive) of the surface seen at each pixel (as the z-buffer's format
        stores its depth), +inf for background.
    zbuffer : (H, W) float64, the z-buffer's depth keys: window depths as the
        format stores them (1 = far plane).
    stats : JSON-serialisable counts per stage, ``zbuffer_bytes`` (the z-buffer's
        size in its format) and ``times`` (seconds per stage).
    settings : the settings used.
    meshes : the objects as the triangle meshes that were drawn (analytic
        spheres tessellated).
    face_offsets : (O + 1,) int64, object ``o``'s faces are global faces
        ``face_offsets[o] : face_offsets[o + 1]``.
    faces : the back-face test of every global face (view space).
    objects : frustum culling per object, ``None`` when switched off.
    clipping : the clipping stage's result (the clipped polygons in world space).
    view_from_world, clip_from_view : (4, 4) float64, the matrices used.
    draw : the polygons in drawing order.
    history : fragment record for step and pixel history (``record_steps``).
    """

    color: np.ndarray
    depth: np.ndarray
    zbuffer: np.ndarray
    stats: dict
    settings: RasterSettings
    meshes: tuple[Mesh, ...]
    face_offsets: np.ndarray
    faces: FaceCulling
    objects: ObjectCulling | None
    clipping: ClipResult
    view_from_world: np.ndarray
    clip_from_view: np.ndarray
    draw: DrawList
    history: StepHistory | None

    def face_index(self, object_index: int, triangle_index: int) -> int:
        """The global face number of a triangle of an object (index into ``faces``)."""
        return int(self.face_offsets[object_index] + triangle_index)


def object_mesh(obj: SceneObject) -> Mesh:
    """The object as triangles: meshes as they are, analytic spheres tessellated."""
    if isinstance(obj, Sphere):
        return shapes.uv_sphere(obj.center, obj.radius, SPHERE_RINGS, SPHERE_SEGMENTS,
                                material=obj.material, name=obj.name)
    return obj


def joined_triangles(meshes) -> tuple[np.ndarray, np.ndarray]:
    """The vertices and triangles of ``meshes``, in order, as one pair of arrays: each mesh's
    corner indices moved past the vertices of the meshes before it.  One mesh: its own arrays, no
    copies."""
    if len(meshes) == 1:
        return meshes[0].vertices, meshes[0].triangles
    vertex_offsets = np.cumsum([0] + [len(m.vertices) for m in meshes])
    world = np.vstack([m.vertices for m in meshes] + [np.empty((0, 3))])
    triangles = np.vstack([m.triangles + v for m, v in zip(meshes, vertex_offsets[:-1], strict=True)]
                          + [np.empty((0, 3), np.int64)])
    return world, triangles


class _Stopwatch:
    """Seconds spent per stage, read with :meth:`lap` at the end of each stage."""

    def __init__(self):
        self.times: dict[str, float] = {}
        self._last = time.perf_counter()

    def lap(self, stage: str) -> None:
        now = time.perf_counter()
        self.times[stage] = now - self._last
        self._last = now


DEFAULT_SETTINGS = RasterSettings()

PARALLEL_WORK = 1_000_000
"""Pixels plus triangles below which a frame runs on one thread.  The back-face test, flat
shading, the triangles' bounding boxes and the drawing share their loops between the threads, and
starting them costs tens of microseconds on a quiet machine and up to a scheduler time
slice (milliseconds) on a busy one: for a small frame one thread is quicker.  (The
image is the same with any number.)"""


def _read_only(a: np.ndarray) -> np.ndarray:
    view = a.view()
    view.flags.writeable = False
    return view


def _warm_up() -> None:

    render_raster(zbuffer_piercing(), RasterSettings(record_steps=True)).history.buffers(1)


ensure_compiled = WarmUp(_warm_up, "core.object_order.kernels", "raster", "all")
"""Compile the raster kernels once per process; returns the seconds it took (0.0 later)."""


def render_raster(scene: Scene, settings: RasterSettings = DEFAULT_SETTINGS) -> RasterResult:
    """Render ``scene`` in object order from its camera.

    Parameters
    ----------
    scene : objects, lights, background and the observer (its image size and
        projection are used).
    settings : which optional stages run.

    Returns
    -------
    RasterResult

    Notes
    -----
    Frames of less work than ``PARALLEL_WORK`` run on one thread.
    """
    import numba

    compile_s = ensure_compiled()
    work = scene.camera.width * scene.camera.height + sum(
        len(obj.triangles) for obj in scene.objects if isinstance(obj, Mesh))
    threads = numba.get_num_threads()
    numba.set_num_threads(threads if work >= PARALLEL_WORK else 1)
    try:
        result = _render(scene, settings)
    finally:
        numba.set_num_threads(threads)
    result.stats["compile_s"] = compile_s  # compiling or loading the kernels; not part of ``times``
    return result


def _render(scene: Scene, settings: RasterSettings) -> RasterResult:
    from core.object_order.kernels.raster import depth_image
    from core.object_order.kernels.transform import view_and_clip

    cam = scene.camera
    ortho = cam.projection == "orthographic"
    watch = _Stopwatch()
    meshes = tuple(object_mesh(obj) for obj in scene.objects)
    face_counts = np.array([len(m.triangles) for m in meshes], dtype=np.int64)
    face_offsets = np.concatenate([[0], np.cumsum(face_counts)]).astype(np.int64)
    world, triangles = joined_triangles(meshes)
    # Read-only either way: a mesh's own arrays are, and numba compiles a kernel apart for read-only
    # arguments, so a one-mesh scene would compile (seconds) inside a stage, after the warm-up.
    world, triangles = _read_only(world), _read_only(triangles)
    watch.lap("setup")

    # 1. World -> view (camera) space -> clip space, once per vertex.
    view_from_world, clip_from_view = cam.view_from_world, cam.clip_from_view
    view, clip = np.empty((len(world), 3)), np.empty((len(world), 4))
    view_and_clip(np.ascontiguousarray(world, dtype=float), view_from_world, clip_from_view, view, clip)
    watch.lap("transform")

    # 2. Back-face culling.
    faces = stages.back_face_culling(view, triangles, ortho)
    candidate = faces.visible if settings.back_face_culling else np.ones(len(triangles), bool)
    watch.lap("back_face_culling")

    # 3. Frustum culling of whole objects; objects inside skip the clipper's tests.
    objects, crossing, outside_faces = None, np.ones(len(meshes), dtype=bool), 0
    if settings.frustum_culling and meshes:
        spheres = [obj.bounding_sphere() for obj in scene.objects]
        objects = culling.frustum_culling(np.array([c for c, _ in spheres]),
                                          np.array([r for _, r in spheres]), cam.frustum_planes())
        state = np.array(objects.state)
        if (state == culling.OUTSIDE).any():
            candidate = candidate & np.repeat(state != culling.OUTSIDE, face_counts)
        crossing = state == culling.CROSSING
        outside_faces = int(face_counts[state == culling.OUTSIDE].sum())
    watch.lap("frustum_culling")

    # 4. Clipping in homogeneous clip space (switched off: every triangle passes whole).
    face_ids = np.flatnonzero(candidate)
    test = (_per_face(crossing, face_offsets, face_ids) if settings.clipping
            else np.zeros(len(face_ids), dtype=bool))
    clipped = stages.clip_triangles(face_ids, triangles[face_ids], clip, world, test)
    polygons = clipped.polygons
    watch.lap("clipping")

    # 5. Projection: perspective divide and viewport mapping of every vertex.
    xy, z_win = rasterization.window_coordinates(polygons.clip, cam.width, cam.height)
    watch.lap("projection")

    # 6. Flat shading, one colour per polygon, in view space (from the normals and centroids
    # of the polygons' faces, which also give the depth transparent polygons are sorted by).
    poly_object = _per_face(np.arange(len(meshes)), face_offsets, polygons.face)
    materials = [m.material for m in meshes]
    alpha = _per_face(np.array([m.opacity for m in materials], dtype=float), face_offsets, polygons.face)
    lights = np.array([(*light.position, 1.0) for light in scene.lights]).reshape(-1, 4)
    colors, sort_depth = stages.face_colors(
        faces.view, faces.triangles, polygons.face, poly_object, ortho,
        np.array([m.color for m in materials], dtype=float), np.array([m.ambient for m in materials]),
        np.array([m.diffuse for m in materials]), (lights @ view_from_world.T)[:, :3],
        np.array([np.multiply(light.color, light.intensity) for light in scene.lights]).reshape(-1, 3),
    )
    watch.lap("shading")

    # 7. Drawing order: opaque first, then transparent (sorted far to near by face centroid).
    transparent = alpha < 1.0
    order = blending.draw_order(transparent, sort_depth, settings.sort_transparent)
    in_order = not transparent.any()  # all opaque: drawn as they come, no reordering to pay for

    def drawn(values):
        return values if in_order else values[order]
    watch.lap("sorting")

    # 8. Rasterization and the z-buffer.
    if in_order and clipped.clipped == 0:  # whole triangles as they come: each is its own fan
        corners, position = polygons.vertex.reshape(-1, 3), np.arange(len(polygons))
    else:
        fan, position = rasterization.fan_triangles(polygons.offsets, order)
        corners = polygons.vertex[fan]
    zpass = fragments.draw(xy, z_win, corners, position, drawn(colors), drawn(alpha),
                           cam.width, cam.height, scene.background, settings.record_steps,
                           settings.depth_format, settings.z_test)
    watch.lap("rasterization")

    depth = depth_image(zpass.zbuf, cam.near, cam.far, ortho)
    object_index = drawn(poly_object)
    triangle_index = drawn(polygons.face) - face_offsets[object_index]
    draw = DrawList(polygons if in_order else polygons.take(order), object_index, triangle_index,
                    drawn(transparent), drawn(colors), drawn(alpha), drawn(sort_depth), zpass.generated,
                    zpass.passed)
    history = None
    if settings.record_steps:
        history = StepHistory(
            cam.width, cam.height, np.asarray(scene.background, dtype=float), cam.near, cam.far, ortho,
            np.concatenate([[0], np.cumsum(zpass.generated)]).astype(np.int64), zpass.fragments,
            draw.color, draw.alpha, object_index, triangle_index, settings.depth_format,
            settings.z_test,
        )
    watch.lap("output")

    stats = _stats(settings, cam.projection, faces, outside_faces, objects, clipped, len(corners),
                   zpass.out_of_range, draw, history, len(meshes), cam.width, cam.height, watch.times)
    return RasterResult(zpass.color, depth, zpass.zbuf, stats, settings, meshes, face_offsets, faces,
                        objects, clipped, view_from_world, clip_from_view, draw, history)


def _per_face(values: np.ndarray, face_offsets: np.ndarray, face: np.ndarray) -> np.ndarray:
    """``values[o]`` for the object ``o`` of every global face in ``face``."""
    if len(values) and (values == values[0]).all():  # one object, or all alike: no look-up
        return np.full(len(face), values[0])
    return values[np.searchsorted(face_offsets[1:], face, side="right")]


def _stats(settings, projection_name, faces, outside_faces, objects, clipped, n_triangles, out_of_range,
           draw, history, n_objects, width, height, times) -> dict:
    """Counts per stage as plain ints (JSON-serialisable)."""
    generated, passed = int(draw.generated.sum()), int(draw.passed.sum())
    back = len(faces.visible) - int(np.count_nonzero(faces.visible))
    return {
        "projection": projection_name,
        "settings": asdict(settings),
        "objects": n_objects,
        "faces": len(faces.visible),
        "faces_back_facing": back,
        "faces_culled": back if settings.back_face_culling else 0,
        "objects_outside": objects.count(culling.OUTSIDE) if objects else 0,
        "objects_inside": objects.count(culling.INSIDE) if objects else 0,
        "objects_crossing": objects.count(culling.CROSSING) if objects else 0,
        "objects_not_tested": 0 if objects else n_objects,
        "faces_in_objects_outside": outside_faces,
        "triangles_accepted_whole": clipped.accepted,
        "triangles_rejected_by_clipping": clipped.rejected,
        "polygons_clipped": clipped.clipped,
        "polygons_drawn": len(draw),
        "triangles_rasterized": n_triangles - out_of_range,
        "triangles_out_of_range": out_of_range,
        "fragments_generated": generated,
        "fragments_passed": passed,
        "fragments_failed": generated - passed,
        "blends": int(draw.passed[draw.transparent].sum()),
        "recorded_bytes": history.nbytes if history else 0,
        "zbuffer_bytes": depth_formats.BYTES_PER_PIXEL[settings.depth_format] * width * height,
        "times": {k: float(v) for k, v in times.items()},
    }
