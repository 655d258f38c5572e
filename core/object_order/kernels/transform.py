"""Transforming vertices compiled: a 4 x 4 matrix applied to every point in one loop.

The pipeline's first stage (world -> view -> clip space,
:mod:`core.object_order.pipeline`).  Matrices act on column vectors
``[x, y, z, 1]``.
"""

from __future__ import annotations

import numpy as np
from numba import njit


@njit(cache=True, nogil=True)
def transform_points(points, matrix, rows):
    """``(matrix @ [p, 1])[:rows]`` for every point ``p``.

    Parameters
    ----------
    points : (N, 3) float64, in the matrix's source frame.
    matrix : (4, 4) float64, e.g. ``view_from_world``.
    rows : int, 3 (an affine map's result) or 4 (homogeneous clip coordinates).

    Returns
    -------
    (N, rows) float64, in the matrix's target frame.
    """
    out = np.empty((points.shape[0], rows))
    for i in range(points.shape[0]):
        x, y, z = points[i, 0], points[i, 1], points[i, 2]
        for k in range(rows):
            out[i, k] = matrix[k, 0] * x + matrix[k, 1] * y + matrix[k, 2] * z + matrix[k, 3]
    return out
