"""Culling: dropping what cannot be seen before any pixel is touched.

Two tests from the lecture, both cheap and both conservative:

- **Back-face culling** (elimination of invisible sides by their normal
  vectors).  A face of a closed solid whose outward normal points away from
  the observer is seen from inside the solid, hence hidden.  The lecture tests
  the sign of ``Nz``, the normal's component along the viewing axis, which is
  exact for the parallel (orthographic) projection.  In perspective the
  projecting rays fan out from the eye, so the normal is compared with the
  vector from the face to the eye instead.  On a convex solid this alone
  solves visibility; on a non-convex one a front face can still be partly
  hidden by another part of the solid, which only the z-buffer resolves.
- **Frustum culling** (only objects inside the viewing pyramid matter).  Each
  object's bounding sphere is compared with the six planes of the frustum:
  entirely *outside* one plane -> dropped; *inside* all six by its radius ->
  drawn without clipping; otherwise *crossing* -> its polygons are clipped
  (:mod:`core.object_order.clipping`).

Conventions are those of :mod:`core.projection`: in view (camera) space the
eye is at the origin looking down -z, so the direction toward the observer is
+z and ``Nz`` is the normal's z component there.
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from core.compiling.jitable import jitable

OUTSIDE, INSIDE, CROSSING = "outside", "inside", "crossing"


@dataclass(frozen=True, eq=False)
class FaceCulling:
    """The back-face test of every face, whether or not culling is switched on.

    Only ``visible`` is found at once (a frame needs no more); the normals,
    centroids and tested values of all faces are computed when first asked
    for (a million faces' would cost a frame's worth of memory traffic); flat
    shading finds those of the faces it draws on the spot
    (:func:`core.object_order.flat_shading.face_colors`).

    Attributes
    ----------
    view : (N, 3) float64, vertex positions in view space.
    triangles : (F, 3) int64, vertex indices of each face.
    orthographic : the parallel projection was tested (else perspective).
    visible : (F,) bool, ``facing > 0``: a front face.
    normal : (F, 3) float64, unit outward normal in view space (from the
        counter-clockwise winding).
    nz : (F,) float64, its z component, the lecture's ``Nz`` (> 0: toward the
        observer along the viewing axis).
    centroid : (F, 3) float64, the face's centroid in view space.
    facing : (F,) float64, the value tested: the cosine between the normal and
        the direction from the centroid to the eye (perspective), or ``Nz``
        (orthographic).
    """

    view: np.ndarray
    triangles: np.ndarray
    orthographic: bool
    visible: np.ndarray

    @cached_property
    def _all(self) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        return self._test(np.arange(len(self.triangles)))

    def _test(self, face: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        from core.object_order.kernels import culling as kernels  # the kernel compiles in this module

        normal, centroid, facing = np.empty((len(face), 3)), np.empty((len(face), 3)), np.empty(len(face))
        kernels.back_face_test(self.view, self.triangles, face, self.orthographic, normal, centroid, facing)
        return normal, centroid, facing

    @property
    def normal(self) -> np.ndarray:
        return self._all[0]

    @property
    def nz(self) -> np.ndarray:
        return self._all[0][:, 2]

    @property
    def centroid(self) -> np.ndarray:
        return self._all[1]

    @property
    def facing(self) -> np.ndarray:
        return self._all[2]

    @property
    def culled(self) -> np.ndarray:
        """(F,) bool, back faces."""
        return ~self.visible


def back_face_culling(view: np.ndarray, triangles: np.ndarray, orthographic: bool) -> FaceCulling:
    """Test every face against the observer.

    Parameters
    ----------
    view : (N, 3) float64, vertex positions in view space.
    triangles : (F, 3) int64, vertex indices of each face, counter-clockwise
        seen from outside.
    orthographic : True for the parallel projection (all projecting rays along
        -z), False for perspective (rays from the eye at the origin).

    Returns
    -------
    FaceCulling

    Notes
    -----
    Compiled (:func:`core.object_order.kernels.culling.front_faces`), face
    by face with :func:`face_facing`.
    """
    from core.object_order.kernels import culling as kernels  # the kernel compiles in this module

    view = np.ascontiguousarray(view, dtype=float)
    triangles = np.ascontiguousarray(triangles, dtype=np.int64)
    visible = np.empty(len(triangles), dtype=bool)
    kernels.front_faces(view, triangles, bool(orthographic), visible)
    return FaceCulling(view, triangles, bool(orthographic), visible)


@jitable
def face_facing(a, b, c, orthographic):
    """The back-face test of one triangle ``a, b, c`` (view space, counter-clockwise from outside).

    Returns
    -------
    nx, ny, nz : its unit outward normal ``(b - a) x (c - a) / |...|`` (zero
        for a triangle with no area).
    cx, cy, cz : its centroid.
    facing : ``Nz`` (orthographic), or the cosine between the normal and the
        direction from the centroid to the eye at the origin (perspective);
        the face is seen from the front when it is > 0.
    """
    e1x, e1y, e1z = b[0] - a[0], b[1] - a[1], b[2] - a[2]
    e2x, e2y, e2z = c[0] - a[0], c[1] - a[1], c[2] - a[2]
    nx, ny, nz = e1y * e2z - e1z * e2y, e1z * e2x - e1x * e2z, e1x * e2y - e1y * e2x
    length = np.sqrt(nx * nx + ny * ny + nz * nz)
    if length == 0:
        length = 1.0
    nx, ny, nz = nx / length, ny / length, nz / length
    cx, cy, cz = (a[0] + b[0] + c[0]) / 3.0, (a[1] + b[1] + c[1]) / 3.0, (a[2] + b[2] + c[2]) / 3.0
    if orthographic:
        return nx, ny, nz, cx, cy, cz, nz
    dist = np.sqrt(cx * cx + cy * cy + cz * cz)  # the eye is the origin: centroid-to-eye is -centroid
    if dist == 0:
        dist = 1.0
    return nx, ny, nz, cx, cy, cz, -(nx * cx + ny * cy + nz * cz) / dist


def is_back_facing(triangle, orthographic: bool = False) -> bool:
    """One triangle in view space: does it turn its back to the observer?

    Examples
    --------
    >>> tri = [[0, 0, -5], [1, 0, -5], [0, 1, -5]]   # counter-clockwise seen from the eye
    >>> is_back_facing(tri), is_back_facing(tri[::-1])
    (False, True)
    """
    corners = np.asarray(triangle, dtype=float)
    return not bool(back_face_culling(corners, np.array([[0, 1, 2]]), orthographic).visible[0])


@dataclass(frozen=True)
class ObjectCulling:
    """Where each object's bounding sphere lies relative to the frustum.

    Attributes
    ----------
    center : (O, 3) float64, bounding sphere centres, world space.
    radius : (O,) float64, their radii (scene units).
    distance : (O, 6) float64, signed distance of each centre from the planes
        left, right, bottom, top, near, far (positive inside).
    state : tuple of ``"outside"``, ``"inside"`` or ``"crossing"`` per object.
    """

    center: np.ndarray
    radius: np.ndarray
    distance: np.ndarray
    state: tuple[str, ...]

    def count(self, state: str) -> int:
        return sum(s == state for s in self.state)


def frustum_culling(center: np.ndarray, radius: np.ndarray, planes: np.ndarray) -> ObjectCulling:
    """Classify bounding spheres against the six frustum planes.

    Parameters
    ----------
    center : (O, 3) float64, world space.
    radius : (O,) float64.
    planes : (6, 4) float64, rows ``(nx, ny, nz, d)`` with unit inward normals,
        world space (:meth:`core.camera.Camera.frustum_planes`).

    Returns
    -------
    ObjectCulling

    Notes
    -----
    The test is conservative: a sphere near a corner of the frustum can be
    outside it while crossing two planes' extensions; it is then called
    crossing and clipping removes its polygons.

    Examples
    --------
    >>> planes = np.array([[1, 0, 0, 1], [-1, 0, 0, 1], [0, 1, 0, 1], [0, -1, 0, 1],
    ...                    [0, 0, 1, 1], [0, 0, -1, 1]], dtype=float)   # the cube [-1, 1]^3
    >>> frustum_culling(np.array([[0, 0, 0], [0.8, 0, 0], [3, 0, 0]]), np.array([0.5] * 3),
    ...                 planes).state
    ('inside', 'crossing', 'outside')
    """
    center = np.asarray(center, dtype=float).reshape(-1, 3)
    radius = np.asarray(radius, dtype=float).reshape(-1)
    distance = center @ planes[:, :3].T + planes[:, 3]
    state = tuple(
        OUTSIDE if np.any(d < -r) else INSIDE if np.all(d >= r) else CROSSING
        for d, r in zip(distance, radius, strict=True)
    )
    return ObjectCulling(center, radius, distance, state)
