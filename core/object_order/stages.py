"""Stages 2, 4 and 6 of the pipeline run over whole arrays: back-face culling, clipping, flat shading.

Each function here takes the frame's arrays, runs its stage's compiled loop
(:mod:`core.object_order.kernels`) and hands back the result the pipeline
(:mod:`core.object_order.pipeline`) and the views read.  The formulas those loops
compile in are written once, in the lecture's modules:

- back-face culling: :func:`core.object_order.culling.face_facing`;
- clipping: :func:`core.object_order.clipping.sutherland_hodgman`;
- flat shading: :func:`core.object_order.flat_shading.lambert`.

Dependencies run one way: this module -> the kernels -> the formulas.  The kernels
are imported where they are used, so importing this module does not load numba
(:mod:`core.compiling.jitable`).  Conventions: view space, the eye at the origin
looking down -z (:mod:`core.projection`).
"""

from __future__ import annotations

from dataclasses import dataclass
from functools import cached_property

import numpy as np

from core.object_order.clipping import ClipResult, Polygons


@dataclass(frozen=True, eq=False)
class FaceCulling:
    """The back-face test of every face, whether or not culling is switched on.

    Only ``visible`` is found at once (a frame needs no more); the normals,
    centroids and tested values of all faces are computed when first asked
    for (a million faces' would cost a frame's worth of memory traffic); flat
    shading finds those of the faces it draws on the spot (:func:`face_colors`).

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
        from core.object_order.kernels import culling as kernels

        face = np.arange(len(self.triangles))
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
    """Test every face against the observer (:func:`core.object_order.culling.face_facing`).

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
    Compiled (:func:`core.object_order.kernels.culling.front_faces`), the faces
    shared by the threads.
    """
    from core.object_order.kernels import culling as kernels

    view = np.ascontiguousarray(view, dtype=float)
    triangles = np.ascontiguousarray(triangles, dtype=np.int64)
    visible = np.empty(len(triangles), dtype=bool)
    kernels.front_faces(view, triangles, bool(orthographic), visible)
    return FaceCulling(view, triangles, bool(orthographic), visible)


def clip_triangles(face: np.ndarray, triangles: np.ndarray, clip: np.ndarray, world: np.ndarray,
                   test: np.ndarray | None = None) -> ClipResult:
    """Clip triangles against the frustum, deciding the easy cases all at once.

    A triangle whose corners are all inside every plane is accepted whole; one
    whose corners are all outside the same plane is rejected; only the rest go
    through :func:`core.object_order.clipping.sutherland_hodgman`.  Compiled
    (:func:`core.object_order.kernels.clip.clip_triangles`).

    Parameters
    ----------
    face : (K,) int64, the global face number of each triangle.
    triangles : (K, 3) int64, vertex indices of its corners.
    clip : (N, 4) float64, vertex positions in clip space.
    world : (N, 3) float64, the same vertices in world space.
    test : (K,) bool, which triangles may cross the frustum; the others (their
        object lies inside it) are accepted untested.  Default: test all.
    """
    from core.object_order.kernels import clip as kernels

    k = len(face)
    test = np.ones(k, dtype=bool) if test is None else np.asarray(test, dtype=bool)
    triangles = np.ascontiguousarray(triangles, dtype=np.int64)
    if not test.any():  # every triangle accepted whole: each is a polygon of its three corners
        polygons = Polygons(np.arange(0, 3 * k + 1, 3, dtype=np.int64), triangles.reshape(-1), clip, world,
                            np.asarray(face, dtype=np.int64), np.zeros(k, dtype=bool))
        return ClipResult(polygons, k, 0, 0)
    outcome, counts = np.empty(k, dtype=np.int8), np.empty(k, dtype=np.int64)
    new = kernels.clip_triangles(triangles, np.ascontiguousarray(clip, dtype=float),
                                 np.ascontiguousarray(world, dtype=float), test, outcome, counts)
    keep = np.flatnonzero(counts)
    offsets = np.zeros(len(keep) + 1, dtype=np.int64)
    np.cumsum(counts[keep], out=offsets[1:])
    vertex = np.empty(offsets[-1], dtype=np.int64)
    kernels.number_vertices(triangles, outcome, keep, offsets, len(clip), vertex)
    if len(new):
        clip, world = np.vstack([clip, new[:, :4]]), np.vstack([world, new[:, 4:]])
    polygons = Polygons(offsets, vertex, clip, world, face[keep], outcome[keep] != kernels.ACCEPTED)
    accepted = int(np.count_nonzero(outcome == kernels.ACCEPTED))
    return ClipResult(polygons, accepted, k - len(keep), int(np.count_nonzero(outcome == kernels.CUT)))


def face_colors(view: np.ndarray, triangles: np.ndarray, face: np.ndarray, material: np.ndarray,
                orthographic: bool, base: np.ndarray, ambient: np.ndarray, diffuse: np.ndarray,
                light_position: np.ndarray, light_rgb: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The flat Lambert colour of each polygon (:func:`core.object_order.flat_shading.lambert`),
    and its face's depth.

    Parameters
    ----------
    view : (N, 3) float64, vertex positions in view space.
    triangles : (F, 3) int64, vertex indices of each face, counter-clockwise seen from outside.
    face : (P,) int64, the face each polygon comes from (row of ``triangles``).
    material : (P,) int64, its material (row of ``base``, ``ambient``, ``diffuse``).
    orthographic : the observer looks along -z from afar (toward him is +z);
        else from the origin (toward him is ``-centroid``).
    base : (M, 3) float64, material colours, RGB in [0, 1].
    ambient, diffuse : (M,) float64, the materials' k_a and k_d.
    light_position : (L, 3) float64, point light positions, view space.
    light_rgb : (L, 3) float64, each light's colour times its intensity.

    Returns
    -------
    colors : (P, 3) float64, RGB in [0, 1].
    depth : (P,) float64, the distance of the face's centroid along the viewing
        axis (``-z`` in view space), the key transparent polygons are sorted by.

    Notes
    -----
    The face's unit normal and centroid are those of the back-face test
    (:func:`core.object_order.culling.face_facing`).  Compiled
    (:func:`core.object_order.kernels.flat_shading.face_colors`), the polygons
    shared by the threads.
    """
    from core.object_order.kernels import flat_shading as kernels

    def f64(x, cols=None):
        x = np.asarray(x, dtype=float)
        return np.ascontiguousarray(x if cols is None else x.reshape(-1, cols))

    out, depth = np.empty((len(face), 3)), np.empty(len(face))
    kernels.face_colors(f64(view, 3), np.ascontiguousarray(triangles, dtype=np.int64),
                        np.ascontiguousarray(face, dtype=np.int64),
                        np.ascontiguousarray(material, dtype=np.int64), bool(orthographic), f64(base, 3),
                        f64(ambient), f64(diffuse), f64(light_position, 3), f64(light_rgb, 3), out, depth)
    return out, depth
