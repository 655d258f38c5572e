"""Rasterization: the fill rule tiles the screen exactly once, depth is exact on the plane.

The compiled rasterizer is checked against exact rational arithmetic
(:class:`fractions.Fraction`), not against the module's own readable code:
coverage by a brute-force point-in-triangle test, depth by solving for the
plane exactly.
"""

from __future__ import annotations

import ast
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

from core.camera import Camera
from core.object_order import fragments, rasterization
from core.object_order import kernels as raster_kernels
from core.object_order.pipeline import render_raster
from core.scene import Mesh, Scene

#: The stale-cache guard itself runs at import; none of its code is compiled into a kernel.
GUARD = "core.compiling.kernel_cache"


def coverage_counts(triangles_xy, width, height) -> np.ndarray:
    """(H, W) int: how many of the given pixel-space triangles produced a fragment at each pixel.

    Every triangle is its own polygon and all lie at the same depth, so the
    count includes fragments that failed the depth test.
    """
    tris = np.asarray(triangles_xy, dtype=float).reshape(-1, 3, 2)
    xy = tris.reshape(-1, 2)
    corners = np.arange(len(xy)).reshape(-1, 3)
    n = len(tris)
    result = fragments.draw(xy, np.full(len(xy), 0.5), corners, np.arange(n), np.ones((n, 3)), np.ones(n),
                            width, height, (0, 0, 0), record=True)
    return np.bincount(result.fragments.pixel, minlength=width * height).reshape(height, width)


def _edge(a, b, p):
    return (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0])


# An infinitesimal nudge: a pixel centre on an edge belongs to the triangle that
# holds the point a tiny step to its right and a far tinier step down (for a
# horizontal edge: the triangle below it).  This is the top-left rule stated
# geometrically, with no reference to edge directions.  With corners on the
# 1/256 pixel grid and coordinates below 2**7, an edge function that is not zero
# is at least 2**-16 away from it and its slopes are multiples of 2**-8, while
# the nudge moves it by less than 2**-32, so the nudge only decides exact ties.
NUDGE = Fraction(1, 2 ** 40)


def brute_force_coverage(corners, width, height) -> np.ndarray:
    """(H, W) int: 1 where the nudged pixel centre lies strictly inside the triangle (exact)."""
    tri = [tuple(Fraction(float(v)) for v in c) for c in corners]
    out = np.zeros((height, width), int)
    xs, ys = [c[0] for c in tri], [c[1] for c in tri]
    for j in range(max(0, int(min(ys)) - 1), min(height, int(max(ys)) + 2)):
        for i in range(max(0, int(min(xs)) - 1), min(width, int(max(xs)) + 2)):
            p = (i + Fraction(1, 2) + NUDGE, j + Fraction(1, 2) + NUDGE * NUDGE)
            e = [_edge(tri[k], tri[(k + 1) % 3], p) for k in range(3)]
            out[j, i] = all(v > 0 for v in e) or all(v < 0 for v in e)
    return out


def _grid_triangle(rng, low, high):
    """Three corners on the 1/256 pixel grid (what snapping leaves), 30 % of them on pixel centres."""
    tri = rng.integers(low * 256, high * 256, (3, 2)) / 256
    if rng.random() < 0.3:  # corners on pixel centres and edges through them
        tri = np.floor(tri) + 0.5
    return tri


def test_square_of_two_triangles_covers_each_pixel_once_even_with_edges_through_centres():
    # Corners at pixel centres: all four sides and the diagonal run exactly through
    # pixel centres, so only the top-left rule decides who owns them.
    a, b, c, d = (2.5, 2.5), (10.5, 2.5), (10.5, 10.5), (2.5, 10.5)
    counts = coverage_counts([[a, b, c], [a, c, d]], 16, 16)
    expected = np.zeros((16, 16), int)
    expected[2:10, 2:10] = 1  # left and top sides included, right and bottom excluded
    assert np.array_equal(counts, expected)


@pytest.mark.parametrize("seed", range(5))
def test_fan_around_a_vertex_covers_each_pixel_once(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 13))
    hub = np.array([20.5, 15.5])  # on a pixel centre: every spoke passes through it
    angles = np.sort(rng.uniform(0, 2 * np.pi, n))
    rim = hub + 12 * np.stack([np.cos(angles), np.sin(angles)], axis=1)
    fan_around_hub = [[hub, rim[k], rim[(k + 1) % n]] for k in range(n)]
    counts = coverage_counts(fan_around_hub, 40, 32)
    assert counts.max() == 1
    assert counts[15, 20] == 1
    # The same convex polygon triangulated differently (fan from its first rim
    # vertex) covers exactly the same pixels: no gaps inside, same boundary.
    fan_from_rim = [[rim[0], rim[k], rim[k + 1]] for k in range(1, n - 1)]
    other = coverage_counts(fan_from_rim, 40, 32)
    assert other.max() == 1
    assert np.array_equal(counts, other)


