"""Primary rays in packets find, ray for ray, the hits that brute force finds.

The packet walk (core.image_order.kernels.bvh_packet) is checked against the
"none" method, which tests every primitive for every ray and shares no
traversal code with it, on meshes, spheres and cameras that make packets fall
apart: image sizes that are no multiple of the packet, an eye inside the mesh,
rays parallel to an axis plane, an orthographic camera.
"""

import math
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from numba import njit

from core import presets_trace
from core.camera import Camera
from core.image_order import flat_layout
from core.image_order.effects_plan import effects_plan
from core.image_order.flat_layout import (
    BOUNDS_TESTS,
    HIT_PRIM,
    HIT_SIZE,
    HIT_T,
    N_COUNTERS,
    OPT_PACKETS,
    PRIM_TESTS,
)
from core.image_order.flat_scene import TraceSettings, kernel_inputs, trace_scene
from core.image_order.intersect_triangle import intersect_triangle, on_shear_axes, ray_shear
from core.image_order.kernels import render
from core.image_order.kernels.bvh_packet import (
    AXIS_FIELDS,
    PACKET_SIZE,
    R_BEST_T,
    R_DIRECTION,
    R_INVERSE,
    R_ORIGIN,
    R_SHEAR,
    R_SHEARED_ORIGIN,
    R_T_MIN,
    RAY_FIELDS,
    _cone,
    _cone_may_enter,
    packet_depth,
    ray_of,
    set_image_point,
    set_primary_rays,
    set_rays,
    shear_rays,
)
from core.image_order.kernels.closest_hit import closest_hit
from core.image_order.kernels.intrinsics.rows import ROW, row_greatest, row_least
from core.image_order.kernels.intrinsics.slabs4 import (
    HALF,
    RAYS,
    slab_half_mask,
    slab_interval4,
    slab_mask4,
    slab_rays_mask,
    slab_test4,
)
from core.image_order.kernels.render import make_scratch
from core.image_order.ray_casting import camera_array, pixel_on_image_plane, primary_ray, view_depth
from core.scene import Material, Mesh, PointLight, Scene, Sphere


def primary_hits(scene: Scene, accel: str, packets: bool | None = True):
    """The primary stage's hits (ny, nx, HIT_SIZE), depths, objects and counters with ``accel``;
    with the BVH, ``packets`` True makes the rays go in packets wherever they can share a walk,
    whether or not packets pay (None: as :meth:`Bvh.packets_pay` decides)."""
    flat = trace_scene(scene)
    structure = flat.geometry.accel(accel)[0]
    k = kernel_inputs(scene, TraceSettings(accel=accel), effects_plan(scene), flat, structure)
    if packets is not None:
        k.opts[OPT_PACKETS] = packets
    w, h = scene.camera.width, scene.camera.height
    hits, depth, objects = np.zeros((h, w, HIT_SIZE)), np.zeros((h, w)), np.zeros((h, w), np.int64)
    color, children = np.zeros((h, w, 3)), np.zeros((h, w, 2, flat_layout.CHILD_SIZE))
    counters = render.render_pass(render.PRIMARY_STAGE, k.cam, np.arange(float(w)), np.arange(float(h)), hits,
                                  depth, objects, color, children, np.zeros((h, w), np.uint8), k.materials,
                                  k.lights, k.opts, k.geo, k.grid, k.bvh, k.bvh_depth, 2, render.no_heat())
    return hits, depth, objects, counters, flat


def assert_same_hits(hits, ref_hits):
    """The same ``t`` at every pixel, and where the primitive is the same, the same barycentric
    weights bit for bit (the walk keeps them from the test that found the hit)."""
    assert np.array_equal(hits[..., HIT_T], ref_hits[..., HIT_T])
    same = hits[..., HIT_PRIM] == ref_hits[..., HIT_PRIM]
    assert np.array_equal(hits[same], ref_hits[same])


