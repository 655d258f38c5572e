"""Every acceleration method finds exactly the hits of brute force; only the work differs."""

import math
from dataclasses import replace

import numpy as np
import pytest

from core import shapes
from core.camera import Camera
from core.image_order.bounding_spheres import bounding_spheres
from core.image_order.effects_plan import effects_plan
from core.image_order.flat_layout import (
    ACCEL_CODES,
    BOUNDS_TESTS,
    CELLS,
    GEO_N_SPHERES,
    GEO_ROWS,
    N_COUNTERS,
    PRIM_TESTS,
    ROW_CENTER,
    ROW_RADIUS,
    SHADOW,
)
from core.image_order.flat_scene import TraceSettings, kernel_inputs, trace_scene
from core.image_order.grid_of_cuboids import cells_on_ray
from core.image_order.intersect_sphere import intersect_sphere
from core.image_order.intersect_triangle import intersect_triangle
from core.image_order.kernels.bvh_build import from_leaf_group
from core.image_order.kernels.closest_hit import closest_hit
from core.image_order.kernels.render import make_scratch
from core.image_order.kernels.shadow_rays import trace_shadow_rays
from core.presets_trace import bumpy_ball
from core.scene import Material, Scene, Sphere

METHODS = ACCEL_CODES  # ("none", "spheres", "grid", "grid+spheres", "bvh")


def mixed_scene() -> Scene:
    """Analytic spheres, closed meshes, an open quad and a non-convex prism, some overlapping."""
    m = Material()
    return Scene(objects=(
        shapes.quad((0.0, 0.0, 0.0), 10.0, m),
        shapes.box((-1.5, 0.8, -1.0), 1.6, m),
        shapes.cone((1.0, 0.0, 1.0), 1.0, 2.2, segments=24, material=m),
        Sphere((2.5, 0.6, -1.5), 0.6, m),
        Sphere((-0.4, 1.4, 1.2), 0.9, m),
        shapes.uv_sphere((0.0, 2.5, -2.5), 1.0, rings=8, segments=12, material=m),
        shapes.notched_prism((-3.0, 0.0, 2.0), (1.5, 1.0, 1.5), 0.7, m),
    ))


def random_rays(rng, n, spread=6.0):
    """Rays from all around the scene, mostly aimed into it, some from inside objects."""
    origins = rng.normal(size=(n, 3)) * spread + [0.0, 1.0, 0.0]
    targets = rng.normal(size=(n, 3)) * 1.5 + [0.0, 1.0, 0.0]
    directions = targets - origins
    directions /= np.linalg.norm(directions, axis=1, keepdims=True)
    return origins, directions


class Query:
    """closest_hit from Python with one method's structures."""

    def __init__(self, scene, method):
        flat = trace_scene(scene)
        structure, _, _ = flat.geometry.accel(method)
        self.k = kernel_inputs(scene, TraceSettings(accel=method), effects_plan(scene), flat, structure)
        self.scratch = make_scratch(self.k.method, flat.geometry.n_prims, len(scene.objects),
                                    self.k.bvh_depth)
        self.counters = np.zeros(N_COUNTERS, np.int64)

    def __call__(self, o, d, t_max=math.inf, any_hit=False):
        k = self.k
        return closest_hit(k.method, tuple(map(float, o)), tuple(map(float, d)), 0.0, float(t_max), any_hit,
                           k.geo, k.grid, k.bvh, self.scratch, self.counters)


@pytest.fixture(scope="module")
def scene():
    return mixed_scene()


def test_every_method_finds_the_same_closest_hits_as_brute_force(scene):
    rng = np.random.default_rng(2024)
    origins, directions = random_rays(rng, 1500)
    queries = {m: Query(scene, m) for m in METHODS}
    hits = 0
    for o, d in zip(origins, directions, strict=True):
        reference = queries["none"](o, d)
        hits += reference[0] >= 0
        for method in METHODS[1:]:
            assert queries[method](o, d) == reference, method
    assert hits > 700