@pytest.mark.parametrize("seed", range(4))
def test_mesh_of_random_triangles_is_watertight(seed):
    """A grid of jittered points, triangulated: every pixel centre inside the grid exactly once."""
    rng = np.random.default_rng(seed)
    gx, gy = np.meshgrid(np.linspace(4, 60, 8), np.linspace(4, 44, 6))
    pts = np.stack([gx, gy], axis=-1)
    pts[1:-1, 1:-1] += rng.uniform(-2.5, 2.5, pts[1:-1, 1:-1].shape)
    tris = []
    for j in range(5):
        for i in range(7):
            p00, p10, p01, p11 = pts[j, i], pts[j, i + 1], pts[j + 1, i], pts[j + 1, i + 1]
            tris += [[p00, p10, p11], [p00, p11, p01]] if (i + j) % 2 else [[p00, p10, p01], [p10, p11, p01]]
    tris = np.array(tris)
    tris[1::3] = tris[1::3, ::-1]  # the fill rule does not depend on the winding
    counts = coverage_counts(tris, 64, 48)
    assert counts.max() == 1
    # Every pixel whose centre lies strictly inside the outer rectangle is covered.
    assert counts[4:44, 4:60].min() == 1
    assert counts.sum() == 40 * 56


@pytest.mark.parametrize("seed", range(3))
def test_kernel_and_readable_coverage_equal_exact_point_in_triangle(seed):
    rng = np.random.default_rng(seed)
    width, height = 48, 40
    on_edge = 0
    for _ in range(30):
        tri = _grid_triangle(rng, -8, 56)
        exact = brute_force_coverage(tri, width, height)
        assert np.array_equal(coverage_counts([tri], width, height), exact)
        assert np.array_equal(rasterization.coverage(rasterization.snap(tri), width, height), exact)
        on_edge += tri[0, 0] % 1 == 0.5
    assert on_edge > 0  # the tie cases were exercised


@pytest.mark.parametrize("seed", range(3))
def test_a_pixel_centre_on_a_shared_edge_belongs_to_exactly_one_triangle(seed):
    """Two triangles on either side of one edge through pixel centres: each centre on it
    is drawn once, by the triangle the exact nudge puts it in, in either drawing order."""
    rng = np.random.default_rng(seed)
    for _ in range(10):
        a = np.floor(rng.uniform(2, 30, 2)) + 0.5  # both ends on pixel centres
        b = a + rng.integers(-12, 13, 2)
        if np.all(a == b):
            continue
        normal = np.array([a[1] - b[1], b[0] - a[0]])
        left, right = (a + b) / 2 + normal * 0.7, (a + b) / 2 - normal * 0.7
        first, second = [a, b, left], [b, a, right]
        counts = coverage_counts([first, second], 40, 40)
        other_order = coverage_counts([second, first], 40, 40)
        assert counts.max() == 1 and np.array_equal(counts, other_order)
        assert np.array_equal(counts, brute_force_coverage(first, 40, 40)
                              + brute_force_coverage(second, 40, 40))


def test_is_top_left_agrees_with_coverage_of_edge_pixels():
    # A right triangle with a vertical left edge and a horizontal top edge through centres.
    tri = np.array([[1.5, 1.5], [1.5, 6.5], [6.5, 1.5]])
    cov = rasterization.coverage(rasterization.snap(tri), 10, 10)
    assert cov[1, 1] and cov[5, 1] and cov[1, 5]  # top and left edges owned
    assert not cov[6, 1] and not cov[1, 6]  # the far corners are not


def _exact_plane_depth(xy, z, px, py):
    """Window depth at ``(px, py)`` on the plane through three corners, in exact rationals."""
    (ax, ay), (bx, by), (cx, cy) = ((Fraction(float(u)), Fraction(float(v))) for u, v in xy)
    za, zb, zc = (Fraction(float(v)) for v in z)
    det = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay)
    beta = ((px - ax) * (cy - ay) - (cx - ax) * (py - ay)) / det
    gamma = ((bx - ax) * (py - ay) - (px - ax) * (by - ay)) / det
    return za + beta * (zb - za) + gamma * (zc - za)


