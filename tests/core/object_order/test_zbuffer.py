"""The z-buffer: cleared buffers, the depth test, and each step against a brute-force reference."""

from __future__ import annotations

import brute_force
import numpy as np
import pytest

from core import presets
from core.camera import Camera
from core.object_order import zbuffer
from core.object_order.depth_formats import DEPTH_FORMATS
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Mesh, Scene


def _rays(cam, jitter=0.0):
    """Unit rays through every pixel centre shifted by ``jitter`` pixels, (H*W, 3) each."""
    hw, hh = cam.half_extent(1.0)
    xs = ((np.arange(cam.width) + 0.5 + jitter) / cam.width * 2 - 1) * hw
    ys = (1 - (np.arange(cam.height) + 0.5 + jitter) / cam.height * 2) * hh
    px, py = np.meshgrid(xs, ys)
    d = np.stack([px, py, -np.ones_like(px)], -1).reshape(-1, 3) @ cam.world_from_view[:3, :3].T
    d /= np.linalg.norm(d, axis=1, keepdims=True)
    return np.broadcast_to(np.asarray(cam.eye, dtype=float), d.shape), d


def painter_reference(scene, k, jitter=0.0):
    """The nearest of the first ``k`` single-triangle objects at each pixel, by ray casting.

    Returns the (H, W) index of the winning object (-1: background) and its
    distance along the viewing axis.
    """
    cam = scene.camera
    o, d = _rays(cam, jitter)
    best = np.full(len(o), np.inf)
    winner = np.full(len(o), -1)
    for index, obj in enumerate(scene.objects[:k]):
        t = brute_force.hit_triangle(o, d, *obj.corners[0])
        closer = t < best
        best[closer], winner[closer] = t[closer], index
    depth = best * (d @ cam.forward)
    return winner.reshape(cam.height, cam.width), depth.reshape(cam.height, cam.width)


@pytest.mark.parametrize("fmt", DEPTH_FORMATS)
def test_cleared_buffers_hold_background_and_far_plane(fmt):
    color, zbuf = zbuffer.cleared_buffers(4, 3, (0.1, 0.2, 0.3), fmt)
    assert color.shape == (3, 4, 3) and np.all(color == [0.1, 0.2, 0.3])
    assert zbuf.shape == (3, 4) and np.all(zbuf == zbuffer.FAR_DEPTH)  # 1.0 is exact in every format


@pytest.mark.parametrize("projection", ["perspective", "orthographic"])
def test_window_depth_converts_back_to_the_distance_along_the_axis(projection):
    cam = Camera(near=0.7, far=25.0, projection=projection)
    distance = np.linspace(cam.near, cam.far, 50)
    clip = (cam.clip_from_view @ np.stack([0 * distance, 0 * distance, -distance, 1 + 0 * distance]))
    z_win = (clip[2] / clip[3] + 1) / 2
    back = zbuffer.distance_from_window_depth(z_win, cam.near, cam.far, projection == "orthographic")
    assert np.allclose(back, distance, rtol=1e-12)


def test_each_step_of_the_three_polygon_figure_matches_a_painter_by_ray_casting():
    scene = presets.zbuffer_three_polygons()
    result = render_raster(scene, RasterSettings(record_steps=True))
    history = result.history
    assert history.n_steps == 3
    assert result.draw.object_index.tolist() == [0, 1, 2]  # green, blue, yellow
    colors = [np.asarray(o.material.color) for o in scene.objects]
    for k in range(4):
        color, zbuf = history.buffers(k)
        winners = [painter_reference(scene, k, j) for j in (-0.05, 0.0, 0.05)]
        winner, depth = winners[1]
        sure = (winners[0][0] == winner) & (winners[2][0] == winner)  # not at an edge
        assert sure.mean() > 0.97
        expected = np.where(winner[..., None] >= 0,
                            np.array(colors + [scene.background])[winner], scene.background)
        assert np.allclose(color[sure], expected[sure], atol=1e-12)
        covered = sure & (winner >= 0)
        ours = zbuffer.distance_from_window_depth(zbuf[covered], scene.camera.near, scene.camera.far,
                                                  False)
        assert np.allclose(ours, depth[covered], rtol=1e-9)
        assert np.all(zbuf[sure & (winner < 0)] == zbuffer.FAR_DEPTH)


def _alone(scene, index, jitter=0.0):
    """(H, W) bool: pixels covered by object ``index`` on its own."""
    only = type(scene)(camera=scene.camera, objects=(scene.objects[index],))
    return painter_reference(only, 1, jitter)[0] == 0


def test_fragment_counts_per_polygon_in_the_three_polygon_figure():
    scene = presets.zbuffer_three_polygons()
    draw = render_raster(scene).draw
    green, blue, yellow = range(3)
    covers = [_alone(scene, i) for i in range(3)]
    assert draw.generated.tolist() == [int(c.sum()) for c in covers]
    assert draw.failed[green] == 0 and draw.failed[blue] == 0  # blue is nearest everywhere
    # Yellow, drawn last, fails exactly where blue covers it too, and passes over green.
    assert draw.failed[yellow] == np.sum(covers[yellow] & covers[blue])
    assert draw.passed[yellow] > 0


def test_piercing_polygons_are_resolved_pixel_by_pixel_in_either_order():
    scene = presets.zbuffer_piercing()
    forward = render_raster(scene)
    backward = render_raster(type(scene)(camera=scene.camera, objects=scene.objects[::-1]))
    different = np.any(forward.color != backward.color, axis=-1)
    assert different.mean() < 0.002  # only where both have the same depth to the last bit
    both = _alone(scene, 0) & _alone(scene, 1)
    column = np.broadcast_to(np.arange(scene.camera.width), both.shape)
    left, right = both & (column < scene.camera.width // 2 - 1), both & (column > scene.camera.width // 2)
    assert left.sum() > 100 and right.sum() > 100
    # Green (z = 0.6 x) is in front on the right, blue (z = -0.6 x) on the left.
    green, blue = (np.asarray(o.material.color) for o in scene.objects)
    assert np.all(forward.color[right] == green) and np.all(forward.color[left] == blue)


def test_depth_test_is_strict():
    assert zbuffer.depth_test(0.2, 0.3)
    assert not zbuffer.depth_test(0.3, 0.3)


@pytest.mark.parametrize("fmt", DEPTH_FORMATS)
def test_of_two_fragments_at_the_same_depth_the_one_drawn_first_stays(fmt):
    """The tie rule: the z-test is strict, so an equal depth fails."""
    corners = [(-1.0, -1.0, 0.0), (1.0, -1.0, 0.0), (0.0, 1.0, 0.0)]
    red, green = (Mesh(corners, [[0, 1, 2]], Material(color=c), n)
                  for c, n in (((1.0, 0.0, 0.0), "red"), ((0.0, 1.0, 0.0), "green")))
    cam = Camera(eye=(0.0, 0.0, 4.0), target=(0.0, 0.0, 0.0), width=40, height=30)
    for first, second in ((red, green), (green, red)):
        result = render_raster(Scene(camera=cam, objects=(first, second)),
                               RasterSettings(depth_format=fmt, record_steps=True))
        covered = np.isfinite(result.depth)
        assert covered.sum() > 100
        assert np.all(result.draw.failed == [0, covered.sum()])
        winner = np.argmax(first.material.color)
        assert np.all(np.argmax(result.color[covered], axis=-1) == winner)
        kept, tied = result.history.pixel_history(20, 15)
        assert kept.passed and not tied.passed and tied.z == tied.stored_z == kept.z
