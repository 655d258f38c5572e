"""The picture of a step, made in the worker, shows the buffers as they stand after that step."""

from dataclasses import replace

import numpy as np

from core import presets
from core.object_order.pipeline import RasterSettings, render_raster
from core.srgb import to_srgb8
from views.images.step_picture import step_picture


def _render():
    scene = presets.lecture_scene()
    scene = replace(scene, camera=scene.camera.replace(width=64, height=48))
    return scene, render_raster(scene, RasterSettings(record_steps=True))


def test_the_last_step_is_the_rendered_image_and_its_depth():
    scene, result = _render()
    last = step_picture(result, scene, result.history.n_steps)
    assert np.allclose(last.image.rgb, result.color)
    assert np.array_equal(np.isinf(last.depth), np.isinf(result.depth))
    seen = np.isfinite(result.depth)
    assert np.allclose(last.depth[seen], result.depth[seen])
    painted = last.image.qimage.convertToFormat(last.image.qimage.Format.Format_RGB888)
    pixels = np.frombuffer(painted.constBits(), np.uint8).reshape(48, painted.bytesPerLine())[:, :64 * 3]
    assert np.array_equal(pixels.reshape(48, 64, 3), to_srgb8(result.color))
    assert f"Step {result.history.n_steps} of {result.history.n_steps}" in last.caption


def test_step_0_is_the_cleared_memory_and_z_buffer():
    scene, result = _render()
    first = step_picture(result, scene, 0)
    assert np.allclose(first.image.rgb, np.broadcast_to(scene.background, first.image.rgb.shape))
    assert np.isinf(first.depth).all()
    assert np.allclose(first.depth_image.rgb, 1.0)  # the far plane is white
    assert first.mask is None and first.polygon is None


def test_a_step_outlines_the_fragments_of_the_polygon_drawn_then():
    scene, result = _render()
    before, after = (step_picture(result, scene, k) for k in (4, 5))
    changed = np.any(before.image.rgb != after.image.rgb, axis=2)
    assert after.mask is not None and after.mask.any()
    assert not (changed & ~after.mask).any()  # only the polygon's own pixels can change
    assert len(after.polygon) >= 3


def test_a_steps_caption_writes_its_counts_of_fragments_alike_with_thousands_separated():
    """A large polygon: fragments, passed and failed all read as "2,617", not "2617" beside "2,617"."""
    scene = presets.lecture_scene()
    scene = replace(scene, camera=scene.camera.replace(width=320, height=240))
    result = render_raster(scene, RasterSettings(record_steps=True))
    history = result.history
    big = max(range(history.n_steps), key=lambda p: int(history.polygon_fragments(p)[3].sum()))
    _, _, _, passed = history.polygon_fragments(big)
    assert passed.sum() >= 1000  # the case the test is about
    caption = step_picture(result, scene, big + 1).caption
    n_passed, n_failed = int(passed.sum()), int((~passed).sum())
    assert f"{passed.size:,} fragments, {n_passed:,} passed the z-test, {n_failed:,} failed" in caption
    assert f" {int(passed.sum())} passed" not in caption