def test_fragment_depth_is_the_exact_plane_depth_at_the_pixel_centre():
    """Each fragment's depth against the plane solved in exact rationals.

    Tolerance 1e-13: a triangle of area > 100 px^2 inside a 40 px square is at least
    200 / 57 = 3.5 px high, so its depth (within [0.2, 0.9]) changes by at most
    0.2 per pixel and no term of the evaluation exceeds about 12; a dozen roundings of
    relative size 2**-53 on such terms stay below 2e-14."""
    rng = np.random.default_rng(7)
    worst, checked = 0.0, 0
    for _ in range(30):
        xy = rng.uniform(0, 40, (3, 2))
        if abs(rasterization.edge_function(*xy)) < 200:
            continue
        z = rng.uniform(0.2, 0.9, 3)
        result = fragments.draw(xy, z, np.array([[0, 1, 2]]), np.array([0]), np.ones((1, 3)), np.ones(1),
                                40, 40, (0, 0, 0), record=True)
        rows, cols = np.divmod(result.fragments.pixel, 40)
        for i, j, zf in zip(cols[::5], rows[::5], result.fragments.z[::5], strict=True):
            exact = _exact_plane_depth(xy, z, i + Fraction(1, 2), j + Fraction(1, 2))
            worst = max(worst, abs(float(Fraction(float(zf)) - exact)))
            checked += 1
    assert checked > 200
    assert worst < 1e-13


def test_the_stale_cache_guard_hashes_every_module_the_raster_kernel_compiles_in():
    """numba checks a cached kernel only against its own file; ``SOURCES`` must name the rest."""
    listed = {p.resolve() for p in raster_kernels.SOURCES}
    folder = Path(raster_kernels.__file__).resolve().parent
    root = folder.parents[2]
    for path in sorted(folder.glob("*.py")):
        assert path in listed
        for node in ast.walk(ast.parse(path.read_text())):
            module = (node.module or "") if isinstance(node, ast.ImportFrom) else ""
            if module.startswith("core.") and module != GUARD:
                target = root / (node.module.replace(".", "/") + ".py")
                assert target.resolve() in listed, f"{path.name} compiles in {target}, not in SOURCES"


CAMERAS = [
    Camera(eye=(1.0, 2.0, 6.0), target=(0.0, 0.0, 0.0), fov_y_deg=50, near=0.5, far=40,
           width=120, height=90),
    Camera(eye=(1.0, 2.0, 6.0), target=(0.0, 0.0, 0.0), projection="orthographic", ortho_height=5,
           near=0.5, far=40, width=120, height=90),
]


@pytest.mark.parametrize("cam", CAMERAS, ids=["perspective", "orthographic"])
def test_depth_is_exact_on_the_triangle_plane(cam):
    """Rasterized depth = the analytic distance of the plane along each pixel's ray."""
    corners = np.array([[-3.0, -1.0, -4.0], [3.5, -1.5, 1.0], [-0.5, 2.5, -1.0]])
    scene = Scene(camera=cam, objects=(Mesh(corners, [[0, 1, 2]]),))
    depth = render_raster(scene).depth
    covered = np.isfinite(depth)
    assert covered.mean() > 0.1
    origins, directions = cam.primary_rays()
    normal = np.cross(corners[1] - corners[0], corners[2] - corners[0])
    t = ((corners[0] - origins) @ normal) / (directions @ normal)
    hits = origins + t[..., None] * directions
    analytic = (hits - np.asarray(cam.eye)) @ cam.forward  # distance along the viewing axis
    assert np.allclose(depth[covered], analytic[covered], rtol=1e-9, atol=0)


def test_window_coordinates_map_the_frustum_corners_to_the_image_corners():
    cam = Camera(width=200, height=100)
    clip = (cam.clip_from_world @ np.c_[cam.frustum_corners(), np.ones(8)].T).T
    xy, z = rasterization.window_coordinates(clip, 200, 100)
    assert np.allclose(xy[:4], [[0, 100], [200, 100], [200, 0], [0, 0]])
    assert np.allclose(z, [0, 0, 0, 0, 1, 1, 1, 1])


def test_fan_triangles_keep_polygons_in_drawing_order():
    corners, position = rasterization.fan_triangles(np.array([0, 4, 7, 7]), np.array([2, 1, 0]))
    assert corners.tolist() == [[4, 5, 6], [0, 1, 2], [0, 2, 3]]
    assert position.tolist() == [1, 2, 2]
