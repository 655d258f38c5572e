"""Step history: rebuilt steps equal fresh renders, memory follows the fragments, pixel history."""

from __future__ import annotations

import numpy as np
import pytest

from core import presets, shapes
from core.camera import Camera
from core.object_order import zbuffer
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Mesh, PointLight, Scene

RECORD = RasterSettings(record_steps=True)
VARIANTS = {"float64": {}, "int16": {"depth_format": "int16"}, "float32-reversed":
            {"depth_format": "float32-reversed"}, "no z-test": {"z_test": False}}


def _small_lecture_scene() -> Scene:
    scene = presets.lecture_scene()
    return Scene(camera=scene.camera.replace(width=160, height=120), objects=scene.objects,
                 lights=scene.lights, background=scene.background)


def _first_polygons(scene: Scene, result, k: int) -> Scene:
    """The scene cut down to the faces of the first ``k`` drawn polygons (and any culled
    faces before them, which are culled again).  Opaque polygons are drawn in scene order."""
    objects = []
    for index, obj in enumerate(scene.objects):
        drawn = result.draw.triangle_index[:k][result.draw.object_index[:k] == index]
        if len(drawn):
            objects.append(Mesh(obj.vertices, obj.triangles[:drawn.max() + 1], obj.material, obj.name))
    return Scene(camera=scene.camera, objects=tuple(objects), lights=scene.lights,
                 background=scene.background)


@pytest.mark.parametrize("variant", VARIANTS)
def test_step_zero_is_the_cleared_buffers_and_the_last_step_the_image(variant):
    scene = _small_lecture_scene()
    result = render_raster(scene, RasterSettings(record_steps=True, **VARIANTS[variant]))
    color, zbuf = result.history.buffers(0)
    assert np.all(color == scene.background) and np.all(zbuf == zbuffer.FAR_DEPTH)
    color, zbuf = result.history.buffers(result.history.n_steps)
    assert np.array_equal(color, result.color) and np.array_equal(zbuf, result.zbuffer)
    with pytest.raises(ValueError, match="step must be in"):
        result.history.buffers(result.history.n_steps + 1)


