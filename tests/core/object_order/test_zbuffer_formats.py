"""The z-buffer's number format: two parallel planes 0.01 apart, counted pixel by pixel.

Two square planes face the observer at distance 50 (and, in the reversed-Z
case, 500), 0.01 apart; the farther one (red) is listed, so drawn, first and
is a little larger, so the nearer one (green) should hide it completely.
Where the format gives both planes the same depth key, the strict z-test
keeps the fragment drawn first and the farther plane shows through.

The expected answer comes from the lecture's perspective depth worked out in
50-digit arithmetic (mpmath): the window depth of a plane at distance ``d`` is
``z = ((f + n) / (f - n) - 2 f n / ((f - n) d) + 1) / 2``, and the formats'
keys are rounded from it exactly as their definitions say.  The rasterizer
computes the same ``z`` in float64; each key is checked to be stable under a
change of 1e-12 in ``z``, far more than float64's error, so its rounding
cannot flip.
"""

from __future__ import annotations

import mpmath
import numpy as np
import pytest

from core.camera import Camera
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Mesh, PointLight, Scene

mpmath.mp.dps = 50
GAP = 0.01


def window_depth(d, near, far):
    """The window depth of a point at distance ``d`` along the viewing axis (mpmath)."""
    d, n, f = (mpmath.mpf(v) for v in (d, near, far))
    return ((f + n) / (f - n) - 2 * f * n / ((f - n) * d) + 1) / 2


def _round24(x):
    """``x`` rounded to float32's 24 significant bits (round half to even)."""
    with mpmath.workprec(24):
        return +x


def key(z, fmt):
    """The depth key of window depth ``z`` (mpmath) by the format's definition."""
    if fmt == "int16":
        return mpmath.floor(z * 65535 + mpmath.mpf(1) / 2) / 65535
    if fmt == "float32":
        return _round24(z)
    if fmt == "float32-reversed":
        return 1 - _round24(1 - z)
    raise AssertionError(fmt)


def stable_key(z, fmt):
    """The key of ``z``, asserting that float64's rounding of ``z`` cannot change it."""
    k = key(z, fmt)
    assert key(z - mpmath.mpf("1e-12"), fmt) == k == key(z + mpmath.mpf("1e-12"), fmt)
    return k


def collide(d, near, far, fmt) -> bool:
    """Do the planes at ``d`` and ``d + GAP`` get the same key in ``fmt``?"""
    return stable_key(window_depth(d, near, far), fmt) == stable_key(window_depth(d + GAP, near, far), fmt)


def _square(d, half, color, name):
    v = [(-half, -half, -d), (half, -half, -d), (half, half, -d), (-half, half, -d)]
    return Mesh(v, [[0, 1, 2], [0, 2, 3]], Material(color=color), name)


def planes_scene(d, near, far) -> Scene:
    cam = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=40, near=near, far=far,
                 width=80, height=60)
    far_plane = _square(d + GAP, 0.24 * d, (1.0, 0.0, 0.0), "farther, red")
    near_plane = _square(d, 0.2 * d, (0.0, 1.0, 0.0), "nearer, green")
    return Scene(camera=cam, objects=(far_plane, near_plane), lights=(PointLight((0.0, 0.0, 10.0)),))


def near_plane_pixels(scene) -> np.ndarray:
    """(H, W) bool: pixel centres whose ray meets the nearer square (by hand: the camera
    looks down -z from the origin, so a ray through view direction (x, y, -1) meets the
    plane z = -d at (x d, y d))."""
    cam, square = scene.camera, scene.objects[1]
    d, half = -square.vertices[0, 2], square.vertices[1, 0]
    hw, hh = cam.half_extent(1.0)
    xs = ((np.arange(cam.width) + 0.5) / cam.width * 2 - 1) * hw
    ys = (1 - (np.arange(cam.height) + 0.5) / cam.height * 2) * hh
    px, py = np.meshgrid(xs, ys)
    return (np.abs(px * d) < half) & (np.abs(py * d) < half)


