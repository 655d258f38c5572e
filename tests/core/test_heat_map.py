"""What each pixel cost: the heat maps of both pipelines add up to their counters and change no pixel."""

from dataclasses import replace

import heat_scenes as hs
import numpy as np
import pytest
import verdict_scenes as vs

from core.accuracy.supersampling import trace_adaptive
from core.heat_map import SHADE, heat_map
from core.image_order.flat_layout import HEAT_BOUNDS_TESTS, HEAT_PRIM_TESTS
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.image_order.ray_tree import trace_pixel
from core.object_order.pipeline import RasterSettings, render_raster
from core.presets_trace import big_mesh, mirror_and_glass
from core.srgb import LUMINANCE

ACCELS = ("none", "spheres", "grid", "grid+spheres", "bvh")


def _small(scene, width=48, height=36):
    return replace(scene, camera=scene.camera.replace(width=width, height=height))


@pytest.mark.parametrize("accel", ACCELS)
def test_traced_heat_adds_up_to_the_counters_and_changes_no_pixel(accel):
    # Mirrors and glass: primary, shadow, reflected and refracted rays all count.
    scene = _small(mirror_and_glass())
    settings = TraceSettings(accel=accel)
    plain, counted = render_trace(scene, settings), render_trace(scene, settings, heat=True)
    assert plain.heat is None
    assert counted.heat.shape == (36, 48, 2) and counted.heat.dtype == np.int64
    accel_stats = counted.stats["accel"]
    assert counted.heat[..., HEAT_PRIM_TESTS].sum() == accel_stats["prim_tests"] > 0
    # Box and sphere tests: bounding spheres, BVH boxes and the grid's cells walked.
    boxes_and_spheres = accel_stats["bounds_tests"] + accel_stats["cells_visited"]
    assert counted.heat[..., HEAT_BOUNDS_TESTS].sum() == boxes_and_spheres
    assert (accel_stats["cells_visited"] > 0) == ("grid" in accel)
    assert (counted.heat >= 0).all()
    assert counted.stats["rays"]["reflection"] > 0 and counted.stats["rays"]["refraction"] > 0
    for a, b in ((plain.color, counted.color), (plain.depth, counted.depth),
                 (plain.object_index, counted.object_index)):
        assert np.array_equal(a, b)  # bit for bit


def test_the_grids_cell_walks_are_its_box_tests_in_the_heat_map():
    # The grid alone tests no bounding sphere: every box test it makes is a cell walked, so its
    # heat map's box and sphere tests are exactly the cells each pixel's rays walk.
    scene = _small(mirror_and_glass())
    counted = render_trace(scene, TraceSettings(accel="grid"), heat=True)
    accel_stats = counted.stats["accel"]
    assert accel_stats["bounds_tests"] == 0
    assert counted.heat[..., HEAT_BOUNDS_TESTS].sum() == accel_stats["cells_visited"] > 0
    assert (counted.heat[..., HEAT_BOUNDS_TESTS] > 0).mean() > 0.5  # most primary rays enter the grid


@pytest.mark.parametrize("accel", [a for a in ACCELS if a != "bvh"])
def test_a_pixels_ray_tree_costs_what_its_heat_map_pixel_says(accel):
    # The heat map counts every ray of a pixel; its ray tree lists the same rays one by one, so
    # their tests add up to the pixel's heat, box and sphere tests (grid cells included) apart.
    # (Not the BVH: the image walks it with packets of primary rays and shares each packet's walk
    # among its pixels, where the ray tree walks one ray alone.)
    scene = _small(mirror_and_glass())
    settings = TraceSettings(accel=accel)
    heat = render_trace(scene, settings, heat=True).heat
    for x, y in ((24, 18), (10, 25), (40, 8)):
        nodes, stack = [], [trace_pixel(scene, x, y, settings)]
        while stack:
            nodes.append(stack.pop())
            stack.extend(nodes[-1].children)
        assert sum(n.tests for n in nodes) == heat[y, x, HEAT_PRIM_TESTS], (x, y)
        assert sum(n.bounds_tests for n in nodes) == heat[y, x, HEAT_BOUNDS_TESTS], (x, y)