def test_every_method_agrees_on_shadow_rays(scene):
    rng = np.random.default_rng(99)
    origins, directions = random_rays(rng, 1000)
    lengths = rng.uniform(0.5, 12.0, size=len(origins))
    queries = {m: Query(scene, m) for m in METHODS}
    blocked = 0
    for o, d, length in zip(origins, directions, lengths, strict=True):
        reference = queries["none"](o, d, length, any_hit=False)[0] >= 0
        blocked += reference
        for method in METHODS:
            assert (queries[method](o, d, length, any_hit=True)[0] >= 0) == reference, method
    assert 200 < blocked < 900


def test_a_batch_of_shadow_rays_on_all_cores_is_blocked_where_brute_force_is_blocked(scene):
    """The bench's shadow-ray kernel: each ray blocked exactly where brute force finds a crossing,
    with the blocker and ``t`` of the BVH's any-hit walk for that ray alone.  The kernel takes the
    rays' numbers in float32, as the bench makes them."""
    rng = np.random.default_rng(5)
    origins, directions = random_rays(rng, 800)
    lengths = rng.uniform(0.5, 12.0, size=len(origins))
    origins, directions, lengths = (a.astype(np.float32) for a in (origins, directions, lengths))
    bvh, brute = Query(scene, "bvh"), Query(scene, "none")
    blockers, blocker_t = np.full(len(origins), -1, np.int64), np.full(len(origins), np.inf)
    counters = trace_shadow_rays(origins, directions, np.zeros(len(origins), np.float32), lengths, bvh.k.bvh,
                                 bvh.k.geo[GEO_N_SPHERES], bvh.k.bvh_depth, 2, blockers, blocker_t)
    for r, (o, d, length) in enumerate(zip(origins, directions, lengths, strict=True)):
        assert (blockers[r] >= 0) == (brute(o, d, length)[0] >= 0), r
        alone = bvh(o, d, length, any_hit=True)
        assert (blockers[r], blocker_t[r]) == alone[:2], r
    assert counters[SHADOW] == len(origins)
    assert 200 < (blockers >= 0).sum() < 700



def test_a_batch_of_shadow_rays_writes_the_answers_of_the_blocked_rays_only(scene):
    """The caller fills the answers first (the bench: -1 and ``inf``, none); the kernel writes each
    blocked ray's blocker and ``t`` and leaves an unblocked ray's two numbers as they were, as
    Embree's ``rtcOccluded16`` sets ``tfar`` only where a ray is blocked."""
    rng = np.random.default_rng(11)
    origins, directions = random_rays(rng, 400)
    lengths = rng.uniform(0.5, 12.0, size=len(origins))
    origins, directions, lengths = (a.astype(np.float32) for a in (origins, directions, lengths))
    bvh, brute = Query(scene, "bvh"), Query(scene, "none")
    blockers, blocker_t = np.full(len(origins), -7, np.int64), np.full(len(origins), 123.0)
    trace_shadow_rays(origins, directions, np.zeros(len(origins), np.float32), lengths, bvh.k.bvh,
                      bvh.k.geo[GEO_N_SPHERES], bvh.k.bvh_depth, 2, blockers, blocker_t)
    blocked = 0
    for r, (o, d, length) in enumerate(zip(origins, directions, lengths, strict=True)):
        if brute(o, d, length)[0] >= 0:
            blocked += 1
            assert (blockers[r], blocker_t[r]) == bvh(o, d, length, any_hit=True)[:2], r
        else:
            assert (blockers[r], blocker_t[r]) == (-7, 123.0), r
    assert 50 < blocked < len(origins) - 50