@pytest.mark.parametrize("variant", VARIANTS)
def test_rebuilt_step_equals_a_fresh_render_of_only_the_first_polygons(variant):
    scene = _small_lecture_scene()
    result = render_raster(scene, RasterSettings(record_steps=True, **VARIANTS[variant]))
    n = result.history.n_steps
    for k in sorted({1, 5, n // 3, n // 2, n - 3, n - 1}):
        color, zbuf = result.history.buffers(k)
        fresh = render_raster(_first_polygons(scene, result, k), RasterSettings(**VARIANTS[variant]))
        assert len(fresh.draw) == k
        assert np.array_equal(color, fresh.color)
        assert np.array_equal(zbuf, fresh.zbuffer)


def test_polygon_fragments_are_the_ones_its_step_adds():
    scene = presets.zbuffer_three_polygons()
    history = render_raster(scene, RECORD).history
    for p in range(history.n_steps):
        before, _ = history.buffers(p)
        after, _ = history.buffers(p + 1)
        cols, rows, z, passed = history.polygon_fragments(p)
        changed = np.any(before != after, axis=-1)
        assert np.array_equal(np.flatnonzero(changed), np.sort(rows[passed] * history.width + cols[passed]))
        assert len(z) == len(passed)


def test_memory_is_proportional_to_the_fragments():
    sphere = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=71, segments=72)  # 10,080 triangles
    assert len(sphere.triangles) >= 10_000
    cam = Camera(eye=(0.0, 0.3, 2.6), target=(0.0, 0.0, 0.0), near=0.5, far=10.0, width=640, height=480)
    scene = Scene(camera=cam, objects=(sphere,), lights=(PointLight((3.0, 4.0, 5.0)),))
    result = render_raster(scene, RasterSettings(back_face_culling=False, record_steps=True))
    history = result.history
    fragments = result.stats["fragments_generated"]
    assert fragments == len(history.fragments) > 640 * 480 * 0.5
    assert history.nbytes <= 13 * fragments + 64 * history.n_steps
    assert history.nbytes < 40e6  # tens of MB, not the ~100 GB of one buffer copy per step
    assert result.stats["recorded_bytes"] == history.nbytes
    color, _ = history.buffers(history.n_steps // 2)  # any step is rebuilt from the record
    assert color.shape == (480, 640, 3)


def test_pixel_history_lists_every_fragment_in_order_with_its_depth_test():
    scene = presets.zbuffer_three_polygons()
    result = render_raster(scene, RECORD)
    history = result.history
    cols, rows, _, passed = history.polygon_fragments(2)  # yellow
    x, y = int(cols[~passed][0]), int(rows[~passed][0])  # a pixel where yellow lost to blue
    events = history.pixel_history(x, y)
    assert [e.polygon for e in events] == sorted(e.polygon for e in events)
    assert [e.object_index for e in events][-2:] == [1, 2]
    stored = zbuffer.FAR_DEPTH
    color = np.asarray(scene.background)
    for e in events:
        assert e.stored_z == stored
        assert e.passed == (e.z < stored)  # the lecture's test: nearer than what is stored
        assert np.array_equal(e.color_before, color)
        if e.passed:
            stored, color = e.z, e.color_after
        else:
            assert np.array_equal(e.color_after, e.color_before)
        assert e.blend is None  # all opaque
        assert e.distance == pytest.approx(zbuffer.distance_from_window_depth(e.z, 1.0, 12.0, False))
        assert e.stored_distance == pytest.approx(
            zbuffer.distance_from_window_depth(e.stored_z, 1.0, 12.0, False))
    assert not events[-1].passed
    assert events[0].stored_distance == pytest.approx(scene.camera.far)  # cleared to the far plane
    assert np.array_equal(color, result.color[y, x])
    assert history.pixel_history(0, 0) == ()
    with pytest.raises(ValueError, match="outside"):
        history.pixel_history(history.width, 0)


def test_pixel_history_of_a_transparent_pixel_gives_the_blend_terms():
    opaque = Material(color=(0.2, 0.4, 0.6), ambient=0.2, diffuse=0.8)
    glass = Material(color=(1.0, 0.5, 0.0), opacity=0.3, ambient=0.2, diffuse=0.8)
    square = [[0, 1, 2], [0, 2, 3]]
    wall = Mesh([(-2, -2, -1), (2, -2, -1), (2, 2, -1), (-2, 2, -1)], square, opaque, "wall")
    pane = Mesh([(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)], square, glass, "pane")
    cam = Camera(eye=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), width=40, height=30)
    result = render_raster(Scene(camera=cam, objects=(pane, wall)), RECORD)
    events = result.history.pixel_history(20, 15)
    assert [e.object_index for e in events] == [1, 0]  # opaque wall first, though listed second
    wall_event, pane_event = events
    assert wall_event.blend is None and np.allclose(wall_event.color_after, opaque.color)
    blend = pane_event.blend
    assert blend.alpha == 0.3
    assert np.allclose(blend.source, glass.color) and np.allclose(blend.destination, opaque.color)
    by_hand = [0.3 * 1.0 + 0.7 * 0.2, 0.3 * 0.5 + 0.7 * 0.4, 0.3 * 0.0 + 0.7 * 0.6]
    assert np.allclose(blend.result, by_hand)
    assert np.allclose(result.color[15, 20], by_hand)


@pytest.mark.parametrize("fmt", ["int16", "int24", "float32", "float32-reversed"])
def test_pixel_history_replays_the_z_test_on_the_formats_keys(fmt):
    """Every event's result is the strict test of its key against the stored key, and the
    stored key after a pass is the incoming one, so the story adds up to the image."""
    scene = _small_lecture_scene()
    result = render_raster(scene, RasterSettings(depth_format=fmt, record_steps=True))
    history = result.history
    crowded = np.bincount(history.fragments.pixel).argmax()  # the pixel most fragments reached
    y, x = divmod(int(crowded), history.width)
    events = history.pixel_history(x, y)
    assert len(events) >= 2
    stored = zbuffer.FAR_DEPTH
    for e in events:
        assert e.stored_z == stored and e.passed == (e.z < stored)
        if e.passed:
            stored = e.z
    assert stored == result.zbuffer[y, x]
    assert np.array_equal(events[-1].color_after, result.color[y, x])
