"""What accuracy costs: supersampling, adaptive sampling, error metrics and sweeps.

The supersampling tests use a straight slanted edge whose exact pixel
coverage is computed here with exact fractions (the area of each pixel on
the lit side of the edge), independently of both renderers.
"""

import math
from dataclasses import replace
from fractions import Fraction

import numpy as np
import pytest

from core.accuracy import error_metrics, supersampling
from core.accuracy.resolution import to_size
from core.accuracy.sweep import DEPTH_RATIOS, KNOBS, Sweep, knee_index, unavailable
from core.camera import Camera
from core.image_order.flat_scene import TraceSettings
from core.object_order.depth_formats import BYTES_PER_PIXEL, DEPTH_FORMATS
from core.object_order.pipeline import RasterSettings, render_raster
from core.presets import lecture_scene
from core.presets_trace import mirror_and_glass
from core.scene import Material, Mesh, PointLight, Scene

W, H = 48, 32
#: The edge, in pixel coordinates (x right, y down): the lit side is y > Y0 + SLOPE * x.
Y0, SLOPE = Fraction(7), Fraction(3, 8)
WHITE = Material(color=(1.0, 1.0, 1.0), ambient=1.0, diffuse=0.0, specular=0.0)


def _edge_scene() -> Scene:
    """A white triangle (shown at exactly 1.0, no lights) on black, its top edge slanted.

    An orthographic camera one scene unit per pixel: pixel coordinates (x, y)
    are world ``(x - W/2, H/2 - y)`` on the plane z = 0.
    """
    cam = Camera(eye=(0.0, 0.0, 10.0), target=(0.0, 0.0, 0.0), projection="orthographic",
                 ortho_height=float(H), near=1.0, far=20.0, width=W, height=H)

    def world(x, y):
        return (float(x) - W / 2, H / 2 - float(y), 0.0)

    far = 1000
    corners = [world(-far, Y0 - SLOPE * far), world(-far, 10 * far), world(far, Y0 + SLOPE * far)]
    # counter-clockwise as the camera (on +z) sees it
    tri = Mesh(vertices=corners, triangles=[[0, 1, 2]], material=WHITE, name="edge")
    return Scene(camera=cam, objects=(tri,), lights=(), background=(0.0, 0.0, 0.0))


def _lit_area(i: int, j: int) -> Fraction:
    """Exact area of pixel (i, j) with y > Y0 + SLOPE x (Sutherland-Hodgman clip, shoelace)."""
    square = [(Fraction(i), Fraction(j)), (Fraction(i + 1), Fraction(j)), (Fraction(i + 1), Fraction(j + 1)),
              (Fraction(i), Fraction(j + 1))]

    def side(p):
        return p[1] - Y0 - SLOPE * p[0]

    clipped = []
    for a, b in zip(square, square[1:] + square[:1], strict=True):
        sa, sb = side(a), side(b)
        if sa >= 0:
            clipped.append(a)
        if (sa > 0 and sb < 0) or (sa < 0 and sb > 0):
            t = sa / (sa - sb)
            clipped.append((a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])))
    if len(clipped) < 3:
        return Fraction(0)
    twice = sum(p[0] * q[1] - q[0] * p[1] for p, q in zip(clipped, clipped[1:] + clipped[:1], strict=True))
    return abs(twice) / 2


@pytest.fixture(scope="module")
def exact_edge():
    """(H, W, 3): the true box-filtered image of the edge scene."""
    coverage = np.array([[float(_lit_area(i, j)) for i in range(W)] for j in range(H)])
    return np.repeat(coverage[..., None], 3, axis=2)


def test_exact_coverage_is_a_clean_half_plane(exact_edge):
    # sanity of the hand-made reference: fully dark at the top, fully lit at the bottom
    assert exact_edge[0, 0, 0] == 0.0 and exact_edge[-1, 0, 0] == 1.0
    assert np.all((exact_edge >= 0) & (exact_edge <= 1))


def test_one_sample_per_pixel_is_the_ordinary_render(exact_edge):
    scene = _edge_scene()
    image = supersampling.trace_supersampled(scene, TraceSettings(mode="raycast"), 1,
                                             np.random.default_rng(0))
    inside = (exact_edge == 1.0)
    assert np.all(image[inside] == 1.0)  # the white surface is shown at exactly 1.0
    assert np.all(image[exact_edge == 0.0] == 0.0)


