"""The lecture's barycentric test for many rays and triangles at once, in plain numpy.

A ray ``o + t d`` crosses the plane of triangle ``(A, B, C)`` at the point
``A + u (B - A) + v (C - A)``; the point lies in the triangle when its
barycentric coordinates ``(1 - u - v, u, v)`` are all >= 0 (the lecture's test
of a point against a triangle).  :func:`crossings` solves for ``u``, ``v`` and
``t`` by Cramer's rule in the arrangement of Möller and Trumbore, written as
the textbook writes it (one reciprocal of the determinant, three products), for
every ray against every triangle; the callers decide what counts as a hit:

* :func:`first_crossings` (the first look, :mod:`core.first_look`, and the
  hard-case lab's ray-cast reference) takes ``det != 0`` and a range of ``t``;
* the textbook test with its ``ε`` (:func:`core.hard_cases.triangle_cases.textbook_moller_trumbore`)
  is shown beside the watertight one the kernels use
  (:func:`core.image_order.intersect_triangle.intersect_triangle`).
"""

from __future__ import annotations

import numpy as np

#: Rays per chunk of :func:`first_crossings` (each chunk holds rays x triangles numbers).
CHUNK_TESTS = 2_000_000


def crossings(origins: np.ndarray, directions: np.ndarray, A: np.ndarray, B: np.ndarray,
              C: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Where each ray crosses each triangle's plane, in barycentric coordinates.

    Parameters
    ----------
    origins, directions : (R, 3) float64, world space.
    A, B, C : (T, 3) float64, the triangles' corners.

    Returns
    -------
    det, u, v, t : (R, T) float64 each
        ``det`` is the system's determinant, ``-d . ((B - A) x (C - A))``
        (0 for a ray parallel to the plane, where ``u``, ``v`` and ``t`` are
        NaN or infinite); the crossing is ``o + t d = A + u (B - A) + v (C - A)``.

    Examples
    --------
    >>> A, B, C = np.array([[0.0, 0.0, -2.0]]), np.array([[1.0, 0.0, -2.0]]), np.array([[0.0, 1.0, -2.0]])
    >>> det, u, v, t = crossings(np.array([[0.25, 0.5, 0.0]]), np.array([[0.0, 0.0, -1.0]]), A, B, C)
    >>> float(det[0, 0]), float(u[0, 0]), float(v[0, 0]), float(t[0, 0])
    (1.0, 0.25, 0.5, 2.0)
    """
    e1, e2 = B - A, C - A
    h = np.cross(directions[:, None, :], e2[None])
    det = np.einsum("rtk,tk->rt", h, e1)
    with np.errstate(divide="ignore", invalid="ignore"):
        inv = 1.0 / det
        s = origins[:, None, :] - A[None]
        u = inv * np.einsum("rtk,rtk->rt", s, h)
        q = np.cross(s, e1[None])
        v = inv * np.einsum("rk,rtk->rt", directions, q)
        t = inv * np.einsum("tk,rtk->rt", e2, q)
    return det, u, v, t


def nearest(crossed: np.ndarray, t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Each ray's nearest crossing among those ``crossed`` ((R, T) bool, with their ``t``).

    Returns
    -------
    index : (R,) int64, the nearest triangle, -1 where the ray crosses none.
    t : (R,) float64, its ``t`` (``inf`` where none).
    """
    t = np.where(crossed, t, np.inf)
    best = np.argmin(t, axis=1)
    t_best = t[np.arange(len(t)), best]
    return np.where(np.isfinite(t_best), best, -1), t_best


def first_crossings(origins: np.ndarray, directions: np.ndarray, triangles: np.ndarray,
                    t_min: float = 0.0, t_max: float = np.inf) -> tuple[np.ndarray, np.ndarray]:
    """The first triangle each ray crosses with ``t_min <= t <= t_max``, and its ``t``.

    A ray crosses a triangle where ``det != 0``, ``u, v >= 0`` and ``u + v <= 1``
    (:func:`crossings`); a ray through an edge counts for either triangle.
    The rays are taken in chunks of about :data:`CHUNK_TESTS` ray-triangle pairs.

    Parameters
    ----------
    origins, directions : (R, 3) float64, world space.
    triangles : (T, 3, 3) float64, world space.
    t_min, t_max : the part of the ray searched (the frustum's depth range, say).

    Returns
    -------
    index : (R,) int64, the nearest triangle, -1 where the ray crosses none.
    t : (R,) float64, its ``t`` (``inf`` where none).

    Examples
    --------
    >>> tri = np.array([[[-1.0, -1.0, -5.0], [1.0, -1.0, -5.0], [0.0, 1.0, -5.0]]])
    >>> first_crossings(np.zeros((2, 3)), np.array([[0.0, 0.0, -1.0], [0.0, 0.0, 1.0]]), tri)
    (array([ 0, -1]), array([ 5., inf]))
    """
    n = len(origins)
    index = np.full(n, -1, dtype=np.int64)
    nearest_t = np.full(n, np.inf)
    if len(triangles) == 0:
        return index, nearest_t
    A, B, C = triangles[:, 0], triangles[:, 1], triangles[:, 2]
    step = max(1, CHUNK_TESTS // len(triangles))
    for first in range(0, n, step):
        det, u, v, t = crossings(origins[first:first + step], directions[first:first + step], A, B, C)
        crossed = (det != 0) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t >= t_min) & (t <= t_max)
        index[first:first + step], nearest_t[first:first + step] = nearest(crossed, t)
    return index, nearest_t
