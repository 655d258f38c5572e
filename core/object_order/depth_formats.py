"""The z-buffer's number format: how many distinct depths it can tell apart.

The lecture's z-buffer stores "the z coordinate of the closest object" per
pixel.  A real depth buffer stores it in a fixed number format, and that
decides which two nearby surfaces it can still order: two polygons closer
together than one step of the format get the same stored depth, and the
z-test then picks between them by drawing order, pixel by pixel
(*z-fighting*).

We store *window depth* ``z`` in [0, 1] (0 on the near plane, 1 on the far
plane, see :mod:`core.projection`).  Under perspective it is a hyperbolic
function of distance, so most of its range is spent close to the near plane
and far surfaces share few values: a larger far/near ratio makes it worse.

Formats (the names the settings and the command line use):

``float64``
    our reference: about 16 significant digits.
``float32``
    24 significant bits.  Floats are densest near 0, but window depth piles
    up near 1, so this helps little.
``float32-reversed``
    store ``1 - z`` (near = 1, far = 0, the comparison reversed), so the
    dense end of the float meets the crowded end of the depth: far surfaces
    keep their order (reversed-Z).
``int24``, ``int16``
    fixed point: ``round(z * (2**bits - 1))``, equal steps over [0, 1].

:func:`depth_key` returns, for a window depth, a float64 key that orders and
ties exactly as the format's stored values would; the z-test compares keys.
"""

from __future__ import annotations

import numpy as np

from core.compiling.jitable import jitable

#: The formats, in the order of their codes (the kernels take the index).
DEPTH_FORMATS = ("float64", "float32", "float32-reversed", "int24", "int16")
#: The kernels' codes of the formats, by name (``DEPTH_FORMATS[FLOAT32] == "float32"``).
FLOAT64, FLOAT32, FLOAT32_REVERSED, INT24, INT16 = range(len(DEPTH_FORMATS))
#: Bytes one pixel of the z-buffer takes in each format.
BYTES_PER_PIXEL = {"float64": 8, "float32": 4, "float32-reversed": 4, "int24": 3, "int16": 2}


def format_code(name: str) -> int:
    """The kernels' code of the format ``name``; ValueError naming the choices otherwise."""
    if name not in DEPTH_FORMATS:
        raise ValueError(f"depth format must be one of {list(DEPTH_FORMATS)}, got {name!r}")
    return DEPTH_FORMATS.index(name)


@jitable
def depth_key(z: float, code: int) -> float:
    """Window depth ``z`` in [0, 1] as format ``code`` stores it, as a comparable float64.

    Smaller keys are nearer; two depths the format cannot tell apart get the
    same key.  For ``float32-reversed`` the key is ``1 - stored`` so that it
    still grows with distance.  ``code`` comes from :func:`format_code`.
    """
    if code == FLOAT64:
        return z
    if code == FLOAT32:
        return float(np.float32(z))
    if code == FLOAT32_REVERSED:
        return 1.0 - float(np.float32(1.0 - z))
    steps = float((1 << (24 if code == INT24 else 16)) - 1)  # INT24 or INT16: fixed point
    return np.floor(min(max(z, 0.0), 1.0) * steps + 0.5) / steps


def depth_keys(z: np.ndarray, name: str) -> np.ndarray:
    """:func:`depth_key` over an array of window depths (for tests and the views)."""
    code = format_code(name)
    flat = np.asarray(z, dtype=np.float64).ravel()
    return np.array([depth_key(v, code) for v in flat]).reshape(np.shape(z))
