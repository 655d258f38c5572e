"""The observer: where the eye is, where it looks, and what it can see.

A :class:`Camera` is the lecture's observer.  Its viewing angle alpha is
``fov_y_deg`` (full vertical angle); the truncated viewing pyramid it sees is
the *frustum*, bounded by the ``near`` (front) and ``far`` (end) planes.  All
conventions are those of :mod:`core.projection`.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from core import projection
from core.compiling.jitable import jitable

PROJECTIONS = ("perspective", "orthographic")
PITCH_LIMIT_DEG = 89.0  # orbit pitch stays within ±this, so the view never lines up with "up"

Vec3 = tuple[float, float, float]


@dataclass(frozen=True)
class Camera:
    """The observer and the image it produces.

    Attributes
    ----------
    eye : world-space position of the observer's eye (scene units).
    target : world-space point the observer looks at.
    up : approximate up direction (world space); must not be parallel to the
        viewing direction.
    fov_y_deg : full vertical viewing angle alpha, in degrees, in (0, 180).
    near, far : distances of the front and end planes from the eye along the
        viewing axis, ``0 < near < far`` (scene units).
    projection : ``"perspective"`` or ``"orthographic"``.
    ortho_height : height of the orthographic view volume (scene units).
    width, height : image size in pixels.
    """

    eye: Vec3 = (6.0, 4.0, 9.0)
    target: Vec3 = (0.0, 0.8, 0.0)
    up: Vec3 = (0.0, 1.0, 0.0)
    fov_y_deg: float = 40.0
    near: float = 1.0
    far: float = 30.0
    projection: str = "perspective"
    ortho_height: float = 6.0
    width: int = 320
    height: int = 240

    def replace(self, **changes) -> Camera:
        """A copy with some fields changed (vectors given as any sequence)."""
        for key in ("eye", "target", "up"):
            if key in changes:
                changes[key] = tuple(float(c) for c in changes[key])
        return replace(self, **changes)

    @property
    def aspect(self) -> float:
        return self.width / self.height

    @property
    def forward(self) -> np.ndarray:
        """Unit viewing direction (world space)."""
        return projection.normalize(np.subtract(self.target, self.eye))

    @property
    def distance(self) -> float:
        """Distance from the eye to the target."""
        return float(np.linalg.norm(np.subtract(self.target, self.eye)))

    @property
    def yaw_deg(self) -> float:
        """Angle of the eye around the target's vertical (+y) axis; 0 on +z, 90 on +x."""
        dx, _, dz = np.subtract(self.eye, self.target)
        return float(np.degrees(np.arctan2(dx, dz)))

    @property
    def pitch_deg(self) -> float:
        """Elevation of the eye above the target's horizontal plane, in [-90, 90]."""
        offset = np.subtract(self.eye, self.target)
        return float(np.degrees(np.arcsin(np.clip(offset[1] / np.linalg.norm(offset), -1, 1))))

    def orbit(self, yaw_deg: float, pitch_deg: float, distance: float | None = None) -> Camera:
        """The observer moved on a sphere around the target (yaw, pitch in degrees).

        Examples
        --------
        >>> Camera(eye=(0, 0, 5), target=(0, 0, 0)).orbit(90, 0).eye
        (5.0, 0.0, 0.0)
        """
        r = self.distance if distance is None else distance
        yaw, pitch = np.radians(yaw_deg), np.radians(pitch_deg)
        offset = r * np.array([np.cos(pitch) * np.sin(yaw), np.sin(pitch), np.cos(pitch) * np.cos(yaw)])
        return self.replace(eye=np.round(np.add(self.target, offset), 12) + 0.0)

    @property
    def view_from_world(self) -> np.ndarray:
        return projection.look_at(self.eye, self.target, self.up)

    @property
    def world_from_view(self) -> np.ndarray:
        return np.linalg.inv(self.view_from_world)

    @property
    def clip_from_view(self) -> np.ndarray:
        if self.projection == "orthographic":
            return projection.orthographic(self.ortho_height, self.aspect, self.near, self.far)
        return projection.perspective(self.fov_y_deg, self.aspect, self.near, self.far)

    @property
    def clip_from_world(self) -> np.ndarray:
        return self.clip_from_view @ self.view_from_world

    def half_extent(self, depth: float) -> tuple[float, float]:
        """Half width and half height of the visible rectangle at ``depth``."""
        if self.projection == "orthographic":
            half_h = self.ortho_height / 2.0
        else:
            half_h = depth * np.tan(np.radians(self.fov_y_deg) / 2.0)
        return half_h * self.aspect, half_h

    def frustum_corners(self) -> np.ndarray:
        """The eight corners of the frustum, (8, 3) world space.

        Order: near plane then far plane, each as bottom-left, bottom-right,
        top-right, top-left as the observer sees them.
        """
        corners = []
        for depth in (self.near, self.far):
            hw, hh = self.half_extent(depth)
            for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
                corners.append((sx * hw, sy * hh, -depth, 1.0))
        return (self.world_from_view @ np.array(corners).T).T[:, :3]

    def frustum_planes(self) -> np.ndarray:
        """The six frustum planes, (6, 4): rows ``(nx, ny, nz, d)``, world space.

        A point ``p`` is inside when ``n . p + d >= 0`` for all six; normals are
        unit length and point inwards.  Order: left, right, bottom, top, near,
        far.  They are read off ``clip_from_world`` (the Gribb-Hartmann method):
        ``-w <= x`` gives row3 + row0, and so on.
        """
        m = self.clip_from_world
        rows = [m[3] + m[0], m[3] - m[0], m[3] + m[1], m[3] - m[1], m[3] + m[2], m[3] - m[2]]
        planes = np.array(rows)
        return planes / np.linalg.norm(planes[:, :3], axis=1, keepdims=True)

    def screen_corners(self) -> np.ndarray:
        """The screen rectangle: the frustum's cross-section on the near plane, (4, 3)."""
        return self.frustum_corners()[:4]

    def project(self, point) -> projection.ProjectedPoint:
        """Follow a world-space point through every projection stage."""
        return projection.project_point(
            point, self.view_from_world, self.clip_from_view, self.width, self.height
        )

    def primary_rays(self, rows: tuple[int, int] | None = None) -> tuple[np.ndarray, np.ndarray]:
        """One ray per pixel centre: origins and unit directions, (H, W, 3) each, world space.

        The rays of :func:`pixel_ray`, the very ones the image-order kernels
        trace (:mod:`core.image_order.ray_casting`): perspective rays start at
        the eye and pass through the pixel centre; orthographic rays are
        parallel to the viewing axis and start on the near plane.
        ``rows = (first, stop)`` gives only those image rows.
        """
        first, stop = rows if rows is not None else (0, self.height)
        x, y = np.meshgrid(np.arange(self.width, dtype=float), np.arange(first, stop, dtype=float))
        half_w, half_h = self.half_extent(1.0)
        origin, direction, _, _ = pixel_ray(
            x, y, float(self.width), float(self.height), half_w, half_h, tuple(map(float, self.eye)),
            tuple(self.world_from_view[:3, :3].ravel().tolist()), tuple(self.forward.tolist()), self.near,
            self.far, self.projection == "orthographic")
        origins = np.stack([np.broadcast_to(c, x.shape) for c in origin], axis=-1)
        directions = np.stack([np.broadcast_to(c, x.shape) for c in direction], axis=-1)
        return origins, directions