def test_without_acceleration_every_primary_ray_tests_every_primitive():
    # Ray casting of one 12-triangle box: no shadow rays (no lights), no secondary rays, so
    # each pixel's ray makes exactly 12 primitive tests and no bounding-volume test.
    scene = _small(vs.pane_over_box())
    scene = replace(scene, objects=scene.objects[1:])  # the box alone
    heat = render_trace(scene, TraceSettings(mode="raycast", accel="none"), heat=True).heat
    assert (heat[..., HEAT_PRIM_TESTS] == 12).all() and (heat[..., HEAT_BOUNDS_TESTS] == 0).all()


def test_on_a_large_mesh_the_bvh_tests_fewer_primitives_a_pixel_than_the_grid_and_the_grid_than_none():
    scene = _small(big_mesh(), 64, 48)
    mean = {accel: render_trace(scene, TraceSettings(mode="raycast", accel=accel), heat=True)
            .heat[..., HEAT_PRIM_TESTS].mean() for accel in ("none", "grid", "bvh")}
    assert mean["bvh"] < mean["grid"] < mean["none"]


def test_a_coarse_image_has_no_heat_map():
    with pytest.raises(ValueError, match="step must be 1"):
        render_trace(_small(mirror_and_glass()), TraceSettings(), step=2, heat=True)


def test_overdraw_counts_every_fragment_at_its_pixel():
    result = render_raster(vs.two_quads(), RasterSettings(record_steps=True))
    overdraw = result.history.fragments_per_pixel()
    assert overdraw.shape == (30, 40)
    assert overdraw.sum() == result.stats["fragments_generated"]
    x, y = vs.PIXEL
    assert overdraw[y, x] == 2  # both quads cover it (see verdict_scenes.two_quads)
    assert overdraw[0, 0] == 0  # the corner's ray passes beside both quads


def test_adaptive_supersampling_takes_the_fewest_samples_away_from_an_edge_and_more_on_it():
    scene = hs.flat_edge()  # worked by hand in its docstring
    adaptive = trace_adaptive(scene, TraceSettings(mode="raycast"), 0.05, hs.N, np.random.default_rng(0))
    assert np.array_equal(adaptive.samples, hs.flat_edge_samples())
    assert adaptive.traced == hs.FLAT_EDGE_TRACED == 1751
    heat = heat_map(adaptive.samples, "samples per pixel")
    assert (heat.top, heat.total) == (17, 17 * 30 + 1 * (40 * 30 - 30))
    # Away from the edge the corners' mean is the flat colour itself; on it, a mix of both.
    assert np.all(adaptive.color[:, :24] == 1.0) and np.all(adaptive.color[:, 25:] == 0.0)
    assert np.all((adaptive.color[:, 24] > 0.0) & (adaptive.color[:, 24] < 1.0))


def test_each_heat_map_pixel_is_its_counts_colour_on_the_scale_only_darkened_by_the_image_beneath():
    # The heat-map lesson step says "dark for none, bright for the most any pixel took", and the
    # window shows the scale beside the map: a pixel must read on that scale.  Laid over the
    # image at three quarters, a pixel with no count over a white image showed a quarter white, a
    # light grey that is nowhere on the scale.  Each pixel is its count's colour on the scale
    # (top = 6, so the scale's colour k/6 is count k's), the same colour where the image is white
    # and darker, never another hue, by at most SHADE where the image is black.
    counts = np.array([[0, 0, 0, 3], [6, 6, 6, 1]])
    image = np.array([[[1.0, 1.0, 1.0], [0.0, 0.0, 0.0], [0.2, 0.5, 0.9], [1.0, 1.0, 1.0]],
                      [[1.0, 1.0, 1.0], [0.0, 0.0, 0.0], [0.3, 0.9, 0.1], [0.5, 0.5, 0.5]]])
    heat = heat_map(counts, "primitive tests")
    shown = heat.over(image)
    scale = heat.colorbar(length=heat.top + 1)[0]  # the strip's colour k is count k's
    for (y, x), count in np.ndenumerate(counts):
        colour = scale[count]
        factor = shown[y, x] / colour
        assert np.allclose(factor, factor[0]), (y, x)  # the same hue, only darker or lighter
        assert 1.0 - SHADE - 1e-12 <= factor[0] <= 1.0 + 1e-12, (y, x)
        if image[y, x].min() == 1.0:
            assert np.allclose(shown[y, x], colour), (y, x)
    none = shown[counts == 0]
    assert none.max() <= scale[0].max() + 1e-12  # no count: as dark as the scale's darkest colour
    assert shown[1, 0] @ LUMINANCE > 0.9  # the most, over white: the scale's brightest (pale yellow)