def assert_same_as_brute_force(scene: Scene):
    """Every pixel: the same ``t``, depth and object as brute force; the same primitive, or another
    one crossed at that very ``t`` (a ray through an edge two triangles share); the same weights
    where the primitive is the same.  Returns the packet run's counters."""
    hits, depth, objects, counters, flat = primary_hits(scene, "bvh")
    ref_hits, ref_depth, ref_objects, _, _ = primary_hits(scene, "none")
    assert_same_hits(hits, ref_hits)
    assert np.array_equal(depth, ref_depth) and np.array_equal(objects, ref_objects)
    origins, directions = scene.camera.primary_rays()
    rows, n_spheres = flat.geometry.rows, flat.geometry.n_spheres
    for y, x in np.argwhere(hits[..., HIT_PRIM] != ref_hits[..., HIT_PRIM]):
        for prim in (int(hits[y, x, HIT_PRIM]), int(ref_hits[y, x, HIT_PRIM])):
            assert prim >= n_spheres  # spheres never tie
            crossing = intersect_triangle(origins[y, x], directions[y, x], *rows[prim].reshape(3, 3))
            assert crossing.hit and crossing.t == hits[y, x, HIT_T]
    assert (ref_hits[..., HIT_PRIM] >= 0).mean() > 0.2  # the scene is in view
    return counters


BALL = presets_trace.bumpy_ball(3000)
LIGHT = (PointLight((4.0, 8.0, 6.0)),)


def test_a_mesh_seen_in_perspective_at_a_size_no_packet_fits():
    camera = presets_trace.BIG_MESH_CAMERA.replace(width=37, height=23)
    assert_same_as_brute_force(Scene(camera=camera, objects=(BALL,), lights=LIGHT))


def flat_bvh(scene):
    return trace_scene(scene).geometry.accel("bvh")[0]


@pytest.mark.parametrize("width, height", [(160, 120), (48, 36)])
def test_where_packets_are_chosen_they_test_fewer_boxes_and_not_many_more_triangles(width, height):
    # At 48 x 36 a packet covers more than a triangle of this ball, and the render goes ray by ray.
    camera = presets_trace.BIG_MESH_CAMERA.replace(width=width, height=height)
    scene = Scene(camera=camera, objects=(BALL,), lights=LIGHT)
    assert flat_bvh(scene).packets_pay(camera) == (width >= 160)
    _, _, _, packets, flat = primary_hits(scene, "bvh", packets=None)
    structure = flat.geometry.accel("bvh")[0]
    k = kernel_inputs(scene, TraceSettings(accel="bvh"), effects_plan(scene), flat, structure)
    scratch = make_scratch(k.method, flat.geometry.n_prims, 1, k.bvh_depth)
    alone = np.zeros(N_COUNTERS, np.int64)
    origins, directions = camera.primary_rays()
    for o, d in zip(origins.reshape(-1, 3), directions.reshape(-1, 3), strict=True):
        closest_hit(k.method, tuple(map(float, o)), tuple(map(float, d)), 0.0, math.inf, False, k.geo, k.grid,
                    k.bvh, scratch, alone)
    if width >= 160:
        assert packets[BOUNDS_TESTS] < 0.5 * alone[BOUNDS_TESTS]
        # Each ray tests a leaf's primitives only where it enters the leaf's box itself: about as
        # many triangles as alone (the packet may find a far hit first, then a nearer one).
        assert packets[PRIM_TESTS] < 1.15 * alone[PRIM_TESTS]
    else:  # one by one: the same walk as closest_hit's, ray for ray (up to the near plane's start)
        assert abs(packets[BOUNDS_TESTS] - alone[BOUNDS_TESTS]) < 0.02 * alone[BOUNDS_TESTS]


def test_packets_are_chosen_for_the_benchmark_at_640_by_480_and_never_for_an_orthographic_camera():
    ball = presets_trace.bumpy_ball(100_000)
    camera = presets_trace.BIG_MESH_CAMERA.replace(width=640, height=480)
    bvh = flat_bvh(Scene(camera=camera, objects=(ball,), lights=LIGHT))
    assert bvh.packets_pay(camera)
    assert not bvh.packets_pay(camera.replace(width=64, height=48))
    assert not bvh.packets_pay(camera.replace(projection="orthographic"))


def test_an_eye_inside_the_mesh():
    camera = Camera(eye=(0.1, 0.9, 0.2), target=(1.0, 0.5, -1.0), width=30, height=18)
    assert_same_as_brute_force(Scene(camera=camera, objects=(BALL,), lights=LIGHT))


def test_rays_parallel_to_an_axis_plane_and_an_orthographic_camera_go_one_by_one():
    # Looking straight down -z with an odd width: the middle column's rays have d_x = 0 exactly,
    # so their packets cannot share a walk (1/d_x is infinite); the others still do.
    axis = Camera(eye=(0.0, 0.8, 6.0), target=(0.0, 0.8, 0.0), width=33, height=21)
    origins, directions = axis.primary_rays()
    assert np.any(directions[..., 0] == 0.0)
    assert_same_as_brute_force(Scene(camera=axis, objects=(BALL,), lights=LIGHT))
    ortho = axis.replace(projection="orthographic", ortho_height=5.0)
    assert_same_as_brute_force(Scene(camera=ortho, objects=(BALL,), lights=LIGHT))