@pytest.mark.parametrize("pipeline", ["trace", "raster"])
def test_supersampling_error_falls_as_n_grows(exact_edge, pipeline):
    scene = _edge_scene()
    errors = []
    for n in (1, 2, 4, 8):
        rng = np.random.default_rng(1)
        if pipeline == "trace":
            image = supersampling.trace_supersampled(scene, TraceSettings(mode="raycast"), n, rng)
        else:
            image = supersampling.raster_supersampled(scene, RasterSettings(), n, rng)
        errors.append(error_metrics.rmse(exact_edge, image))
    assert errors[0] > errors[1] > errors[2] > errors[3], errors
    assert errors[3] < errors[0] / 4  # 8x8 is far better than one sample: 1/N decay would give 1/8


def test_adaptive_reaches_4x4_with_under_half_the_samples(exact_edge):
    scene = _edge_scene()
    settings = TraceSettings(mode="raycast")
    uniform = supersampling.trace_supersampled(scene, settings, 4, np.random.default_rng(2))
    adaptive = supersampling.trace_adaptive(scene, settings, 0.05, 4, np.random.default_rng(2))
    e_uniform = error_metrics.rmse(exact_edge, uniform)
    e_adaptive = error_metrics.rmse(exact_edge, adaptive.color)
    assert e_adaptive <= 1.1 * e_uniform, (e_adaptive, e_uniform)
    assert adaptive.traced < 0.5 * 16 * W * H
    # Flat regions: pixels whose four corners are strictly on one side of the edge.
    ys = np.arange(H + 1)[:, None] - float(Y0) - float(SLOPE) * np.arange(W + 1)[None, :]
    corner_side = np.sign(ys)
    flat = np.abs(corner_side[:-1, :-1] + corner_side[:-1, 1:] + corner_side[1:, :-1]
                  + corner_side[1:, 1:]) == 4
    assert flat.sum() > 0.8 * W * H
    assert np.all(adaptive.samples[flat] == 1)
    crossed = (exact_edge[..., 0] > 0) & (exact_edge[..., 0] < 1)
    assert np.all(adaptive.samples[crossed] == 17)  # every pixel the edge crosses was refined


def test_jitter_puts_one_sample_in_every_stratum():
    pattern = supersampling.jitter(5, 80, 4, np.random.default_rng(3))
    for row in (0, 70):
        xs, ys = pattern.xs(row, np.array([2])), pattern.ys(row, row + 1)
        cells_x = np.floor((xs - 2) * 4).astype(int)
        cells_y = np.floor((ys - row) * 4).astype(int)
        assert sorted(cells_x) == [0, 1, 2, 3] and sorted(cells_y) == [0, 1, 2, 3]


def test_metrics_on_known_images():
    a = np.zeros((8, 8, 3))
    b = a.copy()
    b[:4] = 1.0
    assert error_metrics.rmse(a, b) == pytest.approx(np.sqrt(0.5))
    assert error_metrics.flip(a, a)[0] == 0.0
    mean, error_map = error_metrics.flip(a, b)
    assert 0.5 < mean <= 1.0 and error_map.shape == (8, 8)
    assert error_map[6].max() < error_map[1].min()  # the error sits where the images differ
    objects = np.zeros((2, 5), int)
    assert error_metrics.wrong_pixel_fraction(objects, objects + (np.arange(5) == 0)) == 0.2
    depth = np.full((1, 2), 2.0)
    same = np.zeros((1, 2))
    assert error_metrics.depth_error(depth, depth + [[0.5, np.inf]], same, same) == 0.5


def test_flip_runs_in_a_helper_process_and_gives_what_flip_evaluator_gives_here(monkeypatch):
    # flip-evaluator holds Python's lock for all its work: in the window's process no other thread
    # (the GUI thread) ran Python meanwhile, 277 ms for a 640x480 image.
    rng = np.random.default_rng(7)
    reference, test = rng.random((48, 64, 3)), rng.random((48, 64, 3))
    here, flip_here = [], error_metrics.flip_here
    monkeypatch.setattr(error_metrics, "flip_here", lambda *args: (here.append(1), flip_here(*args))[1])
    mean, error_map = error_metrics.flip(reference, test)
    assert here == []  # computed in the helper
    import flip_evaluator

    from core.srgb import linear_to_srgb

    direct_map, direct_mean, _ = flip_evaluator.evaluate(  # the library called here, by hand
        linear_to_srgb(reference).astype(np.float32), linear_to_srgb(test).astype(np.float32), "LDR",
        inputsRGB=True, applyMagma=False, parameters={"ppd": error_metrics.PIXELS_PER_DEGREE})
    assert mean == float(direct_mean) and np.array_equal(error_map, np.asarray(direct_map).reshape(48, 64))