@jitable(forceinline=True)
def pixel_ray(x, y, width, height, half_width, half_height, eye, rotation, forward, near, far, orthographic):
    """The primary ray through the centre of pixel ``(x, y)``: ``(origin, direction, t_min, t_max)``.

    The lecture's ray "from the eye of the observer through the pixel".  One
    formula for the tracer's kernels (compiled in: its two steps,
    :func:`image_plane_point` once per column and row, :func:`ray_through` per pixel)
    and for :meth:`Camera.primary_rays` (plain numpy, ``x`` and ``y`` arrays of pixels).

    Parameters
    ----------
    x, y : float or array, pixels
        Column and row, from the top-left corner of the image; the ray goes
        through the pixel's centre ``(x + 0.5, y + 0.5)``.
    width, height : float, pixels
        Image size.
    half_width, half_height : float
        :meth:`Camera.half_extent` at distance 1 (perspective) or the view
        volume's half size (orthographic), scene units.
    eye : (3,) float tuple, world space
    rotation : (9,) float tuple
        ``world_from_view[:3, :3]`` row by row (view space looks down -z, +y up).
    forward : (3,) float tuple, world space, the unit viewing direction.
    near, far : float, scene units, the frustum's front and end planes.
    orthographic : bool, parallel projection.

    Returns
    -------
    origin, direction : (3,) tuples of floats (or arrays), world space
        Perspective: from the eye, through the pixel's point on the image
        plane at distance 1; orthographic: from the pixel's point on the near
        plane, along ``forward``.  ``direction`` is unit length.
    t_min, t_max : float (or arrays)
        The part of the ray between the near and the far plane, so the ray
        sees what the frustum holds.
    """
    px, py = image_plane_point(x, y, width, height, half_width, half_height)
    return ray_through(px, py, eye, rotation, forward, near, far, orthographic)


