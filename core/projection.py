"""Projection: from world space to pixels, one named stage at a time.

The lecture projects a 3D scene onto the screen plane in two ways: *perspective*
projection, where every projecting ray meets the observer's eye, and *parallel*
(orthographic) projection, where the projecting rays are parallel and
perpendicular to the screen.  This module gives both as 4x4 matrices and
follows one point through every stage.

Conventions (used everywhere in ``core``)
-----------------------------------------
- World space is right-handed; a scene's "up" is usually +y.
- View (camera) space: the eye at the origin, looking down **-z**, +y up,
  +x to the right (the OpenGL/VTK camera).  A point in front of the observer
  has negative view-space z; its *depth* is ``-z`` (positive, scene units).
- Clip space: homogeneous ``(x, y, z, w)`` after ``clip_from_view``.  A point is
  inside the frustum when ``-w <= x, y, z <= w`` (OpenGL convention).
- NDC (normalised device coordinates): clip divided by ``w``, in ``[-1, 1]^3``;
  ``z_ndc = -1`` on the near plane and ``+1`` on the far plane.
- Pixels: ``x`` grows to the right from the image's left edge, ``y`` grows
  *down* from its top edge (image rows), in pixel units; the centre of pixel
  ``(i, j)`` (column ``i``, row ``j``) is at ``(i + 0.5, j + 0.5)``.
- Matrices act on column vectors and are named ``a_from_b`` (pbrt's habit), so
  ``clip_from_world = clip_from_view @ view_from_world`` reads right to left.
- Angles are degrees in parameters whose name ends in ``_deg``.

The lecture's own perspective form puts the screen (projection) plane at
``z = 0`` and the eye at ``z = -d`` with z pointing into the scene;
:func:`lecture_perspective` gives that matrix.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def normalize(v: np.ndarray) -> np.ndarray:
    """Return ``v`` scaled to unit length (``v`` must not be zero)."""
    v = np.asarray(v, dtype=float)
    return v / np.linalg.norm(v)


def look_at(eye, target, up) -> np.ndarray:
    """View matrix ``view_from_world``: the eye to the origin, looking down -z.

    Parameters
    ----------
    eye, target, up : (3,) float, world space
        Observer position, the point looked at, and the approximate up vector
        (it must not be parallel to ``target - eye``).

    Returns
    -------
    (4, 4) float64

    Examples
    --------
    >>> m = look_at((0, 0, 5), (0, 0, 0), (0, 1, 0))
    >>> (m @ [0, 0, 0, 1]).round(6).tolist()
    [0.0, 0.0, -5.0, 1.0]
    """
    eye = np.asarray(eye, dtype=float)
    forward = normalize(np.asarray(target, dtype=float) - eye)
    right = normalize(np.cross(forward, up))
    true_up = np.cross(right, forward)
    m = np.eye(4)
    m[0, :3], m[1, :3], m[2, :3] = right, true_up, -forward
    m[:3, 3] = -m[:3, :3] @ eye
    return m


def perspective(fov_y_deg: float, aspect: float, near: float, far: float) -> np.ndarray:
    """Perspective matrix ``clip_from_view`` (OpenGL ``gluPerspective``).

    ``fov_y_deg`` is the full vertical viewing angle (the lecture's alpha),
    ``aspect`` is width / height, ``near`` and ``far`` are positive distances.

    Examples
    --------
    >>> p = perspective(90.0, 1.0, 1.0, 10.0)
    >>> v = p @ [0.0, 0.0, -1.0, 1.0]   # a point on the near plane
    >>> float(v[2] / v[3])
    -1.0
    """
    f = 1.0 / np.tan(np.radians(fov_y_deg) / 2.0)
    m = np.zeros((4, 4))
    m[0, 0] = f / aspect
    m[1, 1] = f
    m[2, 2] = (far + near) / (near - far)
    m[2, 3] = 2.0 * far * near / (near - far)
    m[3, 2] = -1.0
    return m


def orthographic(height: float, aspect: float, near: float, far: float) -> np.ndarray:
    """Orthographic (parallel) matrix ``clip_from_view`` (OpenGL ``glOrtho``).

    The view volume is a box ``height`` tall and ``height * aspect`` wide,
    centred on the viewing axis, from depth ``near`` to ``far``.

    Examples
    --------
    >>> o = orthographic(2.0, 1.0, 1.0, 3.0)
    >>> (o @ [1.0, 1.0, -3.0, 1.0]).tolist()   # far top-right corner
    [1.0, 1.0, 1.0, 1.0]
    """
    half_h = height / 2.0
    half_w = half_h * aspect
    m = np.eye(4)
    m[0, 0] = 1.0 / half_w
    m[1, 1] = 1.0 / half_h
    m[2, 2] = -2.0 / (far - near)
    m[2, 3] = -(far + near) / (far - near)
    return m


def lecture_perspective(d: float) -> np.ndarray:
    """The lecture's perspective matrix: screen plane z = 0, eye at z = -d.

    Here z points *into* the scene.  A point ``(x, y, z)`` maps to
    ``(x, y, 0, z/d + 1)``; after dividing by the last coordinate it lands at
    ``(x d / (z + d), y d / (z + d), 0)``, where the ray from the eye through
    the point crosses the screen plane.

    Examples
    --------
    >>> p = lecture_perspective(2.0) @ [4.0, 2.0, 2.0, 1.0]
    >>> (p[:3] / p[3]).tolist()
    [2.0, 1.0, 0.0]
    """
    m = np.eye(4)
    m[2, 2] = 0.0
    m[3, 2] = 1.0 / d
    return m


def lecture_image(point, d: float) -> np.ndarray:
    """Where the lecture's perspective (:func:`lecture_perspective`) puts ``point`` = (x, y, z) on the
    screen, ``(x', y')``: the matrix, then the division by the last coordinate.

    >>> lecture_image([4.0, 2.0, 2.0], 2.0).tolist()
    [2.0, 1.0]
    """
    p = lecture_perspective(d) @ np.append(np.asarray(point, dtype=float), 1.0)
    return p[:2] / p[3]


def lecture_screen_point(view_point, near: float, projection: str = "perspective"):
    """A camera-space point in the lecture's coordinates (Fig. VII.6 and VII.7) and its image.

    The lecture puts the screen in the plane z = 0 and, for perspective, the eye at z = -d, with z
    pointing into the scene; the window's screen is the near plane, at ``d = near`` in front of the
    eye, which looks down camera space's -z.  So ``A = (x, y, -z_view - d)``; perspective takes it to
    ``A' = (x d / (z + d), y d / (z + d))`` (:func:`lecture_image`), orthographic projection
    keeps ``x`` and ``y`` (Fig. VII.7).  Returns ``(A, A')``; ``A'`` is ``None`` for a point at or
    behind the eye, which perspective cannot take to the screen.

    >>> a, image = lecture_screen_point([1.0, 0.5, -4.0], near=2.0)
    >>> a.tolist(), image.tolist()
    ([1.0, 0.5, 2.0], [0.5, 0.25])
    >>> lecture_screen_point([1.0, 0.5, -4.0], near=2.0, projection="orthographic")[1].tolist()
    [1.0, 0.5]
    """
    x, y, z = (float(c) for c in view_point)
    a = np.array([x, y, -z - near])
    if projection == "orthographic":
        return a, a[:2].copy()
    if -z <= 0.0:
        return a, None
    return a, lecture_image(a, near)


def pixel_from_ndc(ndc_xy: np.ndarray, width: int, height: int) -> np.ndarray:
    """Viewport mapping: NDC ``[-1, 1]^2`` to pixel coordinates (y down)."""
    ndc_xy = np.asarray(ndc_xy, dtype=float)
    x = (ndc_xy[..., 0] + 1.0) * 0.5 * width
    y = (1.0 - ndc_xy[..., 1]) * 0.5 * height
    return np.stack([x, y], axis=-1)


@dataclass(frozen=True)
class ProjectedPoint:
    """One point followed through every stage of projection.

    Attributes
    ----------
    world : (3,) world-space position.
    view : (3,) camera-space position (looking down -z); ``depth = -view[2]``.
    clip : (4,) homogeneous clip coordinates before the divide.
    ndc : (3,) clip divided by w; ``None`` when ``w <= 0`` (behind the eye),
        where the divide would mirror the point.
    pixel : (2,) pixel coordinates (x right, y down); ``None`` with ``ndc``.
    inside : bool, the point lies in the frustum (``-w <= x, y, z <= w``).
    """

    world: np.ndarray
    view: np.ndarray
    clip: np.ndarray
    ndc: np.ndarray | None
    pixel: np.ndarray | None
    inside: bool

    @property
    def depth(self) -> float:
        """Distance along the viewing axis, positive in front of the eye."""
        return float(-self.view[2])


def project_point(point, view_from_world, clip_from_view, width, height) -> ProjectedPoint:
    """Project one world-space point through view, clip, NDC and pixel stages."""
    world = np.asarray(point, dtype=float)
    view = (view_from_world @ np.append(world, 1.0))[:3]
    clip = clip_from_view @ np.append(view, 1.0)
    w = clip[3]
    inside = bool(w > 0 and np.all(np.abs(clip[:3]) <= w * (1 + 1e-12)))
    if w <= 0:
        return ProjectedPoint(world, view, clip, None, None, inside)
    ndc = clip[:3] / w
    return ProjectedPoint(world, view, clip, ndc, pixel_from_ndc(ndc[:2], width, height), inside)
