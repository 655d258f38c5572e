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

import numpy as np

OUTSIDE, INSIDE, CROSSING = "outside", "inside", "crossing"


@dataclass(frozen=True)
class FaceCulling:
    """The back-face test of every face, whether or not culling is switched on.

    Attributes
    ----------
    normal : (F, 3) float64, unit outward normal in view space (from the
        counter-clockwise winding).
    nz : (F,) float64, its z component, the lecture's ``Nz`` (> 0: toward the
        observer along the viewing axis).
    centroid : (F, 3) float64, the face's centroid in view space.
    facing : (F,) float64, the value tested: the cosine between the normal and
        the direction from the centroid to the eye (perspective), or ``Nz``
        (orthographic).
    visible : (F,) bool, ``facing > 0``: a front face.
    """

    normal: np.ndarray
    nz: np.ndarray
    centroid: np.ndarray
    facing: np.ndarray
    visible: np.ndarray

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
    """
    coords = [np.ascontiguousarray(view[:, k]) for k in range(3)]
    corner = [np.ascontiguousarray(triangles[:, k]) for k in range(3)]
    a, b, c = ([x[i] for x in coords] for i in corner)  # per corner: x, y, z arrays of length F
    e1 = [b[k] - a[k] for k in range(3)]
    e2 = [c[k] - a[k] for k in range(3)]
    n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]]
    length = np.sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2])
    length[length == 0] = 1.0
    n = [v / length for v in n]
    centroid = [(a[k] + b[k] + c[k]) / 3.0 for k in range(3)]
    if orthographic:
        facing = n[2]
    else:  # the eye is the origin of view space, so the centroid-to-eye vector is -centroid
        dist = np.sqrt(centroid[0] ** 2 + centroid[1] ** 2 + centroid[2] ** 2)
        dist[dist == 0] = 1.0
        facing = -(n[0] * centroid[0] + n[1] * centroid[1] + n[2] * centroid[2]) / dist
    return FaceCulling(np.stack(n, axis=1), n[2], np.stack(centroid, axis=1), facing, facing > 0)


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


def bounding_sphere(points: np.ndarray) -> tuple[np.ndarray, float]:
    """A sphere around points: centred on their bounding box, out to the farthest one.

    Parameters
    ----------
    points : (N, 3) float64, N >= 1.

    Returns
    -------
    center : (3,) float64 and radius : float, in the points' frame and units.

    Examples
    --------
    >>> c, r = bounding_sphere(np.array([[0.0, 0.0, 0.0], [2.0, 0.0, 0.0], [1.0, 1.0, 0.0]]))
    >>> c.tolist(), r
    ([1.0, 0.5, 0.0], 1.118033988749895)
    """
    coords = np.ascontiguousarray(np.asarray(points, dtype=float).T)  # (3, N): fast reductions
    center = (coords.min(axis=1) + coords.max(axis=1)) / 2.0
    offset = coords - center[:, None]
    return center, float(np.sqrt((offset * offset).sum(axis=0).max()))


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
