"""A whole frame shared by the threads, and the compiled stages that replaced array code.

The back-face test, the bounding boxes and the drawing share their loops
between the threads; a frame must come out identical with one thread and with
two, fragments and all.  Sub-pixel triangles, which a fine mesh is made of,
are checked against an exact point-in-triangle test, and the compiled
stages against the array formulas of the lecture modules, bit for bit.
"""

from __future__ import annotations

import numba
import numpy as np
import pytest
from test_raster import brute_force_coverage  # tests/core is on sys.path

from core import projection, shapes
from core.camera import Camera
from core.object_order import fragments, rasterization, stages, zbuffer
from core.object_order.kernels.raster import depth_image
from core.object_order.pipeline import PARALLEL_WORK, RasterSettings, render_raster
from core.scene import Material, Mesh, PointLight, Scene


def _bumpy_scene(crossing: bool) -> Scene:
    """A bumpy opaque sphere of 20,000 triangles at 1280 x 800 (above ``PARALLEL_WORK``);
    with ``crossing`` the observer stands inside the near plane's reach of it and a
    transparent sphere stands in front, so clipping and reordering run too."""
    sphere = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, 71, 140)
    v = sphere.vertices
    bumpy = v * (1.0 + 0.08 * np.sin(7 * np.arctan2(v[:, 2], v[:, 0])))[:, None]
    objects = [Mesh(bumpy, sphere.triangles, Material(color=(0.85, 0.6, 0.3)), "bumpy")]
    eye, target, near = (((0.0, 0.3, 2.2), (0.9, 0.8, 0.0), 1.3) if crossing
                         else ((0.0, 0.6, 3.4), (0.0, 0.0, 0.0), 0.5))
    if crossing:
        objects.append(shapes.uv_sphere((0.6, 0.65, 0.7), 0.3, 20, 40,
                                        material=Material(color=(0.2, 0.4, 0.9), opacity=0.5)))
    camera = Camera(eye=eye, target=target, fov_y_deg=40, near=near, far=10.0, width=1280,
                    height=800)
    return Scene(camera=camera, objects=tuple(objects), lights=(PointLight((3.0, 5.0, 6.0)),))


def _render_with(threads: int, scene: Scene):
    before = numba.get_num_threads()
    numba.set_num_threads(threads)
    try:
        return render_raster(scene, RasterSettings(record_steps=True))
    finally:
        numba.set_num_threads(before)


@pytest.mark.parametrize("crossing", [False, True], ids=["inside", "clipped-and-transparent"])
def test_a_large_frame_is_identical_with_one_and_two_threads(crossing):
    scene = _bumpy_scene(crossing)
    cam = scene.camera
    assert cam.width * cam.height + len(scene.objects[0].triangles) >= PARALLEL_WORK
    one, two = _render_with(1, scene), _render_with(2, scene)
    assert (one.stats["polygons_clipped"] > 100) == crossing
    assert one.draw.transparent.any() == crossing
    assert one.stats["fragments_generated"] > 300_000
    for name in ("color", "depth", "zbuffer"):
        assert np.array_equal(getattr(one, name), getattr(two, name)), name
    for name in ("generated", "passed", "color", "depth", "triangle_index"):
        assert np.array_equal(getattr(one.draw, name), getattr(two.draw, name)), name
    assert np.array_equal(one.faces.normal, two.faces.normal)
    assert np.array_equal(one.draw.polygons.clip, two.draw.polygons.clip)
    for name in ("pixel", "z", "passed"):
        assert np.array_equal(getattr(one.history.fragments, name), getattr(two.history.fragments, name))


def test_sub_pixel_triangles_cover_exactly_the_centres_inside_them():
    """Triangles smaller than a pixel, many of them with a corner or an edge exactly on a
    pixel centre: each one's fragments are those of an exact point-in-triangle test."""
    rng = np.random.default_rng(7)
    width, height, n = 24, 20, 3000
    base = rng.integers(0, [width, height], (n, 1, 2)) + np.where(rng.random((n, 1, 1)) < 0.4, 0.5, 0.0)
    xy = (base + rng.integers(-200, 200, (n, 3, 2)) / 256).reshape(-1, 2)
    corners = np.arange(3 * n).reshape(-1, 3)
    result = fragments.draw(xy, np.full(len(xy), 0.5), corners, np.arange(n), np.ones((n, 3)),
                            np.ones(n), width, height, (0, 0, 0), record=True, threads=2)
    offsets = np.concatenate([[0], np.cumsum(result.generated)])
    drawn = 0
    for t in range(n):
        pixels = result.fragments.pixel[offsets[t]:offsets[t + 1]]
        expected = np.flatnonzero(brute_force_coverage(xy[corners[t]], width, height).ravel())
        assert np.array_equal(pixels, expected), t
        drawn += len(pixels) > 0
    assert 100 < drawn < n / 2  # most cover no centre at all


def test_compiled_window_coordinates_are_the_projection_formulas_bit_for_bit():
    rng = np.random.default_rng(3)
    clip = rng.normal(0, 2, (5000, 4))
    clip[:, 3] = np.abs(clip[:, 3]) + 0.1
    xy, z_win = rasterization.window_coordinates(clip, 640, 480)
    ndc = clip[:, :3] / clip[:, 3:4]
    assert np.array_equal(xy, projection.pixel_from_ndc(ndc[:, :2], 640, 480))
    assert np.array_equal(z_win, (ndc[:, 2] + 1.0) * 0.5)


@pytest.mark.parametrize("orthographic", [False, True])
def test_depth_image_is_the_distance_of_each_covered_pixel_and_infinite_elsewhere(orthographic):
    rng = np.random.default_rng(5)
    zbuf = rng.uniform(0, 1, (30, 40))
    zbuf[rng.random(zbuf.shape) < 0.3] = zbuffer.FAR_DEPTH
    depth = depth_image(zbuf, 0.5, 20.0, orthographic)
    covered = zbuf < zbuffer.FAR_DEPTH
    assert np.isinf(depth[~covered]).all()
    assert np.array_equal(depth[covered],
                          zbuffer.distance_from_window_depth(zbuf[covered], 0.5, 20.0, orthographic))


def test_triangles_accepted_untested_are_the_polygons_the_clipper_makes_of_them():
    """Objects inside the frustum skip the clipper's tests; their polygons must be those
    the clipper itself makes of triangles it finds inside."""
    rng = np.random.default_rng(6)
    clip = np.column_stack([rng.uniform(-0.9, 0.9, (300, 3)), np.ones(300)]) * rng.uniform(1, 5, (300, 1))
    world = rng.normal(size=(300, 3))
    triangles = rng.integers(0, 300, (200, 3))
    face = np.arange(200) + 17
    untested = stages.clip_triangles(face, triangles, clip, world, np.zeros(200, dtype=bool))
    tested = stages.clip_triangles(face, triangles, clip, world, np.ones(200, dtype=bool))
    assert (untested.accepted, untested.rejected, untested.clipped) == (200, 0, 0)
    assert (tested.accepted, tested.rejected, tested.clipped) == (200, 0, 0)
    for name in ("offsets", "vertex", "clip", "world", "face", "clipped"):
        assert np.array_equal(getattr(untested.polygons, name), getattr(tested.polygons, name)), name