def test_spheres_and_a_floor_with_a_shared_diagonal():
    scene = presets_trace.mirror_and_glass()
    assert_same_as_brute_force(replace(scene, camera=scene.camera.replace(width=45, height=31)))


@settings(max_examples=25, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), eye=st.tuples(*[st.floats(-4.0, 4.0)] * 3),
       fov=st.floats(10.0, 120.0))
def test_random_triangles_and_spheres_from_random_eyes(seed, eye, fov):
    rng = np.random.default_rng(seed)
    m = Material()
    corners = rng.uniform(-1.5, 1.5, (40, 1, 3)) + rng.normal(scale=0.6, size=(40, 3, 3))
    objects = (Mesh(corners.reshape(-1, 3), np.arange(120).reshape(40, 3), m),
               Sphere(tuple(rng.uniform(-1.0, 1.0, 3)), float(rng.uniform(0.2, 0.8)), m))
    if math.hypot(eye[0], eye[2]) < 0.3:  # looking along the up vector leaves no camera frame
        eye = (eye[0] + 1.0, eye[1], eye[2] + 1.0)
    camera = Camera(eye=eye, target=(0.0, 0.0, 0.0), fov_y_deg=fov, width=19, height=14)
    hits, _, _, _, _ = primary_hits(Scene(camera=camera, objects=objects, lights=LIGHT), "bvh")
    ref_hits, _, _, _, _ = primary_hits(Scene(camera=camera, objects=objects, lights=LIGHT), "none")
    assert_same_hits(hits, ref_hits)


# --- the interval slab test never rejects a box one of its rays enters -------------------------

@njit
def _entries(node, near, far, o, inverses, t_min, t_max):
    """Each ray's own entries into the node's four boxes, and the packet's lower bounds."""
    n = inverses.shape[0]
    own = np.empty((n, 4))
    for r in range(n):
        e = slab_test4(node, near[0], near[1], near[2], far[0], far[1], far[2], o[0], o[1], o[2],
                       inverses[r, 0], inverses[r, 1], inverses[r, 2], t_min, t_max)
        for c in range(4):
            own[r, c] = e[c]
    a = [inverses[:, axis].min() for axis in range(3)]
    b = [inverses[:, axis].max() for axis in range(3)]
    e = slab_interval4(node, near[0], near[1], near[2], far[0], far[1], far[2], o[0], o[1], o[2],
                       a[0], a[1], a[2], b[0], b[1], b[2], t_min, t_max)
    return own, np.array([e[0], e[1], e[2], e[3]])


def _node_and_packet(rng, spread, n, origin_spread=0.0):
    """A random node of four boxes (flat ones too), ``n`` random origins spread by
    ``origin_spread`` about one point and ``n`` directions of one sign per axis spread by
    ``spread``, with the node's rows of the near and far sides."""
    lo = rng.uniform(-3.0, 3.0, (3, 4))
    hi = lo + rng.exponential(1.0, (3, 4)) * rng.choice([0.0, 1e-6, 1.0], (3, 4))
    node = np.concatenate([lo, hi]).astype(np.float32).reshape(-1)
    origins = rng.uniform(-4.0, 4.0, 3) + rng.normal(scale=origin_spread, size=(n, 3))
    base = rng.normal(size=3)
    base[np.abs(base) < 0.05] = 0.05  # keep each axis' sign over the packet
    directions = base + rng.normal(scale=spread, size=(n, 3)) * np.abs(base)
    directions = np.where(np.sign(directions) == np.sign(base), directions, base)
    negative = directions[0] < 0.0
    near = np.array([4 * axis + (12 if negative[axis] else 0) for axis in range(3)])
    far = np.array([4 * axis + (0 if negative[axis] else 12) for axis in range(3)])
    return node, origins, directions, near, far


@settings(max_examples=200, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), spread=st.sampled_from([1e-9, 1e-4, 0.05, 0.5]))
def test_the_packets_bound_lies_below_every_rays_own_entry(seed, spread):
    node, origins, directions, near, far = _node_and_packet(np.random.default_rng(seed), spread, 16)
    inverses = 1.0 / directions
    own, bound = _entries(node, near, far, origins[0], inverses, 0.0, math.inf)
    entered = own < math.inf
    assert np.all(bound[entered.any(axis=0)] < math.inf)
    assert np.all(bound <= np.where(entered, own, math.inf).min(axis=0))


