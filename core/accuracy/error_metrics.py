"""How far a render is from the reference, in units a user understands.

- :func:`rmse`: root mean square difference of linear RGB, over all pixels
  and channels: the physical error in light, 0 to 1.
- :func:`flip`: NVIDIA's FLIP, a perceptual difference (``flip-evaluator``):
  how visible the difference is to a viewer flipping between the two images
  on a screen, 0 (identical) to 1, with a per-pixel error map.  FLIP judges
  what a screen shows, so both images are encoded to sRGB first, in
  :mod:`core.srgb`.  ``flip-evaluator`` holds Python's lock for the whole of
  its work (277 ms at 640×480), so it runs in a helper process
  (:mod:`core.helper_process`): the window's thread goes on meanwhile.
- :func:`wrong_pixel_fraction`: the share of pixels whose visible object (at
  the pixel centre) is another one than the reference's: silhouettes that
  moved, or surfaces the z-buffer put in the wrong order (z-fighting).
- :func:`depth_error`: mean distance along the viewing axis (scene units)
  between the surfaces the two renders see, where both see the same object:
  for example how far a tessellated sphere lies inside the true one.
"""

from __future__ import annotations

import numpy as np

from core import helper_process
from core.srgb import linear_to_srgb

#: FLIP's default viewing condition: 67 pixels per degree of visual angle (a
#: 0.7 m wide 4K monitor seen from 0.7 m).
PIXELS_PER_DEGREE = 67.0


def rmse(reference: np.ndarray, test: np.ndarray) -> float:
    """Root mean square difference of two (H, W, 3) linear RGB images.

    Examples
    --------
    >>> rmse(np.zeros((1, 2, 3)), np.full((1, 2, 3), 0.5))
    0.5
    """
    _same_shape(reference, test)
    return float(np.sqrt(np.mean((np.asarray(test, float) - np.asarray(reference, float)) ** 2)))


def flip(reference: np.ndarray, test: np.ndarray,
         pixels_per_degree: float = PIXELS_PER_DEGREE) -> tuple[float, np.ndarray]:
    """The mean FLIP error of ``test`` against ``reference``, and its per-pixel map.

    Parameters
    ----------
    reference, test : (H, W, 3) float64, linear RGB in [0, 1].
    pixels_per_degree : how many pixels one degree of the viewer's field of
        view spans (a projector seen from the back of a room has fewer).

    Returns
    -------
    (mean, error_map) : float in [0, 1], and (H, W) float32 in [0, 1].
    """
    _same_shape(reference, test)
    ref = linear_to_srgb(reference).astype(np.float32)
    tst = linear_to_srgb(test).astype(np.float32)
    return helper_process.call(__name__, "flip_here", ref, tst, float(pixels_per_degree))


def flip_here(ref: np.ndarray, tst: np.ndarray, pixels_per_degree: float) -> tuple[float, np.ndarray]:
    """:func:`flip` of two (H, W, 3) float32 sRGB images, computed by the process that calls it."""
    import flip_evaluator

    error_map, mean, _ = flip_evaluator.evaluate(ref, tst, "LDR", inputsRGB=True, applyMagma=False,
                                                 parameters={"ppd": pixels_per_degree})
    return float(mean), np.asarray(error_map).reshape(ref.shape[:2])


def wrong_pixel_fraction(reference_objects: np.ndarray, test_objects: np.ndarray) -> float:
    """Share of pixels whose visible object differs from the reference's.

    Parameters
    ----------
    reference_objects, test_objects : (H, W) int, object index per pixel, -1 for background.

    Examples
    --------
    >>> wrong_pixel_fraction(np.array([[0, 1], [1, -1]]), np.array([[0, 1], [0, -1]]))
    0.25
    """
    _same_shape(reference_objects, test_objects)
    return float(np.mean(np.asarray(reference_objects) != np.asarray(test_objects)))


def depth_error(reference_depth: np.ndarray, test_depth: np.ndarray, reference_objects: np.ndarray,
                test_objects: np.ndarray) -> float:
    """Mean |depth difference| (scene units) over pixels where both renders see the same object.

    Depths are distances along the viewing axis, ``inf`` for background; a
    pixel counts only when both see the same object (not the background).
    0.0 when there is no such pixel.
    """
    _same_shape(reference_depth, test_depth)
    same = (np.asarray(reference_objects) == np.asarray(test_objects)) & (np.asarray(reference_objects) >= 0)
    same &= np.isfinite(reference_depth) & np.isfinite(test_depth)
    if not same.any():
        return 0.0
    return float(np.mean(np.abs(np.asarray(test_depth)[same] - np.asarray(reference_depth)[same])))


def _same_shape(a, b) -> None:
    if np.shape(a) != np.shape(b):
        raise ValueError(f"images must have the same shape, got {np.shape(a)} and {np.shape(b)}")
