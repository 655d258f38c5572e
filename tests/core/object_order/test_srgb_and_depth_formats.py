"""The sRGB curve against the standard's own numbers; depth formats against their definitions."""

import numpy as np

from core.object_order.depth_formats import DEPTH_FORMATS, depth_keys
from core.srgb import linear_to_srgb, srgb_to_linear, to_srgb8


def test_srgb_matches_the_standard_at_its_landmarks():
    # IEC 61966-2-1: 18 % grey encodes to about 0.4614 (118 of 255), the knee is continuous
    assert abs(linear_to_srgb(0.18) - 0.46135) < 1e-4
    assert to_srgb8(np.array([0.0, 0.18, 1.0])).tolist() == [0, 118, 255]
    knee = 0.0031308
    assert abs(12.92 * knee - (1.055 * knee ** (1 / 2.4) - 0.055)) < 1e-6


def test_srgb_round_trips_and_clips():
    x = np.linspace(0, 1, 1001)
    assert np.allclose(srgb_to_linear(linear_to_srgb(x)), x, atol=1e-12)
    assert linear_to_srgb(np.array([-1.0, 2.0])).tolist() == [0.0, 1.0]


def test_each_depth_format_has_the_resolution_of_its_definition():
    z = np.array([0.5, 0.5 + 1e-6, 0.5 + 1e-4])
    keys = {name: depth_keys(z, name) for name in DEPTH_FORMATS}
    assert len(set(keys["float64"])) == 3
    assert keys["int16"][0] == keys["int16"][1] == 32768 / 65535  # one step is 1.5e-5
    assert keys["int16"][2] != keys["int16"][0]
    assert keys["int24"][0] != keys["int24"][2] and keys["int24"][0] != keys["int24"][1]
    # near the far plane float32 cannot tell 1 - 1e-9 from 1; reversed float32 can
    far = np.array([1 - 2e-9, 1 - 1e-9])
    assert len(set(depth_keys(far, "float32"))) == 1
    assert len(set(depth_keys(far, "float32-reversed"))) == 2
    for name in DEPTH_FORMATS:  # every format keeps the order (never swaps two depths)
        k = depth_keys(np.linspace(0, 1, 5001), name)
        assert np.all(np.diff(k) >= 0), name