# --- sixteen rays against one box: each bit is that ray's own test --------------------------------

@njit
def _one_box_sixteen_rays(node, near, far, per_ray, box):
    """slab_rays_mask's bits for box ``box`` of the node (slab_half_mask's for either half of the
    rays must be the same), and slab_test4's entry for each ray alone.
    ``per_ray``: the origin and 1 / d per axis, t_min, t_max and the bound on the entry, each
    sixteen rays side by side."""
    mask = slab_rays_mask(node, near[0] + box, near[1] + box, near[2] + box, far[0] + box, far[1] + box,
                          far[2] + box, per_ray, 0, RAYS, 2 * RAYS, 3 * RAYS, 4 * RAYS, 5 * RAYS, 6 * RAYS,
                          7 * RAYS, 8 * RAYS)
    for first in range(0, RAYS, HALF):  # each half of the rays alone must give the same bits
        half = slab_half_mask(node, near[0] + box, near[1] + box, near[2] + box, far[0] + box,
                              far[1] + box, far[2] + box, per_ray, first, RAYS + first, 2 * RAYS + first,
                              3 * RAYS + first, 4 * RAYS + first, 5 * RAYS + first, 6 * RAYS + first,
                              7 * RAYS + first, 8 * RAYS + first)
        if half != (mask >> first) & ((1 << HALF) - 1):
            raise AssertionError("half a packet's bits differ from the whole packet's")
    bits, alone = np.empty(RAYS, np.bool_), np.empty(RAYS)
    for r in range(RAYS):
        o = per_ray[r], per_ray[RAYS + r], per_ray[2 * RAYS + r]
        e = slab_test4(node, near[0], near[1], near[2], far[0], far[1], far[2], o[0], o[1], o[2],
                       per_ray[3 * RAYS + r], per_ray[4 * RAYS + r], per_ray[5 * RAYS + r],
                       per_ray[6 * RAYS + r], per_ray[7 * RAYS + r])
        bits[r], alone[r] = (mask >> r) & 1, e[box]
    return bits, alone


def test_a_packet_is_as_many_rays_as_the_leaf_box_test_has_lanes():
    assert PACKET_SIZE == RAYS


@settings(max_examples=200, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), spread=st.sampled_from([1e-9, 0.05, 0.5]),
       origin_spread=st.sampled_from([0.0, 0.01, 1.0]))
def test_sixteen_rays_against_one_box_enter_where_each_alone_enters_bit_for_bit(seed, spread, origin_spread):
    # Bit r is set where ray r alone enters the box before its t_max (the packet then tests that
    # leaf's triangles for it): every bit must be that lone ray's own slab test, from its own origin.
    # With no bound (a shadow ray's walk) a box entered right at t_max is entered, as a lone shadow
    # ray's mask (slab_mask4) has it.
    rng = np.random.default_rng(seed)
    node, origins, directions, near, far = _node_and_packet(rng, spread, RAYS, origin_spread)
    rows = np.concatenate([origins.T.reshape(-1), 1.0 / directions.T.reshape(-1)])
    t_min = rng.choice([0.0, 0.5, 2.0], RAYS)
    t_max = t_min + rng.choice([0.0, 0.1, 3.0, math.inf], RAYS)  # a closest hit so far, or none
    for box in range(4):
        # Some rays' closest hit so far lies exactly where they enter the box: they must not enter.
        unbounded = np.concatenate([rows, t_min, np.full(2 * RAYS, math.inf)])
        _, entry = _one_box_sixteen_rays(node, near, far, unbounded, box)
        t_max = np.where((rng.random(RAYS) < 0.3) & (entry < math.inf), entry, t_max)
        bits, alone = _one_box_sixteen_rays(node, near, far, np.concatenate([rows, t_min, t_max, t_max]), box)
        assert np.array_equal(bits, alone < t_max)
        any_hit, _ = _one_box_sixteen_rays(node, near, far,
                                           np.concatenate([rows, t_min, t_max, np.full(RAYS, math.inf)]), box)
        assert np.array_equal(any_hit, alone < math.inf)
        # and what a ray enters is where its line is inside the box, within [t_min, t_max)
        for r in np.flatnonzero(bits):
            point = origins[r] + alone[r] * directions[r]
            assert t_min[r] <= alone[r] < t_max[r]
            sides = node.reshape(6, 4)[:, box].astype(float)
            assert np.all(point >= sides[:3] - 1e-6 * (1 + abs(point)))
            assert np.all(point <= sides[3:] + 1e-6 * (1 + abs(point)))


