"""The hard-case lab: robust methods pass across each slider, the textbook ones fail where they should.

Expected values come from reasoning stated beside each test (rounding grids,
exact geometry), never from the lab's own output.
"""

import math

import mpmath
import numpy as np
import pytest

from core import hard_cases
from core.hard_cases import (
    clipping_cases,
    culling_cases,
    depth_cases,
    optics_cases,
    shadow_acne,
    sphere_cases,
    triangle_cases,
)
from core.hard_cases.result import CaseResult


@pytest.fixture(scope="module")
def defaults() -> dict[str, CaseResult]:
    return {r.name: r for r in hard_cases.run_all()}


def test_registry_names_match_results_and_every_default_passes(defaults):
    assert list(defaults) == list(hard_cases.CASES)
    assert len(defaults) == 10
    for name, r in defaults.items():
        assert r.passed, (name, r.robust_error, r.tolerance)
        assert not r.naive_passed, name  # each default shows the textbook method failing
        assert r.explanation.count(".") >= 2 and r.title and r.rows


def test_unknown_case_is_a_key_error_listing_the_cases():
    with pytest.raises(KeyError, match="shadow_acne"):
        hard_cases.run_case("no such case")


def test_cases_with_a_failure_one_can_see_carry_images(defaults):
    for name in ("shared_edges", "z_fighting", "behind_eye", "shadow_acne", "culling"):
        (image,) = defaults[name].images
        assert image.naive.shape == image.robust.shape and image.naive.shape[2] == 3
        assert image.naive.min() >= 0.0 and image.naive.max() <= 1.0
        assert not np.array_equal(image.naive, image.robust), name


@pytest.mark.parametrize("offset", [1e-13, 1e-12, 3e-11, 1e-9, 1e-6])
def test_tangent_rays_robust_verdicts_always_right(offset):
    assert sphere_cases.tangent_rays(offset).robust_error == 0


def test_tangent_rays_textbook_fails_only_below_its_rounding():
    # b² ≈ 4 · 1234.5² ≈ 6.1e6 carries a rounding of about 6.1e6 · 2^-53 ≈ 7e-10 while Δ ≈ 8 · offset:
    # at offset 1e-6 the sign is safe, at 3e-11 (Δ ≈ 2.4e-10) it is not.
    assert sphere_cases.tangent_rays(1e-6).naive_error == 0
    assert sphere_cases.tangent_rays(3e-11).naive_error >= 1


@pytest.mark.parametrize("offset", [1e-13, 3e-11, 1e-10, 3e-10, 1e-6])
def test_tangent_rays_words_follow_the_slider(offset):
    # They said "b² - 4ac cannot tell the three rays apart and calls them all tangent" at every offset,
    # beside a table that at 1e-6 shows it right three times of three.  b² ≈ 4 · 1234.5² ≈ 6.1e6 is
    # rounded in steps of 2^-30 ≈ 9.3e-10 (6.1e6 lies between 2^22 and 2^23); Δ ≈ 8 · offset
    # (4 (r² - (r (1 ± offset))²) with r = 1): below the step at 1e-13 to 1e-10, above it from 3e-10.
    result = sphere_cases.tangent_rays(offset)
    text = result.explanation
    verdicts = result.rows[0]
    assert "b² and 4ac are both about 6.1e+06 and each is rounded in steps of 9e-10" in text
    if 8 * offset < 2.0**-30:
        assert "is smaller than that" in text or "the exact reference calls all three tangent" in text
        assert f"calls them {verdicts.naive}" in text
        if "smaller" in text:
            assert f"{int(result.naive_error)} of 3 wrong" in text and result.naive_error >= 1
    else:
        assert "is larger than that, so at this offset b² - 4ac still tells them apart" in text
        assert result.naive_error == 0 and verdicts.naive == "misses, tangent, crosses"
    assert "cannot tell the three rays apart" not in text


def test_textbook_discriminant_rounds_each_step_as_written():
    # Plain Python floats round every product and sum in the order written, with no fused
    # multiply-add: the lab's textbook numbers must be those on every machine (BLAS's dot is not).
    o, d, c, r = (0.1, -0.2, 0.3), tuple(sphere_cases.FAR_DIRECTION), (3.7e7, 8.1e7, -4.5e7), 1.0
    f = [p - q for p, q in zip(o, c, strict=True)]
    a = d[0] * d[0] + d[1] * d[1] + d[2] * d[2]
    b = 2.0 * (f[0] * d[0] + f[1] * d[1] + f[2] * d[2])
    cc = (f[0] * f[0] + f[1] * f[1] + f[2] * f[2]) - r * r
    assert float(sphere_cases.textbook_discriminant(o, d, c, r)[0]) == b * b - 4.0 * a * cc


