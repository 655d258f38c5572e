"""Supersampling: several samples per pixel, averaged, so that edges stop being jagged.

One sample per pixel asks "what is at the pixel's centre?" and gets a yes/no
answer at every edge: the staircase.  A pixel is a small square, and its
colour should be the average over that square.  Supersampling estimates that
average from ``N x N`` samples:

- *stratified*: the square is cut into ``N x N`` cells (strata) and every cell
  gets exactly one sample, so no part of the pixel is missed;
- *jittered*: inside its cell the sample lies at a random place (a seeded
  :class:`numpy.random.Generator`), so regular patterns in the scene cannot
  line up with a regular sampling grid (moire);
- *box-filtered*: the pixel's colour is the plain mean of its samples.

``N = 1`` is the ordinary render through the pixel centres.

Image order (:func:`trace_supersampled`) sends the rays through the sample
positions.  The compiled tracer takes a grid of sample columns times sample
rows, so the jitter is drawn per sample column (for each band of
``JITTER_ROWS`` pixel rows) and per sample row: every sample is still uniform
in its own cell.  Object order (:func:`raster_supersampled`) rasterises the
whole image ``N x N`` times, each time with the projection shifted by one
jittered sub-pixel offset, and averages the images: the accumulation-buffer
method, which repeats the whole pipeline per sample position.

*Adaptive* supersampling (:func:`trace_adaptive`), Whitted's idea: trace the
corners of every pixel first; where the four corners agree, their mean is the
pixel (flat regions get one sample's worth of work, since each corner is
shared by four pixels); only pixels whose corners differ by more than a
threshold get the full ``N x N`` stratified samples.  The number of samples
per pixel is kept as a heat map.

Pixel coordinates follow :mod:`core.projection`: x to the right, y down, pixel
``(i, j)`` covering ``[i, i + 1) x [j, j + 1)``.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import dataclass, replace

import numpy as np

from core.camera import Camera
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tracing import sample_tracer
from core.object_order.pipeline import RasterResult, RasterSettings, render_raster
from core.scene import Scene

#: Pixel rows that share one draw of the sample columns' jitter.
JITTER_ROWS = 64
#: Most samples traced in one call of the compiled tracer (bounds its work arrays, about 200 bytes each).
MAX_SAMPLES_PER_CALL = 1 << 18


@dataclass(frozen=True, eq=False)
class Jitter:
    """Where the ``n x n`` samples of each pixel lie, within the pixel.

    Attributes
    ----------
    n : int >= 1, samples per pixel along each axis.
    columns : (bands, W, n) float64 in [0, 1): sample column ``a`` of pixel
        column ``i`` in band ``b`` (pixel rows ``b * band_rows ...``) is at
        ``x = i + (a + columns[b, i, a]) / n``.
    rows : (H, n) float64 in [0, 1): sample row ``c`` of pixel row ``j`` is at
        ``y = j + (c + rows[j, c]) / n``.
    band_rows : int, pixel rows per band.
    """

    n: int
    columns: np.ndarray
    rows: np.ndarray
    band_rows: int

    def xs(self, row: int, cols: np.ndarray) -> np.ndarray:
        """Sample x positions (pixels) of pixel columns ``cols`` in pixel row ``row``, (len(cols) * n,)."""
        cols = np.asarray(cols, dtype=np.int64)
        offsets = (np.arange(self.n) + self.columns[row // self.band_rows, cols]) / self.n
        return (cols[:, None] + offsets).ravel()

    def ys(self, first: int, stop: int) -> np.ndarray:
        """Sample y positions (pixels) of pixel rows ``first .. stop - 1``, ((stop - first) * n,)."""
        rows = np.arange(first, stop)
        return (rows[:, None] + (np.arange(self.n) + self.rows[first:stop]) / self.n).ravel()


def jitter(width: int, height: int, n: int, rng: np.random.Generator) -> Jitter:
    """A stratified jittered pattern of ``n x n`` samples per pixel; ``n = 1`` is the pixel centres."""
    if not (isinstance(n, int | np.integer) and n >= 1):
        raise ValueError(f"samples per axis must be a whole number >= 1, got {n!r}")
    if n == 1:
        return Jitter(1, np.full((1, width, 1), 0.5), np.full((height, 1), 0.5), height)
    bands = -(-height // JITTER_ROWS)
    return Jitter(int(n), rng.random((bands, width, n)), rng.random((height, n)), JITTER_ROWS)


def _box(samples: np.ndarray, n: int) -> np.ndarray:
    """(rows * n, cols * n, 3) samples -> (rows, cols, 3) pixel means."""
    r, c = samples.shape[0] // n, samples.shape[1] // n
    return samples.reshape(r, n, c, n, 3).mean(axis=(1, 3))


def trace_bands(scene: Scene, settings: TraceSettings, pattern: Jitter,
                trace: Callable | None = None) -> Iterator[tuple[int, int, np.ndarray]]:
    """Trace ``pattern``'s samples band by band; yield ``(first_row, stop_row, colour)`` per band.

    ``colour`` is (stop - first, W, 3) float64, the box-filtered linear RGB of
    those pixel rows.  ``trace`` is a prepared :func:`sample_tracer` (made here
    when not given).
    """
    cam = scene.camera
    width, height, n = cam.width, cam.height, pattern.n
    trace = trace or sample_tracer(scene, settings)
    rows_per_call = pattern.band_rows
    if n == 1:  # pixel centres: no jitter to share, so any rows go together
        rows_per_call = max(1, min(height, MAX_SAMPLES_PER_CALL // width))
    cols_per_call = max(1, min(width, MAX_SAMPLES_PER_CALL // (rows_per_call * n * n)))
    for first in range(0, height, rows_per_call):
        stop = min(height, first + rows_per_call)
        ys = pattern.ys(first, stop) - 0.5  # the tracer's k is the centre of pixel k
        out = np.empty((stop - first, width, 3))
        for c0 in range(0, width, cols_per_call):
            cols = np.arange(c0, min(width, c0 + cols_per_call))
            color, _, _ = trace(pattern.xs(first, cols) - 0.5, ys)
            out[:, cols] = _box(color, n)
        yield first, stop, out


def trace_supersampled(scene: Scene, settings: TraceSettings, n: int, rng: np.random.Generator,
                       trace: Callable | None = None) -> np.ndarray:
    """The image traced with ``n x n`` stratified jittered samples per pixel, box-filtered.

    Returns
    -------
    (H, W, 3) float64, linear RGB in [0, 1].
    """
    cam = scene.camera
    pattern = jitter(cam.width, cam.height, n, rng)
    image = np.empty((cam.height, cam.width, 3))
    for first, stop, band in trace_bands(scene, settings, pattern, trace):
        image[first:stop] = band
    return image


@dataclass(frozen=True, eq=False)
class AdaptiveImage:
    """An image traced with adaptive supersampling, and where the samples went.

    Attributes
    ----------
    color : (H, W, 3) float64, linear RGB in [0, 1].
    samples : (H, W) int64, the heat map: 1 where the pixel's corners agreed
        (its share of the corner grid), ``1 + n * n`` where it was refined.
    refined : (H, W) bool, pixels that got the full ``n x n`` samples.
    traced : int, rays actually traced: the ``(W + 1) (H + 1)`` corners plus
        ``n * n`` per refined pixel.
    """

    color: np.ndarray
    samples: np.ndarray
    refined: np.ndarray
    traced: int

    @property
    def samples_per_pixel(self) -> float:
        """Mean rays traced per pixel."""
        return self.traced / self.refined.size


def trace_adaptive(scene: Scene, settings: TraceSettings, threshold: float, n: int,
                   rng: np.random.Generator, trace: Callable | None = None) -> AdaptiveImage:
    """Whitted's adaptive supersampling: refine only the pixels whose corners disagree.

    Parameters
    ----------
    threshold : float >= 0, largest difference (any channel, linear RGB) the
        four corner samples of a pixel may show before it is refined.
    n : samples per axis in a refined pixel (stratified, jittered as in
        :func:`trace_supersampled`, and with the same pattern for the same ``rng``
        state, so a refined pixel gets exactly the colour uniform ``n x n``
        supersampling gives it).

    Returns
    -------
    AdaptiveImage
    """
    if not threshold >= 0:
        raise ValueError(f"threshold must be >= 0, got {threshold!r}")
    cam = scene.camera
    width, height = cam.width, cam.height
    pattern = jitter(width, height, n, rng)
    trace = trace or sample_tracer(scene, settings)
    # 1. The corners of every pixel: pixel k's left edge is the tracer's k - 0.5.
    corners, _, _ = trace(np.arange(width + 1) - 0.5, np.arange(height + 1) - 0.5)
    quad = np.stack([corners[:-1, :-1], corners[:-1, 1:], corners[1:, :-1], corners[1:, 1:]])
    color = quad.mean(axis=0)
    # 2. Pixels whose corners differ by more than the threshold get n x n samples.
    refined = (quad.max(axis=0) - quad.min(axis=0)).max(axis=-1) > threshold
    # One call of the tracer per pixel row with refined pixels.  Each call is small, and waking a
    # second thread for it costs more than it saves (on a busy machine, far more), so they run on one.
    import numba

    threads = numba.get_num_threads()
    numba.set_num_threads(1)
    try:
        for row in np.flatnonzero(refined.any(axis=1)):
            cols = np.flatnonzero(refined[row])
            samples, _, _ = trace(pattern.xs(row, cols) - 0.5, pattern.ys(row, row + 1) - 0.5)
            color[row, cols] = _box(samples, n)[0]
    finally:
        numba.set_num_threads(threads)
    heat = np.where(refined, 1 + n * n, 1).astype(np.int64)
    traced = (width + 1) * (height + 1) + n * n * int(refined.sum())
    return AdaptiveImage(color, heat, refined, traced)


@dataclass(frozen=True)
class _JitteredCamera(Camera):
    """The observer with the image shifted by a sub-pixel offset (the accumulation buffer's jitter).

    ``shift`` (pixels, x right, y down) moves the point every pixel samples
    from its centre to ``centre + shift``.
    """

    shift: tuple[float, float] = (0.0, 0.0)

    @property
    def clip_from_view(self) -> np.ndarray:
        # Moving the sample point by +s pixels is moving the image by -s: in NDC
        # x by -2 s_x / W and (y up) y by +2 s_y / H; in clip space times w.
        m = super().clip_from_view
        shear = np.eye(4)
        shear[0, 3] = -2.0 * self.shift[0] / self.width
        shear[1, 3] = 2.0 * self.shift[1] / self.height
        return shear @ m


def jittered_scene(scene: Scene, shift: tuple[float, float]) -> Scene:
    """``scene`` with every pixel sampled at ``centre + shift`` (pixels) in object order."""
    cam = scene.camera
    fields = {k: getattr(cam, k) for k in cam.__dataclass_fields__ if k != "shift"}
    return replace(scene, camera=_JitteredCamera(**fields, shift=(float(shift[0]), float(shift[1]))))


def raster_bands(scene: Scene, settings: RasterSettings, n: int,
                 rng: np.random.Generator) -> Iterator[RasterResult]:
    """Rasterise ``scene`` once per stratum of an ``n x n`` jittered pattern; yield each render.

    ``n = 1`` is the ordinary render through the pixel centres.  The mean of
    the ``n * n`` colour images is the supersampled image.
    """
    if n == 1:
        yield render_raster(scene, settings)
        return
    offsets = rng.random((n, n, 2))
    for b in range(n):
        for a in range(n):
            shift = ((a + offsets[b, a, 0]) / n - 0.5, (b + offsets[b, a, 1]) / n - 0.5)
            yield render_raster(jittered_scene(scene, shift), settings)


def raster_supersampled(scene: Scene, settings: RasterSettings, n: int,
                        rng: np.random.Generator) -> np.ndarray:
    """The image rasterised with ``n x n`` stratified jittered samples per pixel, box-filtered.

    Returns
    -------
    (H, W, 3) float64, linear RGB in [0, 1].
    """
    cam = scene.camera
    total = np.zeros((cam.height, cam.width, 3))
    for result in raster_bands(scene, settings, n, rng):
        total += result.color
    return total / (n * n)