def test_box_downsample_and_nearest_upsample():
    image = np.arange(16.0).reshape(4, 4)
    assert to_size(image, 2, 2).tolist() == [[2.5, 4.5], [10.5, 12.5]]
    assert to_size(image[:2, :2], 4, 4)[3].tolist() == [4.0, 4.0, 5.0, 5.0]


def _small(scene, w=40, h=30):
    return replace(scene, camera=scene.camera.replace(width=w, height=h))


def test_accel_rows_are_exactly_the_unaccelerated_image():
    sweep = Sweep(_small(mirror_and_glass()), ["accel"], "raytrace", runs=3, reference_spp=2)
    rows = sweep.run()
    assert [r.value for r in rows] == list(KNOBS["accel"].values)
    for r in rows:
        assert r.rmse == 0.0 and r.wrong_pixel_fraction == 0.0 and r.flip == 0.0
        assert r.compared_with == "none"
    assert sum(r.knee for r in rows) == 1


def test_sweep_has_a_row_per_setting_and_a_knee_per_knob():
    sweep = Sweep(_small(mirror_and_glass()), ["depth", "tessellation", "spp"], "raytrace", runs=3,
                  reference_spp=2)
    rows = sweep.run()
    expected = [(k, KNOBS[k].label(v)) for k in ("depth", "tessellation", "spp") for v in KNOBS[k].values]
    assert [(r.knob, r.value) for r in rows] == expected
    for knob in ("depth", "tessellation", "spp"):
        assert sum(r.knee for r in rows if r.knob == knob) == 1
    tess = [r for r in rows if r.knob == "tessellation"]
    assert all(r.mode == "raster" for r in tess)
    # finer spheres: silhouettes and depths approach the tracer's exact spheres
    assert tess[-1].depth_error < tess[0].depth_error
    assert tess[-1].wrong_pixel_fraction < tess[0].wrong_pixel_fraction
    assert [r.bytes for r in tess] == sorted(r.bytes for r in tess)
    # ray depth 0 misses the mirror's and the glass's light: clearly worse than depth 10
    depth = {r.value: r for r in rows if r.knob == "depth"}
    assert depth["0"].rmse > 2 * depth["10"].rmse


def test_sweep_resumes_after_being_stopped():
    sweep = Sweep(_small(lecture_scene(), 24, 18), ["depth"], "raytrace", runs=3, reference_spp=2)
    events = sweep.events()
    for _ in events:
        if sweep.points:
            break  # stopped right after the first setting
    events.close()
    assert len(sweep.points) == 1 and not sweep.finished
    rows = sweep.run()
    assert len(rows) == len(KNOBS["depth"].values) and sweep.finished


def test_knobs_not_offered_say_why():
    assert "no analytic spheres" in unavailable("tessellation", lecture_scene())
    assert unavailable("tessellation", mirror_and_glass()) is None
    sweep = Sweep(lecture_scene(), ["tessellation"], "raster")
    assert sweep.settings == [] and "tessellation" in sweep.skipped


def test_knee_is_the_cheapest_within_tolerance():
    from core.accuracy.sweep import Row

    rows = [Row("spp", str(i), "raycast", s, 0.0, f, 0.0, 0.0, f, 1.0, None, "reference")
            for i, (s, f) in enumerate([(0.5, 0.30), (1.0, 0.02), (2.0, 0.012), (4.0, 0.011)])]
    assert knee_index(rows, 0.01) == 1
    assert knee_index(rows, 0.0) == 3


def test_knee_follows_the_knobs_order_not_timing_noise():
    from core.accuracy.sweep import Row

    # a dearer setting timed faster (a busy machine): the knee stays the cheaper value ...
    rows = [Row("depth", str(d), "raytrace", s, 0.0, f, 0.0, 0.0, f, 1.0, None, "reference")
            for d, (s, f) in enumerate([(0.05, 0.11), (0.08, 0.0147), (0.10, 0.0143), (0.05, 0.0143)])]
    assert knee_index(rows, 0.01) == 1
    # ... while methods that differ only in time are ranked by time
    assert knee_index(rows, 1.0, by_time=True) == 0