@pytest.mark.parametrize("distance", [1.0, 1e3, 1e5, 1e7, 1e9])
def test_far_sphere_robust_within_tolerance(distance):
    assert sphere_cases.far_sphere(distance).passed


def test_far_sphere_textbook_loses_every_digit_at_1e9():
    # At 10^9, b² ≈ 4e18 is rounded to multiples of 512, and Δ is about 3.
    r = sphere_cases.far_sphere(1e9)
    assert r.naive_error >= 0.1 and r.robust_error < 1e-6


def test_far_sphere_textbook_digits_run_out_where_its_words_say():
    # "none at all in float32 beyond a few thousand units, none in float64 beyond about 10^8": the
    # digits correct against the exact discriminant.  It said "a few hundred", where float32 still
    # keeps one or two.
    def digits(distance, of):
        rows = {row.label: row for row in sphere_cases.far_sphere(distance).rows}
        return rows[f"digits correct of {of}"].naive

    assert "none at all in float32 beyond a few thousand units, none in float64 beyond about 10^8" in \
        sphere_cases.far_sphere(1e4).explanation
    assert digits(300, "7 (float32)") >= 1 and digits(500, "7 (float32)") >= 1
    assert digits(3e3, "7 (float32)") == 0 and digits(1e4, "7 (float32)") == 0
    assert digits(1e7, "16 (float64)") >= 5
    assert digits(1e8, "16 (float64)") == 0 and digits(1e9, "16 (float64)") == 0


def test_far_sphere_exact_discriminant_matches_the_distance_to_the_line():
    # Δ = 4a (r² - |v|²) with a = 1: for a unit direction aimed 0.5 beside the centre, Δ ≈ 4 (1 - 0.25) = 3.
    rows = {row.label: row for row in sphere_cases.far_sphere(1e4).rows}
    assert rows["Δ in float64"].exact == pytest.approx(3.0, rel=1e-6)


def test_lecture_segment_has_no_crossing_and_both_roots_outside():
    rows = {row.label: row for row in sphere_cases.lecture_segment().rows}
    assert rows["first crossing in 0 <= t <= 1"].robust == "no crossing"
    assert rows["t_near"].exact < 0 < 1 < rows["t_far"].exact


@pytest.mark.parametrize("distance", [0.0, 1e4, 1e6, 1e8])
def test_shared_edges_watertight_never_cracks(distance):
    r = triangle_cases.shared_edges(distance)
    assert r.robust_error == 0
    assert all(row.robust == 0 for row in r.rows)


def test_parallel_and_in_plane_rays_divide_by_zero_in_the_textbook():
    # The triangle lies in z = 0.25 and both rays have d_z = 0, so det = 0 exactly.
    r = triangle_cases.parallel_rays(1.0)
    rows = {row.label: row for row in r.rows}
    assert math.isinf(rows["parallel, 0.5 above: t (Cramer's rule with no check of det)"].naive)
    assert math.isnan(rows["in the plane: t (Cramer's rule with no check of det)"].naive)
    assert rows["parallel, 0.5 above: verdict"].robust == "miss"
    assert rows["in the plane: verdict"].robust == "miss"


@pytest.mark.parametrize("angle", [1e-12, 1e-9, 1e-6, 1e-3, 1.0])
def test_grazing_ray_is_a_hit_where_exact_arithmetic_puts_it(angle):
    # The ray starts 3 units before the centroid and is aimed at it; its start's height
    # 0.25 + 3 sin θ is rounded by up to 2^-55, which moves the crossing by 2^-55 / sin θ.
    r = triangle_cases.parallel_rays(angle)
    assert r.robust_error == 0
    grazing = r.rows[-1]
    assert grazing.robust == pytest.approx(grazing.exact, rel=1e-9)
    shift = 2.0**-55 / math.sin(math.radians(angle))
    assert grazing.exact == pytest.approx(3.0, abs=4 * shift + 1e-12)


def test_grazing_ray_is_thrown_away_by_the_textbook_epsilon():
    # det ≈ sin θ · |e1 × e2| with |e1 × e2| ≈ 6.9 here: below ε = 1e-8 for θ = 1e-8° (1.7e-10 rad).
    assert triangle_cases.parallel_rays(1e-8).naive_error == 1
    assert triangle_cases.parallel_rays(1.0).naive_error == 0


