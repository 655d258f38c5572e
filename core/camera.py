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
        """One ray per pixel centre: origins and unit directions, (H, W, 3) each.

        Perspective rays start at the eye and pass through the pixel centre on
        the near plane; orthographic rays are parallel to the viewing axis and
        start on the near plane.  ``rows = (first, stop)`` gives only those
        image rows.
        """
        w, h = self.width, self.height
        first, stop = rows if rows is not None else (0, h)
        hw, hh = self.half_extent(1.0)
        xs = ((np.arange(w) + 0.5) / w * 2.0 - 1.0) * hw
        ys = (1.0 - (np.arange(first, stop) + 0.5) / h * 2.0) * hh
        px, py = np.meshgrid(xs, ys)
        rot = self.world_from_view[:3, :3]
        eye = np.asarray(self.eye, dtype=float)
        if self.projection == "orthographic":
            view_pts = np.stack([px, py, np.full_like(px, -self.near)], axis=-1)
            origins = view_pts @ rot.T + eye
            directions = np.broadcast_to(self.forward, origins.shape).copy()
        else:
            view_dirs = np.stack([px, py, -np.ones_like(px)], axis=-1)
            directions = view_dirs @ rot.T
            directions /= np.linalg.norm(directions, axis=-1, keepdims=True)
            origins = np.broadcast_to(eye, directions.shape).copy()
        return origins, directions


def camera_problems(camera: Camera) -> list[tuple[str, str]]:
    """What makes a camera unusable, as ``(field, message)`` pairs (empty if fine)."""
    problems = []
    view = np.subtract(camera.target, camera.eye)
    if not np.any(view):
        problems.append(("target", f"must differ from eye, both are {list(camera.eye)}"))
    elif np.linalg.norm(np.cross(view / np.linalg.norm(view), camera.up)) < 1e-9:
        problems.append(("up", f"must not be parallel to the viewing direction, got {list(camera.up)}"))
    if not 0.0 < camera.fov_y_deg < 180.0:
        problems.append(("fov_y_deg", f"must be in (0, 180) degrees, got {camera.fov_y_deg}"))
    if camera.near <= 0:
        problems.append(("near", f"must be > 0, got {camera.near}"))
    elif camera.near >= camera.far:
        problems.append(("far", f"must be > near ({camera.near}), got {camera.far}"))
    if camera.projection not in PROJECTIONS:
        problems.append(("projection", f"must be one of {list(PROJECTIONS)}, got {camera.projection!r}"))
    if camera.ortho_height <= 0:
        problems.append(("ortho_height", f"must be > 0, got {camera.ortho_height}"))
    for key in ("width", "height"):
        if getattr(camera, key) < 1:
            problems.append((key, f"must be >= 1 pixel, got {getattr(camera, key)}"))
    return problems
