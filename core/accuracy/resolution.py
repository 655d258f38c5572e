"""Image resolution: how many pixels sample the view, compared at the reference's size.

A render at another size is brought to the reference's size before it is
compared: a larger image by averaging each whole block of its pixels (the box
filter of supersampling), a smaller one by repeating its pixels (each
reference pixel takes the rendered pixel its centre falls in), which is how a
low-resolution image looks when shown at the larger size.
"""

from __future__ import annotations

import numpy as np


def scaled_size(width: int, height: int, scale: float) -> tuple[int, int]:
    """The image size ``scale`` times ``width x height``, at least 1 x 1 pixel."""
    return max(1, round(width * scale)), max(1, round(height * scale))


def to_size(image: np.ndarray, width: int, height: int) -> np.ndarray:
    """``image`` (h, w, ...) brought to (height, width, ...), as described above.

    Examples
    --------
    >>> to_size(np.arange(4.0).reshape(2, 2), 1, 1).tolist()
    [[1.5]]
    >>> to_size(np.array([[1, 2]]), 4, 1).tolist()
    [[1, 1, 2, 2]]
    """
    image = np.asarray(image)
    h, w = image.shape[:2]
    if (h, w) == (height, width):
        return image
    if h % height == 0 and w % width == 0 and h // height == w // width and image.dtype.kind == "f":
        k = h // height
        return image.reshape(height, k, width, k, *image.shape[2:]).mean(axis=(1, 3))
    rows = np.minimum(((np.arange(height) + 0.5) * h / height).astype(np.int64), h - 1)
    cols = np.minimum(((np.arange(width) + 0.5) * w / width).astype(np.int64), w - 1)
    return image[rows][:, cols]