def test_window_depth_matches_the_perspective_formula():
    # The ray through a pixel centre meets the floor y = 0 at a view depth found by hand;
    # window depth is (z_ndc + 1) / 2 with z_ndc = (f + n)/(f - n) - 2 f n / ((f - n) depth).
    cam = depth_cases._camera(1e3)
    depth = depth_cases.window_depth(depth_cases._floor(0.0), cam)
    j, i = 80, 37
    with mpmath.workdps(40):
        hw, hh = cam.half_extent(1.0)
        view_dir = [mpmath.mpf((i + 0.5) / cam.width * 2 - 1) * hw,
                    mpmath.mpf(1 - (j + 0.5) / cam.height * 2) * hh, mpmath.mpf(-1)]
        rot = cam.world_from_view[:3, :3]
        world_dir = [sum(mpmath.mpf(rot[r, c]) * view_dir[c] for c in range(3)) for r in range(3)]
        t = -mpmath.mpf(cam.eye[1]) / world_dir[1]  # the view depth, since view_dir.z = -1
        n, f = mpmath.mpf(cam.near), mpmath.mpf(cam.far)
        z_win = ((f + n) / (f - n) - 2 * f * n / ((f - n) * t) + 1) / 2
    assert depth[j, i] == pytest.approx(float(z_win), abs=1e-12)


@pytest.mark.parametrize("ratio", [1e2, 1e4, 1e6, 1e7])
def test_reversed_depth_never_z_fights(ratio):
    assert depth_cases.z_fighting(ratio).robust_error == 0


def test_float32_depth_fights_only_when_the_near_plane_comes_close():
    # The floors' window depths differ by about near · gap / (distance · eye height):
    # 1 · 0.01 / (92 · 2) ≈ 5e-5 at near = 1 (far above float32's 6e-8 step near 1),
    # 1e-5 · 5e-5 ≈ 5e-10 at near = 1e-5 (far below it).
    assert depth_cases.z_fighting(1e2).naive_error == 0
    r = depth_cases.z_fighting(1e7)
    both = int(r.rows[0].label.split("of ")[1].rstrip(")"))
    assert r.naive_error > 0.5 * both


@pytest.mark.parametrize("ratio", [1e2, 1e3, 1e6])
def test_z_fighting_words_follow_the_slider(ratio):
    # They said "float32 and the integer formats store both floors as the same number" at every
    # ratio, beside a table where at far/near 100 no format loses a pixel.  The smallest gap: along a
    # pixel's ray the upper floor lies at (h - g) / h of the lower one's depth z, so their window depths
    # (f / (f - n)) (1 - n / z) differ by (f / (f - n)) (n / z) g / (h - g), least at the floor's far
    # corners, z = (4 + 92 · 30) / √904 ≈ 91.93 along the view axis: 5.47e-5 at far/near 100, then
    # ten times less for each factor of ten (pixel centres lie a little nearer: a little more).
    r = depth_cases.z_fighting(ratio)
    text = r.explanation
    f, g, h = 100.0, 0.01, 2.0
    n = f / ratio
    least = (f / (f - n)) * (n / ((4 + 92 * 30) / math.sqrt(904))) * g / (h - g)
    stated = float(text.split("as little as ")[1].split(",")[0])
    assert least <= stated * 1.06 and stated <= least * 1.25, (least, stated)
    assert f"a difference in the {math.ceil(-math.log10(stated))}th digit" in text
    wrong = {row.label.strip()[3:]: row.naive for row in r.rows[1:6]}
    lost = [fmt for fmt, pixels in wrong.items() if pixels]
    if ratio == 1e2:
        assert lost == [] and "every format still tells the floors apart" in text
    else:
        said = {1e3: "At far/near 1,000, int16 stores both floors as the same number",
                1e6: "At far/near 1,000,000, float32, int24 and int16 store both floors as the same number"}
        assert lost == (["int16"] if ratio == 1e3 else ["float32", "int24", "int16"])
        assert said[ratio] in text


@pytest.mark.parametrize("behind", [0.05, 0.5, 2.0, 10.0, 50.0])
def test_clipping_matches_the_ray_caster(behind):
    r = clipping_cases.behind_the_eye(behind)
    assert r.robust_error == 0 and r.naive_error > 0
    rows = {row.label: row for row in r.rows}
    # The camera looks along -z from z = 5, so a corner `behind` units behind it has w = -behind.
    assert rows["w of the corner behind the eye"].robust == pytest.approx(-behind, abs=1e-12)


