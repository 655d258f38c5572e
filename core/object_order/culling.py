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

The back-face test of every face of a frame runs compiled
(:func:`core.object_order.stages.back_face_culling`), face by face with
:func:`face_facing`, the formula written once here.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.compiling.jitable import jitable

OUTSIDE, INSIDE, CROSSING = "outside", "inside", "crossing"


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
    """One triangle in view space: does it turn its back to the observer? (:func:`face_facing`)

    Examples
    --------
    >>> tri = [[0, 0, -5], [1, 0, -5], [0, 1, -5]]   # counter-clockwise seen from the eye
    >>> is_back_facing(tri), is_back_facing(tri[::-1])
    (False, True)
    """
    a, b, c = np.asarray(triangle, dtype=float)
    return not face_facing(a, b, c, bool(orthographic))[6] > 0


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
