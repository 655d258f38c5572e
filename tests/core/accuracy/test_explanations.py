"""The Cost pane's words on each knob's curve say what the pipelines and arithmetic bear out."""

from dataclasses import replace
from fractions import Fraction

import flip_evaluator
import numpy as np

from core.accuracy.explanations import EXPLANATIONS
from core.image_order.flat_layout import ACCEL_CODES
from core.image_order.flat_scene import TraceSettings
from core.image_order.ray_tracing import render_trace
from core.presets import lecture_scene
from core.presets_trace import mirror_and_glass
from core.srgb import linear_to_srgb


def test_sixteen_bit_depth_has_about_a_quarter_of_a_step_for_a_tenth_of_a_unit_at_50_units():
    # Window depth, 0 on the near plane and 1 on the far one: d(z) = f (z - n) / (z (f - n)).  With
    # f = 100 and n = 1/10, from z = 50 to z = 50.1 it grows by 100 (1/10) (1/10) / (50 · 50.1 · 99.9)
    # = 1 / 250,249.5 ≈ 4.0e-6, and 16 bits have 65,535 steps over [0, 1]: 0.262 of one step.
    text = EXPLANATIONS["depth-format"]
    assert "far plane 100 units away and the near plane at 0.1 (1:1000)" in text
    assert "a tenth of a unit in depth 50 units away is only about a quarter of one" in text
    f, n = Fraction(100), Fraction(1, 10)

    def depth(z):
        return f * (z - n) / (z * (f - n))

    steps = (depth(Fraction(501, 10)) - depth(Fraction(50))) * (2**16 - 1)
    assert f / n == 1000 and Fraction(1, 5) < steps < Fraction(3, 10)


def _mean_flip(reference: np.ndarray, test: np.ndarray) -> float:
    srgb = [linear_to_srgb(image).astype(np.float32) for image in (reference, test)]
    return float(np.mean(flip_evaluator.evaluate(*srgb, "LDR")[0]))


def test_with_one_mirror_and_one_glass_ball_rays_beyond_depth_3_add_almost_nothing_visible():
    # Mean FLIP against depth 10 (rays followed ten generations deep), at 160 x 120: each depth
    # takes some error away, but going from 3 to 5 takes less than a fifth of what going from 1 to 3
    # took.
    scene = mirror_and_glass()
    assert [o.material.reflectivity > 0 for o in scene.objects].count(True) == 1
    assert [o.material.transparency > 0 for o in scene.objects].count(True) == 1
    scene = replace(scene, camera=scene.camera.replace(width=160, height=120))
    images = {d: render_trace(scene, TraceSettings(max_depth=d, min_weight=0.0)).color
              for d in (1, 2, 3, 5, 10)}
    error = {d: _mean_flip(images[10], images[d]) for d in (1, 2, 3, 5)}
    assert error[1] > error[2] > error[3] > error[5]
    assert error[3] - error[5] < (error[1] - error[3]) / 5, error
    assert "with one mirror and one glass ball, rays beyond depth 3 add almost nothing visible" in \
        EXPLANATIONS["depth"]


def test_every_acceleration_method_finds_exactly_the_same_image():
    scene = replace(lecture_scene(), camera=lecture_scene().camera.replace(width=160, height=120))
    images = [render_trace(scene, TraceSettings(accel=accel)).color for accel in ACCEL_CODES]
    assert all(np.array_equal(images[0], image) for image in images[1:])
    assert "every method finds exactly the same hits, so the error is exactly 0" in EXPLANATIONS["accel"]