@jitable(forceinline=True)
def image_plane_point(x, y, width, height, half_width, half_height):
    """Where the centre of pixel ``(x, y)`` lies on the image plane, ``(px, py)`` in view space
    (:func:`pixel_ray`'s first step; ``px`` depends on the column alone, ``py`` on the row)."""
    return ((x + 0.5) / width * 2.0 - 1.0) * half_width, (1.0 - (y + 0.5) / height * 2.0) * half_height


@jitable(forceinline=True)
def ray_through(px, py, eye, rotation, forward, near, far, orthographic):
    """The rest of :func:`pixel_ray`: the ray through the image plane's point ``(px, py)``
    (:func:`image_plane_point`)."""
    r = rotation
    ex, ey, ez = eye
    fx, fy, fz = forward
    if orthographic:
        vz = -near
        o = (ex + r[0] * px + r[1] * py + r[2] * vz,
             ey + r[3] * px + r[4] * py + r[5] * vz,
             ez + r[6] * px + r[7] * py + r[8] * vz)
        return o, (fx, fy, fz), 0.0, far - near
    dx = r[0] * px + r[1] * py - r[2]
    dy = r[3] * px + r[4] * py - r[5]
    dz = r[6] * px + r[7] * py - r[8]
    length = np.sqrt(dx * dx + dy * dy + dz * dz)
    d = (dx / length, dy / length, dz / length)
    along = d[0] * fx + d[1] * fy + d[2] * fz
    return (ex, ey, ez), d, near / along, far / along


#: The smallest pixel a camera may have, in radians of viewing angle (perspective)
#: or relative to the size of the coordinates (orthographic), and the smallest
#: ``near / far``.  float64 resolves about 2.2e-16, so 1e-10 keeps neighbouring
#: pixels a million rounding steps apart: below it the rasterizer's depths and
#: pixel positions collapse while rays still differ, so the two renderers
#: would disagree.
MIN_PIXEL = 1e-10
MIN_NEAR_RATIO = 1e-10


def _finite_problems(camera: Camera) -> list[tuple[str, str]]:
    problems = []
    for key in ("eye", "target", "up", "fov_y_deg", "near", "far", "ortho_height"):
        value = getattr(camera, key)
        if not np.isfinite(np.asarray(value, dtype=float)).all():
            problems.append((key, f"must be finite, got {value!r}"))
    return problems