# --- the cone of a packet of shadow rays to one light leaves every box one of its rays enters ------

@njit
def _cone_and_rays(node, near, far, origins, directions, t_max):
    """The packet's cone's boxes (bits), whether the cone serves, and each ray's own mask
    (slab_mask4, its lone walk's test: entering anywhere in ``[0, t_max]``).  The rays come in
    float32, as the batch's do; each ray's own test takes its numbers widened, as the packet does."""
    n = origins.shape[0]
    # The lanes past the packet's rays hold what an earlier packet left there: huge numbers here.
    rays, axes = np.full(RAY_FIELDS * PACKET_SIZE, -1e300), np.empty(AXIS_FIELDS * PACKET_SIZE, np.int64)
    set_rays(rays, axes, origins, directions, np.zeros(n, np.float32), t_max, 0, n)
    cone = _cone(rays, n)
    own = np.empty(n, np.int64)
    for r in range(n):
        o, d = origins[r].astype(np.float64), directions[r].astype(np.float64)
        own[r] = slab_mask4(node, near[0], near[1], near[2], far[0], far[1], far[2], o[0], o[1], o[2],
                            1.0 / d[0], 1.0 / d[1], 1.0 / d[2], 0.0, np.float64(t_max[r]))
    return _cone_may_enter(node, 0, cone), cone[-1], own


def _narrow(*arrays):
    """The arrays in float32, as the batch of shadow rays takes them."""
    return tuple(np.asarray(a, np.float32) for a in arrays)


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), origin_spread=st.sampled_from([1e-6, 0.01, 0.3]),
       light_size=st.sampled_from([0.0, 1e-8, 5e-8]), n=st.sampled_from([RAYS, RAYS - 1, 5, 1]))
def test_the_cone_of_shadow_rays_to_one_light_leaves_every_box_a_ray_enters(seed, origin_spread, light_size,
                                                                             n):
    # The bench's shadow rays: sixteen origins near one point, each ray's direction to the light
    # rounded to float32 and t_max its float32 distance, so that the far ends miss the light by
    # rounding; with ``light_size`` the rays go to points of a small light (relative to its
    # distance), so the far ends lie off ray 0's far end, the cone's apex, by more.  Box 0 is a
    # tiny box around a point of one ray's segment, often its far end, which may lie off the
    # cone's rays by that much.  No box that a ray's own test enters may be left out by the cone,
    # and the cone must serve (else it tests nothing).  A packet at the end of a batch holds
    # fewer rays than sixteen (``n``).
    rng = np.random.default_rng(seed)
    node, origins, _, near, far = _node_and_packet(rng, 0.0, RAYS, origin_spread)
    origins = origins.astype(np.float32).astype(float)  # the batch's numbers are float32's
    distance = rng.choice([1.0, 10.0, 1000.0])
    light = origins[0] + rng.normal(size=3) * distance
    to_light = light + rng.normal(scale=light_size * np.abs(light).max(), size=(RAYS, 3)) - origins
    length = np.linalg.norm(to_light, axis=1)
    directions = (to_light / length[:, None]).astype(np.float32).astype(float)
    t_max = length.astype(np.float32).astype(float)
    if np.any(np.sign(directions) != np.sign(directions[0])) or np.any(directions == 0.0):
        return  # the packet would not share a walk (can_share_walk)
    negative = directions[0] < 0.0
    near = np.array([4 * axis + (12 if negative[axis] else 0) for axis in range(3)])
    far = np.array([4 * axis + (0 if negative[axis] else 12) for axis in range(3)])
    origins, directions, t_max = origins[:n], directions[:n], t_max[:n]
    r = rng.integers(n)
    point = origins[r] + rng.choice([rng.uniform(0.0, 1.0), 1.0]) * t_max[r] * directions[r]
    half = 1e-9 * np.abs(point).max()
    sides = node.reshape(6, 4)
    sides[:3, 0] = np.nextafter((point - half).astype(np.float32), np.float32(-np.inf))
    sides[3:, 0] = np.nextafter((point + half).astype(np.float32), np.float32(np.inf))
    may, serves, own = _cone_and_rays(node, near, far, *_narrow(origins, directions, t_max))
    assert serves
    assert own[r] & 1  # the ray enters the tiny box
    entered = np.bitwise_or.reduce(own)
    assert entered & ~may == 0, (entered, may)