def _shadow_rays_of_the_view(scene, light, width, height):
    """From every hit of a 4 x 4-pixel tile's rays (tile after tile, as the bench orders them)
    towards ``light``: origins just before the hit, directions to the light, ``t < 1``."""
    camera = Camera(eye=(7.0, 6.0, 9.0), target=(0.0, 0.8, 0.0), width=width, height=height)
    eyes, directions = camera.primary_rays()
    tiles = [(j, i) for y in range(0, height, 4) for x in range(0, width, 4)
             for j in range(y, y + 4) for i in range(x, x + 4)]
    brute = Query(scene, "none")
    origins = []
    for j, i in tiles:
        prim, t, *_ = brute(eyes[j, i], directions[j, i])
        if prim >= 0:
            origins.append(eyes[j, i] + t * (1.0 - 1e-9) * directions[j, i])
    origins = np.array(origins)
    return origins, np.asarray(light, float) - origins


_LIGHTS = [(-6.0, 5.0, 3.0), (-5.0, 3.0, -2.0), (0.3, 9.0, 0.2)]


@pytest.mark.parametrize("light", [*_LIGHTS, "each ray another light", "a light at infinity",
                                   "every other ray without an end"])
def test_shadow_rays_of_neighbouring_hits_in_packets_find_the_blocker_each_finds_alone(scene, light):
    """The bench's shadow rays: sixteen neighbouring hits' rays to one light walk the tree as one
    packet (their origins differ); each ray must get the blocker and ``t`` of its own walk alone,
    bit for bit, and be blocked exactly where brute force finds a crossing before the light.
    The light above the middle makes packets whose directions straddle an axis plane, which go
    one by one.  Rays to three lights near one another in turn share walks too (their
    directions' signs agree), with no cone of rays to one light to pass over boxes
    (bvh_packet._cone)."""
    origins, directions = _shadow_rays_of_the_view(scene, light if light in _LIGHTS else _LIGHTS[0], 40, 32)
    n = len(origins)
    t_max = np.ones(n)
    if light == "each ray another light":
        lights = np.asarray(_LIGHTS[0]) + [[0.0, 0.0, 0.0], [0.5, 1.0, -0.5], [-0.5, -0.5, 0.5]]
        directions = lights[np.arange(n) % 3] - origins
    elif light == "a light at infinity":  # one direction, no end
        directions = np.tile(np.asarray(_LIGHTS[0]) / np.linalg.norm(_LIGHTS[0]), (n, 1))
        t_max = np.full(n, math.inf)
    elif light == "every other ray without an end":  # a packet's far ends, some infinitely far
        t_max[1::2] = math.inf
    origins, directions, t_max = (a.astype(np.float32) for a in (origins, directions, t_max))
    bvh, brute = Query(scene, "bvh"), Query(scene, "none")
    blockers, blocker_t = np.full(n, -1, np.int64), np.full(n, np.inf)
    counters = trace_shadow_rays(origins, directions, np.zeros(n, np.float32), t_max, bvh.k.bvh,
                                 bvh.k.geo[GEO_N_SPHERES], bvh.k.bvh_depth, 2, blockers, blocker_t)
    spheres_blocking = 0
    for r in range(n):
        alone = bvh(origins[r], directions[r], t_max[r], any_hit=True)
        assert (blockers[r], blocker_t[r]) == alone[:2], r
        assert (blockers[r] >= 0) == (brute(origins[r], directions[r], t_max[r])[0] >= 0), r
        spheres_blocking += 0 <= blockers[r] < bvh.k.geo[GEO_N_SPHERES]
    # most packets share a walk: the rays of a packet point one way on every axis
    signs = np.sign(directions[:n - n % 16]).reshape(-1, 16, 3)
    assert (signs == signs[:, :1]).all(axis=(1, 2)).mean() > 0.5
    assert counters[SHADOW] == n
    assert 0.1 * n < (blockers >= 0).sum() < 0.9 * n and spheres_blocking > 0