def _view_problems(camera: Camera) -> list[tuple[str, str]]:
    """Problems of the viewing direction and of the basis computed from it."""
    view = np.subtract(camera.target, camera.eye)
    scale = max(1.0, float(np.abs(camera.eye).max()), float(np.abs(camera.target).max()))
    distance = float(np.max(np.abs(view)))
    if distance == 0.0:
        return [("target", f"must differ from eye, both are {list(camera.eye)}")]
    if distance < 1e-9 * scale:
        return [("target", f"too close to eye ({distance:.3g} apart) to give a viewing "
                           f"direction; keep them at least {1e-9 * scale:.3g} apart")]
    unit = view / distance
    if np.linalg.norm(np.cross(unit / np.linalg.norm(unit), camera.up)) < 1e-9:
        return [("up", f"must not be parallel to the viewing direction, got {list(camera.up)}")]
    with np.errstate(all="ignore"):
        basis = projection.look_at(camera.eye, camera.target, camera.up)
    if not np.isfinite(basis).all():
        return [("target", "eye, target and up give no finite viewing basis")]
    return []


def _precision_problems(camera: Camera) -> list[tuple[str, str]]:
    """A frustum too thin for the rasterizer's float64 arithmetic."""
    problems = []
    h = camera.height
    if np.radians(camera.fov_y_deg) / h < MIN_PIXEL:
        least = np.degrees(MIN_PIXEL * h)
        problems.append(("fov_y_deg", f"too small for a {h}-pixel-high image: at least "
                                      f"{least:.3g} degrees, got {camera.fov_y_deg}"))
    if camera.near < MIN_NEAR_RATIO * camera.far:
        problems.append(("near", f"too small for far = {camera.far}: at least "
                                 f"{MIN_NEAR_RATIO * camera.far:.3g} (far / 1e10), got {camera.near}"))
    scale = max(1.0, float(np.abs(camera.eye).max()), camera.far)
    if camera.ortho_height / h < MIN_PIXEL * scale:
        problems.append(("ortho_height", f"too small for a {h}-pixel-high image at coordinates "
                                         f"this size: at least {MIN_PIXEL * scale * h:.3g}, "
                                         f"got {camera.ortho_height}"))
    if not problems:
        with np.errstate(all="ignore"):
            clip = camera.clip_from_view
        if not np.isfinite(clip).all():
            problems.append(("projection", "the projection matrix is not finite"))
    return problems


def camera_problems(camera: Camera) -> list[tuple[str, str]]:
    """What makes a camera unusable, as ``(field, message)`` pairs (empty if fine).

    Besides the ranges of its fields, a camera is judged by what it computes:
    its viewing basis and projection matrix must be finite, and its pixels and
    depth range wide enough for float64 (:data:`MIN_PIXEL`,
    :data:`MIN_NEAR_RATIO`), so that the rasterizer and the ray caster either
    both render it or both refuse it.
    """
    problems = _finite_problems(camera)
    if problems:
        return problems
    problems = _view_problems(camera)
    range_ok = True
    if not 0.0 < camera.fov_y_deg < 180.0:
        problems.append(("fov_y_deg", f"must be in (0, 180) degrees, got {camera.fov_y_deg}"))
        range_ok = False
    if camera.near <= 0:
        problems.append(("near", f"must be > 0, got {camera.near}"))
        range_ok = False
    elif camera.near >= camera.far:
        problems.append(("far", f"must be > near ({camera.near}), got {camera.far}"))
        range_ok = False
    if camera.projection not in PROJECTIONS:
        problems.append(("projection", f"must be one of {list(PROJECTIONS)}, got {camera.projection!r}"))
        range_ok = False
    if camera.ortho_height <= 0:
        problems.append(("ortho_height", f"must be > 0, got {camera.ortho_height}"))
        range_ok = False
    for key in ("width", "height"):
        if getattr(camera, key) < 1:
            problems.append((key, f"must be >= 1 pixel, got {getattr(camera, key)}"))
            range_ok = False
    if range_ok:
        problems += _precision_problems(camera)
    return problems
