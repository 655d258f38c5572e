"""Heat maps: what each pixel cost, as colours over the image, with their scale and totals.

The lecture's acceleration section is about where the time goes: a ray that
tests every primitive, against one that tests a few boxes first.  The tracer
counts each pixel's tests (``render_trace(..., heat=True)``, primitive tests and
bounding-volume tests apart) and object order counts the fragments that reach
each pixel (:meth:`core.object_order.step_history.StepHistory.fragments_per_pixel`,
the overdraw).  :func:`heat_map` turns one such count per pixel into colours
from 0 (the colour map's first colour) to the largest count (its last), shaded
by the image beneath so that the scene stays readable and each colour reads on the scale.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.srgb import LUMINANCE, colormapped

COLORMAP = "inferno"
#: How much the image beneath darkens a heat map's colour, where the image is black (0: not at all).
SHADE = 0.4


@dataclass(frozen=True, eq=False)
class HeatMap:
    """One count per pixel, coloured, with what the scale needs.

    Attributes
    ----------
    counts : (H, W) int64, the count of each pixel.
    what : what is counted, e.g. ``"primitive tests"``.
    top : int, the largest count: the top of the colour scale (0 for none at all).
    total : int, the sum of all counts (equal to the render's counter).
    colored : (H, W, 3) float64, linear RGB, ``counts`` through the colour map.
    colormap : the matplotlib colour map's name.
    """

    counts: np.ndarray
    what: str
    top: int
    total: int
    colored: np.ndarray
    colormap: str = COLORMAP

    @property
    def mean(self) -> float:
        """The mean count a pixel."""
        return float(self.counts.mean()) if self.counts.size else 0.0

    def over(self, image: np.ndarray, shade: float = SHADE) -> np.ndarray:
        """The heat shaded by ``image`` (H, W, 3) linear RGB: each pixel its count's colour on the
        scale, darkened where the image is dark, by ``shade`` where it is black.

        So the scene stays readable and every pixel still reads on the scale beside the map: a
        pixel with no count is the scale's darkest colour over any image.  (Laid over the image
        at three quarters, such a pixel over a white image showed a light grey, nowhere on the
        scale.)
        """
        brightness = np.clip(np.asarray(image, dtype=float) @ LUMINANCE, 0.0, 1.0)
        return self.colored * (1.0 - shade + shade * brightness)[..., None]

    def colorbar(self, length: int = 256, thickness: int = 12) -> np.ndarray:
        """The colour scale as a (thickness, length, 3) linear-RGB strip: 0 left, ``top`` right."""
        return np.repeat(colormapped(np.linspace(0.0, 1.0, length), self.colormap)[None], thickness, axis=0)


def heat_map(counts: np.ndarray, what: str, colormap: str = COLORMAP) -> HeatMap:
    """Colour ``counts`` (H, W) from 0 to their largest value (a linear scale).

    Examples
    --------
    >>> m = heat_map(np.array([[0, 2], [4, 2]]), "primitive tests")
    >>> m.top, m.total, m.mean
    (4, 8, 2.0)
    """
    counts = np.asarray(counts, dtype=np.int64)
    top = int(counts.max()) if counts.size else 0
    level = counts / top if top > 0 else np.zeros(counts.shape)
    return HeatMap(counts, what, top, int(counts.sum()), colormapped(level, colormap), colormap)