def _parallel_planes(d=50.0, gap=0.01, far=100.0) -> Scene:
    """Two squares facing the observer at distances ``d`` and ``d + gap``; the farther (red) drawn first."""
    cam = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=40, near=1.0, far=far,
                 width=40, height=30)

    def square(z, half, color, name):
        v = [(-half, -half, -z), (half, -half, -z), (half, half, -z), (-half, half, -z)]
        return Mesh(v, [[0, 1, 2], [0, 2, 3]], Material(color=color), name)

    return Scene(camera=cam, objects=(square(d + gap, 0.24 * d, (1.0, 0.0, 0.0), "far"),
                                      square(d, 0.2 * d, (0.0, 1.0, 0.0), "near")),
                 lights=(PointLight((0.0, 0.0, 10.0)),))


def _int16_collides(d, gap, near, far) -> bool:
    """Exact window depths of both planes (fractions) rounded to 16 bits: the same step?"""
    d, gap, near, far = (Fraction(v) for v in (d, gap, near, far))

    def step(x):
        z = ((far + near) / (far - near) - 2 * far * near / ((far - near) * x) + 1) / 2
        return math.floor(z * 65535 + Fraction(1, 2))

    return step(d) == step(d + gap)


@pytest.fixture(scope="module")
def depth_format_rows():
    sweep = Sweep(_parallel_planes(), ["depth-format"], "raster", runs=3, reference_spp=1)
    return {r.value: r for r in sweep.run()}


def test_every_depth_format_is_swept_at_every_ratio_with_its_bytes(depth_format_rows):
    scene = _parallel_planes()
    for fmt in DEPTH_FORMATS:
        zbuffer = render_raster(scene, RasterSettings(depth_format=fmt)).stats["zbuffer_bytes"]
        for ratio in DEPTH_RATIOS:
            row = depth_format_rows[f"{fmt}@1:{ratio}"]
            assert row.mode == "raster" and row.bytes == zbuffer == 40 * 30 * BYTES_PER_PIXEL[fmt]
            assert row.compared_with == f"float64@1:{ratio}"
    assert len(depth_format_rows) == len(DEPTH_FORMATS) * len(DEPTH_RATIOS)


def test_int16_fights_at_1_to_1000_and_float64_never(depth_format_rows):
    assert _int16_collides(50, 0.01, 100 / 1000, 100)  # so the planes must fight
    assert depth_format_rows["int16@1:1000"].wrong_pixel_fraction > 0.01
    assert not _int16_collides(50, 0.01, 100 / 10, 100)
    assert depth_format_rows["int16@1:10"].wrong_pixel_fraction == 0.0
    for ratio in DEPTH_RATIOS:
        row = depth_format_rows[f"float64@1:{ratio}"]
        assert row.wrong_pixel_fraction == 0.0 and row.rmse == 0.0


def test_reversed_float32_is_never_worse_than_float32(depth_format_rows):
    for ratio in DEPTH_RATIOS:
        plain = depth_format_rows[f"float32@1:{ratio}"]
        reversed_ = depth_format_rows[f"float32-reversed@1:{ratio}"]
        assert reversed_.wrong_pixel_fraction <= plain.wrong_pixel_fraction


def test_the_depth_format_knee_is_the_fewest_bytes_that_never_fight_visibly(depth_format_rows):
    rows = list(depth_format_rows.values())
    (knee,) = [r for r in rows if r.knee] or [rows[knee_index(rows)]]
    worst = {}
    for r in rows:
        name = r.value.split("@")[0]
        worst[name] = max(worst.get(name, 0.0), r.flip)
    fine = [f for f in DEPTH_FORMATS if worst[f] <= 0.01]
    assert knee.value.split("@")[0] == min(fine, key=lambda f: (BYTES_PER_PIXEL[f], worst[f]))
    assert knee.value.endswith("@1:10000")


def test_knee_reports_its_error_as_a_multiple_of_the_best():
    sweep = Sweep(_small(lecture_scene(), 24, 18), ["depth"], "raytrace", runs=3, reference_spp=2)
    rows = sweep.run()
    best = min(r.flip for r in rows)
    for r in rows:
        assert r.flip_vs_best == pytest.approx(r.flip / best)
    assert sum(r.knee for r in rows) == 1