def wrong_pixels(d, near, far, fmt) -> int:
    """Pixels of the nearer square where the farther square's colour shows."""
    scene = planes_scene(d, near, far)
    result = render_raster(scene, RasterSettings(depth_format=fmt))
    red_shows = result.color[..., 0] > result.color[..., 1]
    return int(np.sum(red_shows & near_plane_pixels(scene)))


def test_the_rasterizer_uses_the_window_depth_the_test_works_out():
    scene = planes_scene(50, 0.1, 1000)
    history = render_raster(scene, RasterSettings(record_steps=True)).history
    far_z, near_z = history.polygon_fragments(0)[2][0], history.polygon_fragments(2)[2][0]
    assert abs(far_z - window_depth(50 + GAP, 0.1, 1000)) < 1e-13
    assert abs(near_z - window_depth(50, 0.1, 1000)) < 1e-13


def test_int16_fights_at_near_far_0_1_to_1000_and_not_at_10_to_100():
    # 0.1 / 1000: dz/dd = f n / ((f - n) d^2) = 4.0e-5 per unit, so the gap is 4.0e-7 in
    # window depth, 1/38 of one int16 step (1 / 65535 = 1.5e-5): both planes round to the
    # same step.  10 / 100: dz/dd = 4.4e-3, the gap is 4.4e-5, about three steps.
    assert collide(50, 0.1, 1000, "int16") and not collide(50, 10, 100, "int16")
    expected = int(near_plane_pixels(planes_scene(50, 0.1, 1000)).sum())
    assert expected > 1000
    assert wrong_pixels(50, 0.1, 1000, "int16") == expected  # the nearer square vanishes
    assert wrong_pixels(50, 10, 100, "int16") == 0
    assert wrong_pixels(50, 0.1, 1000, "float64") == 0


def test_reversed_float32_fights_no_more_than_float32_and_less_where_depth_piles_up():
    # At distance 500 with 0.1 / 1000 the gap is 4e-9 in window depth, near z = 0.9999, where
    # float32's step is 6e-8: both planes round to the same float32.  Reversed, the stored
    # value is 1 - z = 1.0e-4, where float32's step is 7e-12: the planes stay apart.
    cases = [(50, 0.1, 1000), (50, 10, 100), (500, 0.1, 1000)]
    for d, near, far in cases:
        counts = {fmt: wrong_pixels(d, near, far, fmt) for fmt in ("float32", "float32-reversed")}
        expected = int(near_plane_pixels(planes_scene(d, near, far)).sum())
        for fmt, count in counts.items():
            assert count == (expected if collide(d, near, far, fmt) else 0), (d, near, far, fmt)
        assert counts["float32-reversed"] <= counts["float32"]
    assert collide(500, 0.1, 1000, "float32") and not collide(500, 0.1, 1000, "float32-reversed")
    assert wrong_pixels(500, 0.1, 1000, "float32-reversed") < wrong_pixels(500, 0.1, 1000, "float32")


def test_pixel_history_shows_the_keys_that_tied():
    scene = planes_scene(50, 0.1, 1000)
    result = render_raster(scene, RasterSettings(depth_format="int16", record_steps=True))
    far_event, near_event = result.history.pixel_history(40, 30)
    tied = float(stable_key(window_depth(50, 0.1, 1000), "int16"))
    assert far_event.passed and far_event.z == tied and far_event.stored_z == 1.0
    assert not near_event.passed and near_event.z == near_event.stored_z == tied
    assert result.zbuffer[30, 40] == tied


@pytest.mark.parametrize(("fmt", "size"), [("float64", 8), ("float32", 4), ("float32-reversed", 4),
                                           ("int24", 3), ("int16", 2)])
def test_stats_give_the_z_buffers_bytes_in_its_format(fmt, size):
    result = render_raster(planes_scene(50, 10, 100), RasterSettings(depth_format=fmt))
    assert result.stats["zbuffer_bytes"] == size * 80 * 60
    assert result.stats["settings"]["depth_format"] == fmt


def test_an_unknown_depth_format_is_named_with_the_choices():
    with pytest.raises(ValueError, match=r"depth format must be one of \['float64', .*'int16'\], got 'int8'"):
        RasterSettings(depth_format="int8")
