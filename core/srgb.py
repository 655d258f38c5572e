"""Linear RGB to sRGB: the one place colours are encoded for a screen or a file.

Shading adds and scales light, so every colour in the scene and in the
renderers is *linear* RGB (twice the value, twice the light).  Screens and
image files expect *sRGB*, whose values follow the eye's response instead;
writing linear values straight to 8 bits makes an image too dark with its
shadows crushed.  Every pane and every exported image converts here.

The transfer curve is the sRGB standard's (IEC 61966-2-1): linear below
0.0031308, a 1/2.4 power above it.
"""

from __future__ import annotations

import numpy as np


def linear_to_srgb(rgb: np.ndarray) -> np.ndarray:
    """Encode linear RGB in [0, 1] (clipped) as sRGB in [0, 1], float64, same shape."""
    c = np.clip(np.asarray(rgb, dtype=np.float64), 0.0, 1.0)
    encoded = np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)
    return np.where(c >= 1.0, 1.0, encoded)  # exactly white, not 1 - 1e-16


def srgb_to_linear(srgb: np.ndarray) -> np.ndarray:
    """Decode sRGB in [0, 1] (clipped) to linear RGB, float64, same shape."""
    c = np.clip(np.asarray(srgb, dtype=np.float64), 0.0, 1.0)
    return np.where(c <= 0.04045, c / 12.92, np.power((c + 0.055) / 1.055, 2.4))


#: The weights of a linear RGB colour's luminance (Rec. 709, the sRGB primaries).
LUMINANCE = np.array([0.2126, 0.7152, 0.0722])

#: Values converted at a time by :func:`to_srgb8`: a 4096 x 4096 frame in one go made several
#: 400 MB temporaries and held the program for seconds, deaf to Ctrl+C (checked between blocks).
BLOCK_VALUES = 1 << 20


def to_srgb8(rgb: np.ndarray) -> np.ndarray:
    """Linear RGB in [0, 1] to 8-bit sRGB (uint8), rounded to nearest, for display and files."""
    rgb = np.asarray(rgb)
    if rgb.ndim == 0 or rgb.size <= BLOCK_VALUES:
        return np.round(linear_to_srgb(rgb) * 255.0).astype(np.uint8)
    out = np.empty(rgb.shape, np.uint8)
    rows = max(1, BLOCK_VALUES * len(rgb) // rgb.size)  # of the first axis (image rows) per block
    for start in range(0, len(rgb), rows):
        out[start:start + rows] = np.round(linear_to_srgb(rgb[start:start + rows]) * 255.0)
    return out


def colormapped(level: np.ndarray, colormap: str) -> np.ndarray:
    """Levels in [0, 1] through a matplotlib colour map, as linear RGB (so that
    :func:`to_srgb8` shows exactly the map's colours)."""
    from matplotlib import colormaps

    return srgb_to_linear(colormaps[colormap](np.clip(level, 0.0, 1.0))[..., :3])
