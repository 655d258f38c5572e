"""The z-buffer (depth buffer): which surface is nearest, decided pixel by pixel.

The lecture's algorithm: clear the *image memory* to the background colour
and the *z-buffer* to the greatest depth that can occur, the far (end) plane.
Then, polygon after polygon, every fragment is tested against the z-buffer:
if it lies nearer than the value stored at its pixel it passes, and its colour
goes to image memory and its depth to the z-buffer; otherwise it fails and
nothing changes.  Objects may be drawn in any order and may even pierce each
other: each pixel is decided on its own.

The lecture stores "the z coordinate" with z pointing from the observer into
the scene.  Like GPUs and VTK, this z-buffer stores the *window depth*
``z_win = (z_ndc + 1) / 2``: 0 on the near plane, 1 on the far plane, and
smaller means nearer, so the test and the clear value are the lecture's.
It stores it in a number format (:mod:`core.object_order.depth_formats`): the
value kept and compared is the format's *depth key* of the window depth,
which for the default ``float64`` is the window depth itself.
:func:`distance_from_window_depth` turns a depth back into the distance along
the viewing axis.  Conventions are those of :mod:`core.projection`.

The test (:func:`depth_test`) is written once and compiled into the
rasterizer's kernel (:mod:`core.object_order.kernels.raster`); the running of
the algorithm over a whole draw list is :mod:`core.object_order.fragments`.
"""

from __future__ import annotations

import numpy as np

from core.compiling.jitable import jitable
from core.object_order.depth_formats import depth_key, format_code

FAR_DEPTH = 1.0
"""Window depth of the far plane: the value the z-buffer is cleared to.  Every
depth format stores it exactly, so its key is ``FAR_DEPTH`` in every format."""


def cleared_buffers(width: int, height: int, background,
                    depth_format: str = "float64") -> tuple[np.ndarray, np.ndarray]:
    """Image memory filled with ``background`` and a z-buffer filled with the far plane.

    Returns
    -------
    color : (H, W, 3) float64, RGB in [0, 1].
    zbuf : (H, W) float64, the far plane's depth key in ``depth_format``
        (``FAR_DEPTH`` in every format).
    """
    color = np.empty((height, width, 3))
    for c, value in enumerate(np.asarray(background, dtype=float)):
        color[..., c] = value  # channel by channel: far quicker than broadcasting the RGB triple
    return color, np.full((height, width), depth_key(FAR_DEPTH, format_code(depth_format)))


@jitable
def depth_test(key, stored_key):
    """The z-buffer test: a fragment passes when it is nearer than what is stored.

    Both arguments are depth keys of the same format (smaller is nearer).
    Strictly nearer is the tie rule: of two fragments with the same key, the
    one drawn first stays.

    Examples
    --------
    >>> depth_test(0.4, 1.0), depth_test(0.4, 0.4)
    (True, False)
    """
    return key < stored_key


@jitable
def distance_from_window_depth(z_win, near, far, orthographic):
    """Window depth back to the distance along the viewing axis (scene units, positive).

    Perspective: ``d = 2 n f / ((f + n) - z_ndc (f - n))`` with
    ``z_ndc = 2 z_win - 1`` (the inverse of the perspective matrix's depth
    row); orthographic: depth is linear, ``d = n + z_win (f - n)``.  ``z_win`` is
    a number or an array; the formula is compiled into the kernels too
    (:func:`core.object_order.kernels.raster.depth_image`).

    Examples
    --------
    >>> float(distance_from_window_depth(0.0, 1.0, 30.0, False))   # near plane
    1.0
    >>> float(distance_from_window_depth(1.0, 1.0, 30.0, False))   # far plane
    30.0
    """
    if orthographic:
        return near + z_win * (far - near)
    return 2.0 * near * far / ((far + near) - (2.0 * z_win - 1.0) * (far - near))