def test_a_shadow_rays_blocker_is_reported_where_the_ray_crosses_it(scene):
    """Any-hit gives the blocker's own crossing: the lecture's worked sphere and triangle tests agree."""
    rng = np.random.default_rng(7)
    origins, directions = random_rays(rng, 600)
    lengths = rng.uniform(0.5, 12.0, size=len(origins))
    queries = {m: Query(scene, m) for m in METHODS}
    checked = {"sphere": 0, "triangle": 0}
    for o, d, length in zip(origins, directions, lengths, strict=True):
        for method, query in queries.items():
            prim, t, *_ = query(o, d, length, any_hit=True)
            if prim < 0:
                continue
            rows, n_spheres = query.k.geo[GEO_ROWS], query.k.geo[GEO_N_SPHERES]
            if prim < n_spheres:
                worked = intersect_sphere(o, d, rows[prim, ROW_CENTER:ROW_CENTER + 3], rows[prim, ROW_RADIUS])
                roots = [r for r in (worked.t_near, worked.t_far) if r is not None and r >= 0.0]
                checked["sphere"] += 1
            else:
                roots = [intersect_triangle(o, d, *rows[prim].reshape(3, 3)).t]
                checked["triangle"] += 1
            assert 0.0 <= t < length, method
            assert any(math.isclose(t, r, rel_tol=1e-12) for r in roots if r is not None), method
    assert min(checked.values()) > 100, checked


def test_shadow_rays_grazing_edges_and_corners_are_blocked_exactly_when_a_closest_hit_lies_before_the_light(
        scene):
    """Any-hit (stop at the first blocker) against closest hit, on rays aimed at edges and corners.

    The light sits before, just before, just after or beyond the aimed-at
    point, so the segment's end falls on both sides of a hit as well.  A
    blocker found by any-hit lies on the segment, and any-hit never does more
    primitive tests than the closest-hit search it cuts short.  The BVH's
    any-hit walk is the exception on blocked rays: it takes the children unsorted
    (``bvh_traverse.any_child``), so it may test a farther leaf before the
    blocker; on a ray that nothing blocks both walks test exactly the leaves whose
    boxes the segment enters.
    """
    rng = np.random.default_rng(31)
    corners = np.concatenate([ob.corners for ob in scene.objects if hasattr(ob, "corners")])
    queries = {m: Query(scene, m) for m in METHODS}
    blocked = 0
    rays = 1500
    for _ in range(rays):
        o = rng.normal(size=3) * 6.0 + [0.0, 1.0, 0.0]
        a, b, _ = corners[rng.integers(len(corners))][rng.permutation(3)]
        target = a if rng.random() < 0.3 else a + rng.random() * (b - a)
        d = target - o
        aimed = float(np.linalg.norm(d))
        d /= aimed
        length = aimed * rng.choice([0.5, 1.0 - 1e-9, 1.0 + 1e-9, 3.0])
        reference = queries["none"](o, d, length)[0] >= 0
        blocked += reference
        for method, query in queries.items():
            before = query.counters[PRIM_TESTS]
            closest = query(o, d, length)
            closest_tests = query.counters[PRIM_TESTS] - before
            before = query.counters[PRIM_TESTS]
            first = query(o, d, length, any_hit=True)
            any_tests = query.counters[PRIM_TESTS] - before
            assert (first[0] >= 0) == (closest[0] >= 0) == reference, method
            assert first[1] < length if reference else first[1] == math.inf, method
            if method == "bvh":
                assert any_tests == closest_tests or reference, method
            else:
                assert any_tests <= closest_tests, method
    assert 0.3 * rays < blocked < 0.9 * rays


def test_grid_and_bvh_do_far_fewer_tests_on_a_big_mesh():
    scene = Scene(objects=(bumpy_ball(20_000),))
    rng = np.random.default_rng(1)
    origins, directions = random_rays(rng, 200, spread=5.0)
    per_ray = {}
    for method in METHODS:
        q = Query(scene, method)
        results = [q(o, d) for o, d in zip(origins, directions, strict=True)]
        per_ray[method] = q.counters / len(origins)
        if method == "none":
            reference = results
        assert results == reference, method
    n = 2 * 100 * 99  # triangles of the ball
    assert per_ray["none"][PRIM_TESTS] == n
    assert per_ray["spheres"][BOUNDS_TESTS] == 1
    assert per_ray["grid"][PRIM_TESTS] < n / 50 and per_ray["grid"][CELLS] > 1
    assert per_ray["grid+spheres"][PRIM_TESTS] <= per_ray["grid"][PRIM_TESTS]
    assert per_ray["bvh"][PRIM_TESTS] < n / 500 and per_ray["bvh"][BOUNDS_TESTS] < 200