def test_the_cone_leaves_boxes_out_and_does_not_serve_rays_to_two_lights():
    # Rays from around (0, 0, 0) up to a light at (0.5, 10, 0.7): the box around their origins and
    # the one on their way (boxes 0 and 3) are entered, the two off to the side (1 and 2) are left
    # out by the cone too; rays to two lights far apart make no cone.
    node = np.array([[-0.1, 5.0, 4.0, -1.0], [4.0, 4.0, 4.0, 9.0], [-0.1, 5.0, 4.0, -1.0],
                     [0.8, 6.0, 5.0, 1.0], [6.0, 6.0, 6.0, 9.5], [0.9, 6.0, 5.0, 1.0]],
                    np.float32).reshape(-1)
    rng = np.random.default_rng(3)
    origins = rng.normal(scale=0.05, size=(RAYS, 3))
    for lights, serves in (([0.5, 10.0, 0.7],), True), (([0.5, 10.0, 0.7], [0.9, 10.0, 0.2]), False):
        ends = np.array(lights)[np.arange(RAYS) % len(lights)]
        directions = ends - origins
        near, far = np.array([0, 4, 8]), np.array([12, 16, 20])
        may, ok, own = _cone_and_rays(node, near, far, *_narrow(origins, directions, np.ones(RAYS)))
        assert ok == serves
        if serves:
            assert np.bitwise_or.reduce(own) == 0b1001 and may == 0b1001
        else:
            assert may == 0b1111


@njit
def _packet_rows(origins, directions, t_min, t_max, start, n):
    """The packet's rows of origins and directions after set_rays, and its rays read back."""
    rays, axes = np.full(RAY_FIELDS * PACKET_SIZE, np.nan), np.empty(AXIS_FIELDS * PACKET_SIZE, np.int64)
    set_rays(rays, axes, origins, directions, t_min, t_max, start, n)
    back = np.empty((n, 8))
    for r in range(n):
        o, d, _, ray_t_min, ray_t_max = ray_of(rays, axes, r)
        back[r] = o[0], o[1], o[2], d[0], d[1], d[2], ray_t_min, ray_t_max
    return back


@pytest.mark.parametrize("start, n", [(0, RAYS), (37, RAYS), (100 - RAYS, RAYS), (40, 7), (99, 1)])
def test_a_packet_of_shadow_rays_holds_the_batchs_rays_from_its_start(start, n):
    # A whole packet's coordinates are copied three rows at once (rows.deinterleave3), a short
    # one's one by one: either way ray r of the packet is ray start + r of the batch, exactly, its
    # float32 numbers widened to float64 (tiny, huge and subnormal ones among them).
    rng = np.random.default_rng(start)
    origins, directions = rng.normal(size=(100, 3)), rng.normal(size=(100, 3))
    origins[::7, 0], directions[3::11, 1], origins[5::13, 2] = 1e-44, 3e38, -1e-30
    t_min, t_max = rng.uniform(0.0, 1.0, 100), rng.uniform(1.0, 2.0, 100)
    narrow = [a.astype(np.float32) for a in (origins, directions, t_min, t_max)]
    back = _packet_rows(*narrow, start, n)
    expected = np.hstack([narrow[0], narrow[1], narrow[2][:, None], narrow[3][:, None]])[start:start + n]
    assert back.dtype == np.float64 and np.array_equal(back, expected.astype(np.float64))
    assert (back[:, :6] != np.hstack([origins, directions])[start:start + n]).any()  # rounded: float32's


@njit
def _packet_shears(origins, directions, n):
    """Each ray's shear ``(kx, ky, kz, sx, sy, sz)`` and origin on the shear's axes as the packet's
    rows hold them once set_rays made the rays and shear_rays their shear."""
    rays, axes = np.full(RAY_FIELDS * PACKET_SIZE, np.nan), np.full(AXIS_FIELDS * PACKET_SIZE, -9, np.int64)
    set_rays(rays, axes, origins, directions, np.zeros(n, np.float32), np.ones(n, np.float32), 0, n)
    shear_rays(rays, axes, n)
    shears = np.empty((n, 9))
    for r in range(n):
        kx, ky, kz, sx, sy, sz = ray_of(rays, axes, r)[2]
        shears[r, 0], shears[r, 1], shears[r, 2] = kx, ky, kz
        shears[r, 3], shears[r, 4], shears[r, 5] = sx, sy, sz
        for k in range(3):
            shears[r, 6 + k] = rays[(R_SHEARED_ORIGIN + k) * PACKET_SIZE + r]
    return shears


