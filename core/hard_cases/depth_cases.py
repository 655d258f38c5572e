"""Z-fighting: two nearly coplanar floors, and how many pixels each depth format gets wrong.

A floor (drawn first, red) and a second floor ``GAP`` above it (drawn second,
blue) are seen from an eye ``EYE_HEIGHT`` above them, out to the far plane.
The upper one is nearer along every ray from the eye, so in exact arithmetic
blue wins every pixel both cover.  The z-buffer, though, stores window depth
in a number format (:mod:`core.object_order.depth_formats`), and far away the
two floors' window depths differ by less than one step of the format: the
strict test ``z < stored`` then keeps the red floor (*z-fighting*).

Window depth is computed per pixel the way the rasterizer does it: the
corners go through ``clip_from_world`` and the perspective divide, and the
plane of window depth through a triangle's three corners is evaluated at
each pixel centre it covers (:func:`core.object_order.rasterization.depth_plane`);
:func:`core.object_order.depth_formats.depth_key` then rounds it as each
format stores it.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.hard_cases.result import CaseImage, CaseResult, Parameter, Row
from core.in_words import listed
from core.object_order import rasterization
from core.object_order.depth_formats import DEPTH_FORMATS, depth_keys
from core.object_order.zbuffer import depth_test

#: Far plane distance, gap between the floors and the eye's height above them (scene units).
FAR, GAP, EYE_HEIGHT = 100.0, 0.01, 2.0
WIDTH, HEIGHT = 160, 100
RED, BLUE, BACKGROUND = (0.85, 0.15, 0.1), (0.15, 0.35, 0.9), (0.04, 0.05, 0.08)

#: The floor's extent: x in [-HALF_WIDTH, HALF_WIDTH], world z from -NEAR_EDGE to -FAR_EDGE.
HALF_WIDTH, NEAR_EDGE, FAR_EDGE = 60.0, 3.0, 92.0


def _floor(y: float, x0=-HALF_WIDTH, x1=HALF_WIDTH, z0=-NEAR_EDGE, z1=-FAR_EDGE) -> np.ndarray:
    """Two triangles (2, 3, 3) of the floor rectangle ``[x0, x1] x [z1, z0]`` at height ``y``."""
    a, b, c, d = (x0, y, z0), (x1, y, z0), (x1, y, z1), (x0, y, z1)
    return np.array([(a, b, c), (a, c, d)], dtype=float)


def window_depth(triangles: np.ndarray, camera: Camera) -> np.ndarray:
    """Window depth of the surface per pixel, as the rasterizer interpolates it.

    Parameters
    ----------
    triangles : (T, 3, 3) float64, world space, all in front of the near plane.
    camera : the observer (its matrices and image size).

    Returns
    -------
    (H, W) float64, window depth in [0, 1]; NaN where no triangle covers the pixel.
    """
    corners = triangles.reshape(-1, 3)
    clip = np.column_stack([corners, np.ones(len(corners))]) @ camera.clip_from_world.T
    xy, z = rasterization.window_coordinates(clip, camera.width, camera.height)
    xy, z = xy.reshape(-1, 3, 2), z.reshape(-1, 3)
    px, py = np.meshgrid(np.arange(camera.width) + 0.5, np.arange(camera.height) + 0.5)
    depth = np.full((camera.height, camera.width), np.nan)
    for k in range(len(triangles)):
        covered = rasterization.coverage(rasterization.snap(xy[k]), camera.width, camera.height)
        a, b, c = (tuple(corner) for corner in xy[k])
        plane = rasterization.depth_plane(a, b, c, *z[k])
        depth[covered] = rasterization.plane_depth(plane, a, px, py)[covered]
    return depth


def _camera(ratio: float) -> Camera:
    return Camera(eye=(0.0, EYE_HEIGHT, 0.0), target=(0.0, 0.0, -30.0), fov_y_deg=50.0,
                  near=FAR / ratio, far=FAR, width=WIDTH, height=HEIGHT)


def _second_hidden(first: np.ndarray, second: np.ndarray, fmt: str) -> np.ndarray:
    """Pixels both cover where the polygon drawn second fails the z-test (strictly nearer passes,
    :func:`core.object_order.zbuffer.depth_test`)."""
    both = ~np.isnan(first) & ~np.isnan(second)
    k1 = depth_keys(np.where(both, first, 1.0), fmt)
    k2 = depth_keys(np.where(both, second, 1.0), fmt)
    return both & ~depth_test(k2, k1)


def _picture(far_depth, near_depth, fmt) -> np.ndarray:
    image = np.empty((HEIGHT, WIDTH, 3))
    image[:] = BACKGROUND
    image[~np.isnan(far_depth)] = RED
    shown = ~np.isnan(near_depth) & ~_second_hidden(far_depth, near_depth, fmt)
    image[shown] = BLUE
    return image


NAIVE_FORMAT, ROBUST_FORMAT = "float32", "float32-reversed"


def _fought(ratio: float, wrong: dict[str, int]) -> str:
    """What the formats did at ``ratio``, from the pixels each got wrong."""
    lost = [fmt for fmt in DEPTH_FORMATS if wrong[fmt]]
    kept = [fmt for fmt in DEPTH_FORMATS if not wrong[fmt]]
    if not lost:
        return (f"At far/near {ratio:,.0f} every format still tells the floors apart; slide the ratio up to "
                "see them fight.")
    one = len(lost) == 1
    return (f"At far/near {ratio:,.0f}, {listed(lost)} {'stores' if one else 'store'} both floors as the "
            f"same number at some pixels, and there the red one, drawn first, stays; {listed(kept)} still "
            f"{'tell' if len(kept) > 1 else 'tells'} them apart.")


def _ordinal(n: int) -> str:
    """``n`` as an ordinal in digits.

    >>> [_ordinal(n) for n in (1, 2, 3, 4, 11, 12, 21)]
    ['1st', '2nd', '3rd', '4th', '11th', '12th', '21st']
    """
    return f"{n}{'th' if 10 <= n % 100 <= 20 else {1: 'st', 2: 'nd', 3: 'rd'}.get(n % 10, 'th')}"


def z_fighting(ratio: float = 1e6) -> CaseResult:
    """Two floors ``GAP`` apart seen with ``far / near = ratio``; wrongly hidden pixels per depth format.

    Parameters
    ----------
    ratio : float >= 100, far / near (the far plane stays at ``FAR``, the near plane
        stays in front of the floors' near edge).
    """
    camera = _camera(ratio)
    lower = window_depth(_floor(0.0), camera)
    upper = window_depth(_floor(GAP), camera)
    same_plane = window_depth(_floor(0.0, -13.7, 17.3, -4.1, -87.3), camera)
    wrong = {fmt: int(_second_hidden(lower, upper, fmt).sum()) for fmt in DEPTH_FORMATS}
    speckle = {fmt: int((~_second_hidden(lower, same_plane, fmt) & ~np.isnan(lower)).sum())
               for fmt in (NAIVE_FORMAT, ROBUST_FORMAT, "float64")}
    covered = ~np.isnan(lower) & ~np.isnan(upper)
    both = int(covered.sum())
    smallest = float(np.min((lower - upper)[covered]))  # the floors' window depths, nearest together
    digit = int(np.ceil(-np.log10(smallest)))
    rows = [
        Row(f"blue floor wrongly hidden (pixels of {both})", wrong[NAIVE_FORMAT], wrong[ROBUST_FORMAT], 0),
        *[Row(f"  in {fmt}", wrong[fmt], None, 0) for fmt in DEPTH_FORMATS],
        Row("a smaller floor exactly in the red floor's plane, drawn second: pixels where it wins "
            f"the tie (in float64: {speckle['float64']}; a tie has no right answer)",
            speckle[NAIVE_FORMAT], speckle[ROBUST_FORMAT], None),
    ]
    return CaseResult(
        name="z_fighting", title="6. Z-fighting: nearly coplanar floors, far/near ratio growing",
        parameter=Parameter("ratio", "far / near of the frustum (far = 100)", ratio, 100.0, 1e7),
        naive_method="z-buffer in float32", robust_method="z-buffer in float32, reversed (1 - z)",
        reference_method="the upper floor is nearer along every ray (exact)",
        rows=tuple(rows), naive_error=float(wrong[NAIVE_FORMAT]), robust_error=float(wrong[ROBUST_FORMAT]),
        error_unit="pixels wrongly hidden", tolerance=0.0,
        tolerance_reason=(f"the gap {GAP:g} at distance {FAR_EDGE:g} changes 1 - z by a fraction "
                          f"{GAP / EYE_HEIGHT:g}, far above float32's relative step 6e-8"),
        explanation=(
            "Window depth is 1 - near/distance up to a constant, so far away it crowds against 1 and "
            f"the gap between the floors shrinks with the near plane: here to as little as {smallest:.0e}, "
            f"a difference in the {_ordinal(digit)} digit. {_fought(ratio, wrong)} Reversed depth "
            "stores 1 - z, a small number that float32 keeps with 7 significant digits, so the relative "
            "gap survives at any near plane. Exactly coplanar polygons are a tie no format can break: use "
            "drawing order or a depth offset."
        ),
        images=(CaseImage(f"red floor drawn first, blue floor {GAP:g} above it drawn second",
                          _picture(lower, upper, NAIVE_FORMAT), _picture(lower, upper, ROBUST_FORMAT)),),
    )