def test_a_ray_that_passes_far_from_the_spheres_tests_no_sphere():
    """Two balls resting on a large floor: a ray that meets the floor far from both tests the
    floor's two triangles and no sphere, though the floor's box holds the balls."""
    m = Material()
    scene = Scene(objects=(shapes.quad((0.0, 0.0, 0.0), 100.0, m), Sphere((-1.0, 1.0, 0.0), 1.0, m),
                           Sphere((1.5, 0.5, 0.0), 0.5, m)))
    query = Query(scene, "bvh")
    for x, z in [(30.0, 30.0), (-40.0, 10.0), (20.0, -45.0)]:
        query.counters[:] = 0
        prim, t, *_ = query((x, 5.0, z), (0.0, -1.0, 0.0))
        assert prim >= 2 and t == pytest.approx(5.0, abs=1e-12)  # the floor (primitives 0, 1: the balls)
        assert query.counters[PRIM_TESTS] == 2
    query.counters[:] = 0
    prim, t, *_ = query((-1.0, 5.0, 0.0), (0.0, -1.0, 0.0))
    assert prim == 0 and t == pytest.approx(3.0, abs=1e-12)  # the top of the first ball
    assert query.counters[PRIM_TESTS] <= 3


def test_bvh_rays_aimed_at_edges_and_vertices_from_inside_a_closed_mesh_always_hit():
    """Watertight through the BVH: its four-at-a-time triangle test must defer exactly these rays."""
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings=12, segments=16, material=Material())
    rng = np.random.default_rng(5)
    bumpy = replace(ball, vertices=ball.vertices * (1 + 0.05 * rng.standard_normal((len(ball.vertices), 1))))
    query = Query(Scene(objects=(bumpy,)), "bvh")
    corners = bumpy.vertices[bumpy.triangles]
    for _ in range(400):
        o = rng.normal(size=3) * 0.2
        tri = corners[rng.integers(len(corners))]
        target = tri[0] if rng.random() < 0.5 else (tri[0] + tri[1]) / 2
        assert query(o, target - o)[0] >= 0


def test_bounding_spheres_contain_their_meshes(scene):
    for b in bounding_spheres(scene):
        obj = scene.objects[b.object_index]
        if b.exact:
            assert (tuple(b.center), b.radius) == (obj.center, obj.radius)
        else:
            assert np.linalg.norm(obj.vertices - b.center, axis=1).max() <= b.radius


def test_bvh_boxes_contain_what_is_below_them(scene):
    geometry = trace_scene(scene).geometry
    bvh, _, _ = geometry.accel("bvh")
    nodes = bvh.nodes
    assert sorted(bvh.order.tolist()) == list(range(geometry.n_prims))
    for i, node in enumerate(nodes):
        lo, hi = node[:3], node[3:6]
        if node[7] > 0:
            prims = bvh.order[int(node[6]):int(node[6] + node[7])]
            assert np.all(geometry.lo[prims] >= lo) and np.all(geometry.hi[prims] <= hi), i
        else:
            for child in (int(node[6]), int(node[6]) + 1):
                assert np.all(nodes[child, :3] >= lo) and np.all(nodes[child, 3:6] <= hi), i
    levels = bvh.levels()
    assert levels[0] == 0 and levels.max() == bvh.depth - 1
    assert len(bvh.node_boxes(1)) == 2