@pytest.mark.parametrize("n", [RAYS, 5])
def test_a_packet_of_shadow_rays_gets_each_rays_own_shear_for_its_triangle_tests(n):
    # set_rays makes what the box tests need; shear_rays, called by the walk at its first leaf,
    # the shear of the watertight triangle test: each ray's must be the scalar test's own
    # (intersect_triangle.ray_shear, and the origin on its axes), bit for bit, whichever
    # component is largest, ties between two (the later axis wins) and negative ones among them.
    rng = np.random.default_rng(n)
    origins = rng.normal(size=(n, 3)).astype(np.float32)
    directions = rng.normal(size=(n, 3)).astype(np.float32)
    directions[0] = (3.0, 0.5, -1.0)
    directions[1] = (-0.25, 2.0, 2.0)
    directions[2] = (1.0, -1.0, 0.5)
    directions[3] = (1e-30, -4.0, 3.0)
    shears = _packet_shears(origins, directions, n)
    for r in range(n):
        d, o = directions[r].astype(np.float64), origins[r].astype(np.float64)
        own = ray_shear(*d)
        assert tuple(shears[r, :6]) == own, r
        assert tuple(shears[r, 6:]) == on_shear_axes(*o, own[2]), r
    assert {int(k) for k in shears[:, 2]} == {0, 1, 2}  # every axis the largest somewhere


def test_a_packet_is_as_many_rays_as_a_row_of_copied_coordinates():
    assert PACKET_SIZE == ROW


@njit
def _row_extremes(numbers, at):
    return row_least(numbers, at), row_greatest(numbers, at)


def _halved(row, keep):
    """Python's own ``min`` or ``max`` (``keep``) of each number and the one half a row on, as the
    cone's rows were halved in memory before: 8, 4, 2 then 1 apart."""
    row = list(row)
    half = len(row) // 2
    while half >= 1:
        row[:half] = [keep(row[r], row[r + half]) for r in range(half)]
        half //= 2
    return row[0]


_ROW_NUMBERS = st.sampled_from([0.0, -0.0, 1.0, -1.0, 2.5, 1e-300, -1e300, math.inf, -math.inf, math.nan])


@settings(max_examples=300, deadline=None)
@given(row=st.lists(st.one_of(_ROW_NUMBERS, st.floats(allow_nan=True)), min_size=ROW, max_size=ROW),
       at=st.integers(0, 3))
def test_a_rows_least_and_greatest_are_those_of_halving_it_bit_for_bit(row, at):
    # The cone's extremes are taken in registers (rows.row_least / row_greatest); they must be the
    # very numbers the halving loops left, signed zeros, ties and NaN included.
    numbers = np.full(ROW + 4, 7.0)
    numbers[at:at + ROW] = row
    least, greatest = _row_extremes(numbers, at)
    for got, keep in ((least, min), (greatest, max)):
        want = _halved(row, keep)
        same_bits = np.array([got]).tobytes() == np.array([want]).tobytes()
        assert same_bits or (math.isnan(got) and math.isnan(want))


# --- a shadow ray's mask of the boxes it enters: the same boxes as the slab test's entries ---------

@njit
def _mask_and_entries(node, near, far, o, inverse, t_min, t_max):
    e = slab_test4(node, near[0], near[1], near[2], far[0], far[1], far[2], o[0], o[1], o[2], inverse[0],
                   inverse[1], inverse[2], t_min, t_max)
    mask = slab_mask4(node, near[0], near[1], near[2], far[0], far[1], far[2], o[0], o[1], o[2], inverse[0],
                      inverse[1], inverse[2], t_min, t_max)
    return mask, np.array([e[0], e[1], e[2], e[3]])


@settings(max_examples=300, deadline=None)
@given(seed=st.integers(0, 2**32 - 1))
def test_a_shadow_rays_mask_names_exactly_the_boxes_it_enters(seed):
    """Rays along axis planes (a zero component: ``1 / d`` infinite) and origins on a box's side
    (``0 * inf``, NaN, which the slab test skips) included."""
    rng = np.random.default_rng(seed)
    node, origins, directions, _, _ = _node_and_packet(rng, 0.5, 1)
    o, d = origins[0], directions[0]
    d[rng.random(3) < 0.3] = rng.choice([0.0, -0.0])
    sides = node.reshape(6, 4).astype(float)
    on_side = rng.random(3) < 0.3
    o = np.where(on_side, sides[rng.integers(0, 6), rng.integers(0, 4)], o)
    with np.errstate(divide="ignore"):
        inverse = 1.0 / d
    negative = np.signbit(inverse)
    near = np.array([4 * axis + (12 if negative[axis] else 0) for axis in range(3)])
    far = np.array([4 * axis + (0 if negative[axis] else 12) for axis in range(3)])
    t_min = rng.choice([0.0, 0.5])
    mask, entries = _mask_and_entries(node, near, far, o, inverse, t_min, t_min + rng.choice([0.1, 3.0, 1e9]))
    assert [bool(mask >> c & 1) for c in range(4)] == list(entries < math.inf)
    for c in np.flatnonzero(entries < math.inf):  # and an entered box holds the point where the ray enters
        point = o + np.nan_to_num(entries[c] * d)
        assert np.all(point >= sides[:3, c] - 1e-6 * (1 + abs(point)))
        assert np.all(point <= sides[3:, c] + 1e-6 * (1 + abs(point)))


