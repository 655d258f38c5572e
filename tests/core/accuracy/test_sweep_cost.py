"""A sweep's cost is estimated from the scene and settings alone, before anything is rendered or built."""

import tracemalloc

from core import budget, shapes
from core.accuracy import sweep_cost
from core.accuracy.sweep import Sweep
from core.scene import Scene, Sphere


def test_the_raster_reference_tessellation_is_counted_without_building_it():
    # 1000 spheres: the raster reference tessellates each into 128 x 256, 65,024 triangles,
    # 65 million in all: several GB if they were built.
    scene = Scene(objects=tuple(Sphere((0.0, 0.0, -k), 0.5) for k in range(1000)))
    sweep = Sweep(scene, ("spp",), "raster")
    tracemalloc.start()
    cost = sweep_cost.estimate(sweep)
    _, peak = tracemalloc.get_traced_memory()
    tracemalloc.stop()
    per_sphere = len(shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, 128, 256).triangles)
    assert cost.parts["triangles"] == 1000 * per_sphere * budget.BYTES_PER_TRIANGLE["raster"]
    assert cost.bytes > 10e9 and peak < 1e6


def test_the_largest_render_of_a_resolution_sweep_has_four_times_the_pixels():
    scene = Scene()
    cam = scene.camera
    cost = sweep_cost.estimate(Sweep(scene, ("resolution",), "raycast"))
    assert cost.parts["image buffers"] == 4 * cam.width * cam.height * budget.BYTES_PER_PIXEL["raycast"]


def test_a_sweep_takes_longer_with_more_reference_samples():
    scene = Scene()
    fast = sweep_cost.estimate(Sweep(scene, ("depth",), "raytrace", reference_spp=1))
    slow = sweep_cost.estimate(Sweep(scene, ("depth",), "raytrace", reference_spp=16))
    assert slow.seconds > fast.seconds