@pytest.mark.parametrize("angle", [0.0, 20.0, 41.0, 42.0, 60.0, 89.0])
def test_refraction_or_total_reflection(angle):
    r = optics_cases.total_internal_reflection(angle)
    assert r.passed
    critical = math.degrees(math.asin(1 / 1.5))
    continues = r.rows[0]
    if angle > critical:
        assert math.isnan(r.naive_error) and continues.naive == "NaN"
        assert continues.robust == continues.exact == "reflected (total)"
        assert r.rows[-1].robust == 1.0
    else:
        assert continues.robust == continues.exact == "refracted"
        assert r.naive_error < 1e-14


def test_refracted_direction_obeys_snell():
    # sin θ2 = 1.5 sin θ1: the component along the surface grows by the ratio of the indices.
    from core.image_order.optics import refract

    n = optics_cases.NORMAL / np.linalg.norm(optics_cases.NORMAL)
    tangent = optics_cases.TANGENT / np.linalg.norm(optics_cases.TANGENT)
    d = math.cos(math.radians(30)) * n + math.sin(math.radians(30)) * tangent
    ok, t = refract(tuple(d), tuple(-n), 1.5)
    assert ok and np.linalg.norm(np.cross(t, n)) == pytest.approx(1.5 * math.sin(math.radians(30)), rel=1e-14)


@pytest.mark.parametrize("distance", [0.0, 1e4, 1e6, 1e10, 1e13])
def test_scaled_offset_never_self_shadows(distance):
    masks = shadow_acne.self_shadowed(distance, 1e-6)
    assert masks["on_square"].sum() > 1000
    assert not masks["scaled"].any()


def test_fixed_epsilon_fails_once_rounding_exceeds_it():
    # A coordinate near 10^4 is rounded to about 10^4 · 2^-53 ≈ 1e-12, well below ε = 1e-6;
    # near 10^11 it is about 1e-5, above it.
    near = shadow_acne.self_shadowed(1e4, 1e-6)
    far = shadow_acne.self_shadowed(1e11, 1e-6)
    assert not near["fixed"].any()
    assert far["fixed"].sum() > 0.1 * far["on_square"].sum()
    # With no offset at all, acne appears even at the origin.
    assert shadow_acne.self_shadowed(0.0, 0.0)["none"].sum() > 0.1 * near["on_square"].sum()


@pytest.mark.parametrize("yaw", [0.0, 30.0, 45.0, 60.0, 90.0])
def test_zbuffer_resolves_the_non_convex_solid(yaw):
    r = culling_cases.non_convex_culling(yaw)
    assert r.robust_error == 0
    rows = {row.label: row for row in r.rows}
    assert rows["pixels covered"].robust == rows["pixels covered"].exact


def test_culling_alone_shows_the_hidden_part_of_the_notch():
    assert culling_cases.non_convex_culling(45.0).naive_error > 100


def test_ray_cast_reference_sees_a_screen_filling_triangle_and_nothing_before_the_near_plane():
    from core.camera import Camera
    from core.hard_cases.ray_cast_reference import reference

    cam = Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=60.0, near=1.0, far=10.0,
                 width=20, height=10)
    # At depth 5 the view is 2·5·tan 30° ≈ 5.8 high and 11.5 wide: this triangle covers it all.
    big = np.array([[[-40.0, -20.0, -5.0], [40.0, -20.0, -5.0], [0.0, 40.0, -5.0]]])
    seen, certain = reference(cam, big)
    assert (seen == 0).all() and certain.all()
    too_near = big.copy()
    too_near[..., 2] = -0.5  # in front of the near plane: clipped away, so nothing is seen
    seen, _ = reference(cam, too_near)
    assert (seen == -1).all()
    # Two triangles sharing the diagonal of a square 3 units in front of the eye (16 x 16 pixels,
    # 60°): the square spans view x, y in [-1, 1] against a half-extent 3 tan 30° ≈ 1.73, so pixel
    # columns 4..11 lie well inside it, and the centres with i + j = 15 lie exactly on the diagonal.
    a, b, c, d = (-1.0, -1.0, -3.0), (1.0, -1.0, -3.0), (1.0, 1.0, -3.0), (-1.0, 1.0, -3.0)
    pair = np.array([[a, b, c], [a, c, d]])
    seen, certain = reference(Camera(eye=(0.0, 0.0, 0.0), target=(0.0, 0.0, -1.0), fov_y_deg=60.0,
                                     near=1.0, far=10.0, width=16, height=16), pair)
    assert {0, 1} <= set(seen[certain].tolist())
    i = np.arange(4, 12)
    assert not certain[15 - i, i].any()
    assert certain[15 - i, i - 1].all() and certain[15 - i, np.minimum(i + 1, 15)].all()