@pytest.mark.parametrize("width, height", [(1, 1), (5, 3)])
def test_tiny_images(width, height):
    camera = presets_trace.BIG_MESH_CAMERA.replace(width=width, height=height)
    hits, _, _, _, _ = primary_hits(Scene(camera=camera, objects=(BALL,), lights=LIGHT), "bvh")
    ref_hits, _, _, _, _ = primary_hits(Scene(camera=camera, objects=(BALL,), lights=LIGHT), "none")
    assert_same_hits(hits, ref_hits)


@njit
def _packet_of(cam, xs, ys):
    """The packet's arrays after :func:`set_primary_rays` for the pixels ``xs, ys``."""
    rays, axes = np.zeros(PACKET_SIZE * RAY_FIELDS), np.zeros(PACKET_SIZE * AXIS_FIELDS, np.int64)
    for r in range(len(xs)):
        px, py = pixel_on_image_plane(cam, xs[r], ys[r])
        set_image_point(rays, r, px, py)
    set_primary_rays(cam, rays, axes, len(xs))
    return rays, axes


@settings(max_examples=60, deadline=None)
@given(seed=st.integers(0, 2**32 - 1), n=st.integers(1, PACKET_SIZE), orthographic=st.booleans(),
       eye=st.tuples(*[st.floats(-4.0, 4.0)] * 3))
def test_a_packets_rays_made_side_by_side_are_the_cameras_rays_bit_for_bit(seed, n, orthographic, eye):
    # Made four at a time in vector instructions, each ray must still be the one a lone ray is:
    # the camera's formula, its shear and its origin on the shear's axes, whatever axis is largest;
    # and the depth the image shows for a hit along it must be the lone ray's view depth.
    camera = Camera(eye=eye, target=(0.3, -0.2, 0.1), width=97, height=61, fov_y_deg=70.0,
                    projection="orthographic" if orthographic else "perspective", ortho_height=3.0)
    rng = np.random.default_rng(seed)
    xs, ys = rng.integers(0, camera.width, n).astype(float), rng.integers(0, camera.height, n).astype(float)
    cam = camera_array(camera)
    rays, axes = _packet_of(cam, xs, ys)

    def field(row, r):
        return rays[row * PACKET_SIZE + r]

    for r in range(n):
        o, d, t_min, t_max = primary_ray(cam, xs[r], ys[r])
        kx, ky, kz, sx, sy, sz = ray_shear(*d)
        assert [axes[a * PACKET_SIZE + r] for a in range(3)] == [kx, ky, kz]
        assert [field(R_ORIGIN + a, r) for a in range(3)] == list(o)
        assert [field(R_DIRECTION + a, r) for a in range(3)] == list(d)
        assert [field(R_INVERSE + a, r) for a in range(3)] == [1.0 / c for c in d]
        assert [field(R_SHEAR + a, r) for a in range(3)] == [sx, sy, sz]
        assert [field(R_SHEARED_ORIGIN + a, r) for a in range(3)] == [o[kx], o[ky], o[kz]]
        assert (field(R_T_MIN, r), field(R_BEST_T, r)) == (t_min, t_max)
        for t in (t_min, 0.37 * t_min + 0.63 * t_max, t_max):
            assert packet_depth(rays, r, t) == view_depth(cam, o, d, t)


@pytest.mark.parametrize("v", [(1.0, 2.0, 3.0), (-5.0, 0.5, 0.25), (0.0, -0.0, 7.0)])
def test_a_vector_on_the_shear_axes_is_its_components_in_the_shears_order(v):
    for kz in range(3):
        kx, ky = (kz + 1) % 3, (kz + 2) % 3
        assert on_shear_axes(*v, kz) == (v[kx], v[ky], v[kz])