def test_wide_bvh_reaches_every_primitive_once_inside_its_float32_boxes(scene):
    """The four-wide float32 form the traversal reads holds the same primitives, in boxes rounded outwards,
    and each leaf's triangle groups hold exactly its triangles, which its parent's row names as well
    (group and count, for a shadow ray to test them without reading the leaf's own row)."""
    geometry = trace_scene(scene).geometry
    bvh, _, _ = geometry.accel("bvh")
    boxes = bvh.wide[:, :24].astype(np.float64).reshape(-1, 2, 3, 4)  # node, lo/hi, axis, child
    refs = bvh.wide.view(np.int32)[:, 24:28]
    named = bvh.wide.view(np.int32)[:, 28:32]  # per child: the leaf's group and count, or 0
    reached = []
    pending = [0]
    while pending:
        node = pending.pop()
        for c in range(4):
            lo, hi = boxes[node, 0, :, c], boxes[node, 1, :, c]
            if np.all(lo > hi):  # an unused slot
                continue
            ref = int(refs[node, c])
            if ref >= 0:
                assert named[node, c] == 0
                child = boxes[ref]
                used = ~np.all(child[0] > child[1], axis=0)
                assert np.all(child[0][:, used] >= lo[:, None]) and np.all(child[1][:, used] <= hi[:, None])
                pending.append(ref)
                continue
            first, count, group = bvh.leaves[~ref]
            prims = bvh.order[first:first + count]
            assert 0 < count <= 4  # a leaf is at most one group: one vector test
            assert np.all(geometry.lo[prims] >= lo) and np.all(geometry.hi[prims] <= hi)
            reached.extend(prims.tolist())
            if np.any(prims < geometry.n_spheres):
                assert count == 1 and group == -1  # a sphere's leaf holds it alone
                assert named[node, c] == 0
                continue
            assert from_leaf_group(named[node, c]) == (group, count)
            # Lanes past the count repeat the last triangle, so a test of all four finds no other crossing.
            padded = bvh.groups[group].reshape(3, 3, 4).transpose(2, 0, 1).reshape(4, 9)
            assert np.array_equal(padded, geometry.rows[prims[np.minimum(np.arange(4), count - 1)]])
            # groups[g] holds corner, axis, lane: triangle j of the leaf is lane j % 4 of group j // 4.
            lanes = bvh.groups[group:group + (count + 3) // 4].reshape(-1, 3, 3, 4).transpose(0, 3, 1, 2)
            assert np.array_equal(lanes.reshape(-1, 9)[:count], geometry.rows[prims])
    assert sorted(reached) == list(range(geometry.n_prims))
    assert len(bvh.wide) < len(bvh.nodes) / 2


def test_grid_lists_every_primitive_in_the_cells_it_overlaps(scene):
    geometry = trace_scene(scene).geometry
    grid, _, _ = geometry.accel("grid")
    nx, ny, nz = grid.resolution
    assert grid.cell_counts().shape == (nz, ny, nx)
    for p in range(geometry.n_prims):
        first = np.floor((geometry.lo[p] - grid.lo) / grid.cell_size).clip(0, grid.resolution - 1)
        last = np.floor((geometry.hi[p] - grid.lo) / grid.cell_size).clip(0, grid.resolution - 1)
        for i, j, k in [first.astype(int), last.astype(int)]:
            assert p in grid.prims_in_cell(i, j, k)


def test_cells_on_ray_walk_neighbour_to_neighbour_along_the_ray(scene):
    grid, _, _ = trace_scene(scene).geometry.accel("grid")
    rng = np.random.default_rng(4)
    origins, directions = random_rays(rng, 300)
    walked = 0
    for o, d in zip(origins, directions, strict=True):
        cells = cells_on_ray(grid, o, d)
        if len(cells) == 0:
            continue
        walked += 1
        steps = np.abs(np.diff(cells, axis=0)).sum(axis=1)
        assert np.all(steps == 1)  # each step crosses one wall
        assert np.all(cells >= 0) and np.all(cells < grid.resolution)
        for box in grid.cell_boxes(cells):  # the ray really passes through each cell (slab test)
            with np.errstate(divide="ignore", invalid="ignore"):
                t0, t1 = (box[0] - o) / d, (box[1] - o) / d
            near = np.nanmax(np.minimum(t0, t1))
            far = np.nanmin(np.maximum(t0, t1))
            assert near <= far + 1e-9 and far >= -1e-9
    assert walked > 100
