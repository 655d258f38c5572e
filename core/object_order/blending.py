"""Transparency in object order: opaque first, then transparent far to near, blended.

The lecture's rule: draw all opaque polygons first; then draw the transparent
ones ordered from the farthest to the closest, each mixing its colour into the
image memory with

    c0 = alpha_s cs + (1 - alpha_s) cd

where alpha_s in (0, 1) is the polygon's transparency coefficient (its
``Material.opacity``), cs its colour, cd the colour already stored at the
pixel and c0 the colour written back.

Transparent fragments are depth-tested and, like every passing fragment, write
their depth.  So the order matters twice: a transparent polygon drawn too
early hides the ones behind it drawn later (they fail the depth test), and
two blends give different colours in different orders.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.compiling.jitable import jitable


@jitable
def blend_over(alpha, source, destination):
    """The lecture's blend ``c0 = alpha cs + (1 - alpha) cd`` (RGB in [0, 1]).

    Written once: the rasterizer's kernel applies it channel by channel
    (:mod:`core.object_order.kernels.raster`), the pixel history to whole
    colours; ``source`` and ``destination`` may be numbers or (3,) arrays.
    With ``alpha = 1`` (opaque) it writes ``cs`` unchanged.

    Examples
    --------
    >>> blend_over(0.25, np.array([1.0, 0.0, 0.0]), np.array([0.0, 0.0, 1.0])).tolist()
    [0.25, 0.0, 0.75]
    """
    return alpha * source + (1.0 - alpha) * destination


@dataclass(frozen=True)
class Blend:
    """One blend at one pixel: the lecture's terms.

    Attributes
    ----------
    alpha : the polygon's transparency coefficient alpha_s.
    source : (3,) cs, the polygon's colour.
    destination : (3,) cd, the colour in image memory before.
    result : (3,) c0, the colour written.
    """

    alpha: float
    source: np.ndarray
    destination: np.ndarray
    result: np.ndarray


def draw_order(transparent: np.ndarray, depth: np.ndarray, sort: bool = True) -> np.ndarray:
    """The order to draw polygons in: opaque first, then transparent.

    Parameters
    ----------
    transparent : (P,) bool, polygons with alpha_s < 1.
    depth : (P,) float64, distance of each polygon from the observer along the
        viewing axis (scene units), used to sort the transparent ones.
    sort : draw the transparent polygons from the farthest to the closest; if
        False, in the order given (which shows why sorting is needed).

    Returns
    -------
    (P,) int64, polygon indices in drawing order.  Ties keep the given order.

    Examples
    --------
    >>> draw_order(np.array([True, False, True]), np.array([1.0, 5.0, 3.0])).tolist()
    [1, 2, 0]
    """
    transparent = np.asarray(transparent, dtype=bool)
    if not transparent.any():  # all opaque: the order given
        return np.arange(len(transparent), dtype=np.int64)
    opaque, clear = np.flatnonzero(~transparent), np.flatnonzero(transparent)
    if sort:
        clear = clear[np.argsort(-np.asarray(depth)[clear], kind="stable")]
    return np.concatenate([opaque, clear]).astype(np.int64)
