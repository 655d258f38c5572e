"""Primary rays through the BVH in packets: one walk of the tree for 4 x 4 neighbouring pixels.

The rays of a perspective camera all start at the eye, and neighbouring
pixels' rays point almost the same way, so they enter almost the same boxes.
A packet walks the tree once for all of them.  At an inner node one
*interval* slab test
(:func:`~core.image_order.kernels.intrinsics.slabs4.slab_interval4`) asks
whether any ray of the packet can enter each child box: per axis it uses the
smallest and largest ``1 / d`` of the packet, and because rounding is
monotonic it never rejects a box that one of the rays would enter by its own
test.  At a leaf, every ray tests the leaf's box on its own, all sixteen in one
vector test
(:func:`~core.image_order.kernels.intrinsics.slabs4.slab_rays_mask`, lane for
lane the very test a lone ray makes), and each ray that enters tests the
leaf's primitives with exactly the arithmetic of a lone ray
(:func:`~core.image_order.kernels.bvh_traverse.test_leaf`).  The test gives
a mask, and a loop visits only the rays it names, two at a time: both test the
leaf's triangles in one vector test of eight lanes
(:func:`~core.image_order.kernels.intrinsics.triangle4.triangle_test4x2`,
each lane rounding as the ray's own test); the leaf's group and count come from
its parent's row, already read for the box, and the leaf's own row only to name
a crossing.  The packet's bound on
its rays' closest hits is worked out again only after a leaf that brought one
of them closer.  On the 1,000,000-triangle benchmark a packet meets about 22
leaf boxes and each ray enters about 6 of them: with a branch per ray on
whether it entered, and the bound worked out after every leaf, the primary
stage took 109 ms of one thread's CPU, now 95 (100,000 triangles: 34 -> 32).

So each ray finds the crossing that it would find alone, bit for bit: it
tests every leaf that it would test alone.  What the packet saves is the
walk.  On the 100,000-triangle benchmark at 640 x 480 a packet visits about
12 nodes where a lone ray visits about 9: one interval test serves 16 rays.
The rays' own tests of the leaf boxes are what a packet adds, and they are
cheap, sixteen rays at once.  Without them a ray would test the primitives of
every leaf any ray of its packet enters (at 64 x 48, 17 times the
triangles); with them it tests about as many as alone (7.3 triangles per
ray on the benchmark, 7.2 alone; 9.4 when the rays tested the boxes one by
one and, to save those tests, stopped where most of them entered anyway).
Where two triangles are crossed at the very same ``t`` (a ray through their
shared edge), either is the answer; a packet may test them in
another order than a lone ray and name the other one.

A packet needs one origin and one sign of ``d`` per axis for all its rays,
with no direction parallel to an axis plane (``1 / d`` finite).  Where that
fails (an orthographic camera, whose rays start side by side on the near
plane; a packet straddling the plane where one component of ``d`` changes
sign), its rays go through the tree one at a time
(:func:`~core.image_order.kernels.bvh_traverse.bvh_closest`).

Shadow rays go in packets too (:func:`packet_occluded`, for the bench's batch of
shadow rays, :mod:`core.image_order.kernels.shadow_rays`): sixteen rays from
neighbouring hits to one light, whose origins differ.  Their walk tests every
node's four boxes with each ray on its own, so each ray meets exactly the nodes
and leaves of its lone walk, in the same order, and names the same blocker; the
packet reads each node once for all of them.  How a node's boxes are tested
depends on how many of the rays are still in it (:func:`_children_entering`):
deep in the tree a few rays test them one by one, higher up all of them at
once, sixteen lanes a box, and only the boxes that the cone from the light to
the rays' origins may enter (:func:`_cone`).

A packet is kept in two small per-thread arrays: ``rays`` (RAY_FIELDS x
PACKET_SIZE floats) and ``axes`` (AXIS_FIELDS x PACKET_SIZE integers), with
the rows named below: one number of all the packet's rays side by side, so
that four rays' numbers load as one vector.
"""

from __future__ import annotations

import math

from core.image_order.flat_layout import BOUNDS_TESTS, PRIM_TESTS
from core.image_order.intersect_triangle import on_shear_axes, ray_shear
from core.image_order.kernels.bvh_build import (
    LEAF_SIZE,
    WIDE_GROUPS,
    WIDE_REFS,
    WIDE_SIZE,
    WIDTH,
    from_leaf_group,
)
from core.image_order.kernels.bvh_traverse import (
    NO_WEIGHTS,
    closest_in_group,
    from_stack_entry,
    hit_record,
    near_and_far_rows,
    nearest_child,
    prefetch_child,
    stack_entry,
    test_leaf,
)
from core.image_order.kernels.intrinsics.bits import bit_count, lowest_bit
from core.image_order.kernels.intrinsics.rows import deinterleave3, row_greatest, row_least
from core.image_order.kernels.intrinsics.slabs4 import (
    HALF,
    slab_cone_mask4,
    slab_half_mask,
    slab_interval4,
    slab_mask4,
    slab_rays_mask,
)
from core.image_order.kernels.intrinsics.triangle4 import GROUP_SIZE, triangle_test4, triangle_test4x2
from core.image_order.kernels.intrinsics.unchecked import load_at, store_at
from core.image_order.kernels.jit import jit, jit_inline
from core.image_order.ray_casting import primary_ray_through, view_depth_of_ray

#: Pixels of a packet: rows and columns.
PACKET_ROWS = PACKET_COLS = 4
PACKET_SIZE = PACKET_ROWS * PACKET_COLS  # the lanes of slabs4.slab_rays_mask (RAYS)
# Rows of the packet's rays: origin, 1 / d, t_min, the closest hit so far (t_max to start), the
# shear of the watertight triangle test, the origin on its axes, the direction, the point on the
# image plane a primary ray goes through (ray_casting.pixel_on_image_plane), the weights of the
# closest hit so far (test_leaf's, set only once there is a hit), the view depth's start and step
# along the ray
# (ray_casting.view_depth_of_ray), and inf (an any-hit walk's bound on where a box is entered);
# then the shadow packets' cone's work rows (_cone): each ray's origin from the apex (twice: one
# row for its least, whose lanes past the packet's rays hold inf, one for its greatest, -inf),
# its far end's distance from the apex and the size of its numbers.
(R_ORIGIN, R_INVERSE, R_T_MIN, R_BEST_T, R_SHEAR, R_SHEARED_ORIGIN, R_DIRECTION, R_IMAGE_POINT, R_WEIGHTS,
 R_DEPTH, R_NO_BOUND, R_CONE_LOW, R_CONE_HIGH, R_CONE_SPREAD, R_CONE_SIZE) = (
    0, 3, 6, 7, 8, 11, 14, 17, 19, 23, 25, 26, 29, 32, 33)
RAY_FIELDS = 34
# ... and the integer rows: the shear's axes kx, ky, kz, the closest primitive in leaf order (-1: none).
A_AXES, A_BEST_K = 0, 3
AXIS_FIELDS = 4


@jit_inline
def _at(field, r):
    """Flat index of number ``field`` of ray ``r`` in a packet's array."""
    return field * PACKET_SIZE + r


@jit_inline
def set_ray(rays, axes, r, o, d, t_min, t_max):
    """Make ``o + t d`` (``t_min <= t < t_max``) ray ``r`` of the packet."""
    for a in range(3):
        store_at(rays, _at(R_ORIGIN + a, r), o[a])
        store_at(rays, _at(R_DIRECTION + a, r), d[a])
    store_at(rays, _at(R_T_MIN, r), t_min)
    store_at(rays, _at(R_BEST_T, r), t_max)
    store_at(rays, _at(R_NO_BOUND, r), math.inf)
    _derive(rays, axes, r, o, d)


@jit_inline
def _derive(rays, axes, r, o, d):
    """What ray ``r`` of the packet, from ``o`` along ``d``, needs besides: ``1 / d`` and no closest
    hit yet (:func:`_derive_inverse`), the shear of the watertight triangle test and the origin on
    its axes (:func:`_derive_shear`)."""
    inverse = _derive_inverse(rays, axes, r, d)
    _derive_shear(rays, axes, r, o, d, inverse)


@jit_inline
def _derive_inverse(rays, axes, r, d):
    """Ray ``r``'s ``1 / d``, what its box tests need, and no closest hit yet; returns ``1 / d``."""
    inverse = (1.0 / d[0], 1.0 / d[1], 1.0 / d[2])
    for a in range(3):
        store_at(rays, _at(R_INVERSE + a, r), inverse[a])
    store_at(axes, _at(A_BEST_K, r), -1)
    return inverse


@jit_inline
def _derive_shear(rays, axes, r, o, d, inverse):
    """Ray ``r``'s shear of the watertight triangle test and its origin on the shear's axes, what
    its triangle tests need (``inverse``: its ``1 / d``)."""
    kx, ky, kz, sx, sy, _ = ray_shear(d[0], d[1], d[2])
    sz = on_shear_axes(inverse[0], inverse[1], inverse[2], kz)[2]  # the shear's 1 / d_kz, not divided again
    okx, oky, okz = on_shear_axes(o[0], o[1], o[2], kz)
    store_at(rays, _at(R_SHEAR, r), sx)
    store_at(rays, _at(R_SHEAR + 1, r), sy)
    store_at(rays, _at(R_SHEAR + 2, r), sz)
    store_at(rays, _at(R_SHEARED_ORIGIN, r), okx)
    store_at(rays, _at(R_SHEARED_ORIGIN + 1, r), oky)
    store_at(rays, _at(R_SHEARED_ORIGIN + 2, r), okz)
    store_at(axes, _at(A_AXES, r), kx)
    store_at(axes, _at(A_AXES + 1, r), ky)
    store_at(axes, _at(A_AXES + 2, r), kz)


@jit_inline
def set_rays(rays, axes, origins, directions, t_min, t_max, start, n):
    """Make rays ``0 .. n-1`` of the packet rays ``start .. start + n - 1`` of the arrays
    (:func:`set_ray`; ``origins`` and ``directions`` (N, 3), ``t_min`` and ``t_max`` (N,), all
    float32, each number widened to float64).

    Their numbers are copied in first (a whole packet's coordinates three rows at once,
    :func:`~core.image_order.kernels.intrinsics.rows.deinterleave3`); then what follows from
    them is worked out in one loop with no branch that reads and writes only the packet's rows,
    four rays per vector instruction, as :func:`set_primary_rays` does, where the loop that read
    each ray's numbers from the arrays and made it went one ray at a time.

    Only what the box tests need is made here, ``1 / d`` (three divisions a ray); the shear of
    the triangle tests (two divisions more) waits for :func:`shear_rays`, which a walk calls
    when it first reaches a leaf.  On the lecture scene's shadow rays a packet visits 1.4 nodes
    and 0.5 leaves on average, and the divisions were about a fifth of the time (perf): with
    the shear made here the bench's batch took 1.03-1.07 of its time now on the lecture scene,
    1.03 on the 10,000-triangle ball, 1.01 on the 100,000 and 1.00 on the 1,000,000 (one and
    two threads, the two ways alternating in one process, the blockers the same bit for bit).
    """
    if n == PACKET_SIZE:
        deinterleave3(origins, start, rays, _at(R_ORIGIN, 0), _at(R_ORIGIN + 1, 0), _at(R_ORIGIN + 2, 0))
        deinterleave3(directions, start, rays, _at(R_DIRECTION, 0), _at(R_DIRECTION + 1, 0),
                      _at(R_DIRECTION + 2, 0))
    else:
        for r in range(n):
            for a in range(3):
                store_at(rays, _at(R_ORIGIN + a, r), origins[start + r, a])
                store_at(rays, _at(R_DIRECTION + a, r), directions[start + r, a])
    for r in range(n):
        store_at(rays, _at(R_T_MIN, r), t_min[start + r])
        store_at(rays, _at(R_BEST_T, r), t_max[start + r])
        store_at(rays, _at(R_NO_BOUND, r), math.inf)
    for r in range(n):
        _derive_inverse(rays, axes, r, _three(rays, R_DIRECTION, r))


@jit
def shear_rays(rays, axes, n):
    """Make the shear of rays ``0 .. n-1`` of a packet from :func:`set_rays` (:func:`_derive_shear`,
    the numbers :func:`set_ray` makes, bit for bit), before their first triangle test: in one loop
    with no branch, four rays per vector instruction.

    A call, once a packet, not inlined: inlined where the walk reaches its first leaf, it made
    the walk's own loop larger, and on the bumpy balls, whose packets all reach leaves, the
    batch took 1.00-1.03 of the time it took with the shear made in :func:`set_rays`; as a
    call, 0.97-1.00.
    """
    for r in range(n):
        _derive_shear(rays, axes, r, _three(rays, R_ORIGIN, r), _three(rays, R_DIRECTION, r),
                      _three(rays, R_INVERSE, r))


@jit_inline
def set_image_point(rays, r, px, py):
    """Ray ``r`` of the packet goes through the point ``(px, py)`` of the image plane, a pixel's
    :func:`~core.image_order.ray_casting.pixel_on_image_plane` (:func:`set_primary_rays`)."""
    store_at(rays, _at(R_IMAGE_POINT, r), px)
    store_at(rays, _at(R_IMAGE_POINT + 1, r), py)


@jit_inline
def set_primary_rays(cam, rays, axes, n):
    """Make rays ``0 .. n-1`` of the packet the camera's primary rays through their points on the
    image plane (:func:`set_image_point`).

    One loop over the rays, with no branch and no index that differs from ray to ray
    (:func:`~core.image_order.intersect_triangle.on_shear_axes`): the compiler makes it four rays
    per vector instruction, and the ten divisions and the square root a ray costs (its
    direction, near and far, ``1 / d`` and the shear) go four at a time.  Each lane rounds as
    the scalar code does, so the rays are the same bit for bit.  The view depth of the rays'
    hits is prepared here too (:func:`packet_depth`).
    """
    for r in range(n):
        px, py = load_at(rays, _at(R_IMAGE_POINT, r)), load_at(rays, _at(R_IMAGE_POINT + 1, r))
        o, d, t_min, t_max = primary_ray_through(cam, px, py)
        set_ray(rays, axes, r, o, d, t_min, t_max)
        start, step = view_depth_of_ray(cam, o, d)
        store_at(rays, _at(R_DEPTH, r), start)
        store_at(rays, _at(R_DEPTH + 1, r), step)


@jit_inline
def ray_of(rays, axes, r):
    """Ray ``r`` of the packet: ``(o, d, shear, t_min, t_max)`` (``t_max``: its closest hit so far)."""
    shear = _three(axes, A_AXES, r) + _three(rays, R_SHEAR, r)
    return (_three(rays, R_ORIGIN, r), _three(rays, R_DIRECTION, r), shear, load_at(rays, _at(R_T_MIN, r)),
            load_at(rays, _at(R_BEST_T, r)))


@jit_inline
def _three(array, field, r):
    """Numbers ``field``, ``field + 1`` and ``field + 2`` of ray ``r``."""
    return load_at(array, _at(field, r)), load_at(array, _at(field + 1, r)), load_at(array, _at(field + 2, r))


@jit_inline
def _four(array, field, r):
    """Numbers ``field`` to ``field + 3`` of ray ``r``."""
    return _three(array, field, r) + (load_at(array, _at(field + 3, r)),)


@jit_inline
def can_share_walk(rays, n, one_origin):
    """Whether rays ``0 .. n-1`` have one sign of ``d`` per axis and finite ``1 / d``, and with
    ``one_origin`` also one origin (:func:`packet_closest`; :func:`packet_occluded` needs none).

    All the rays are looked at, with no early way out: the loop then has no branch, and the
    compiler makes it four rays per vector instruction (a packet almost always can share).  On
    the benchmark's 100,000 triangles the test ray by ray, stopping at the first that could not
    share, took 14-15 of the about 280 cycles a primary ray costs, this one 9-10 (both counts
    include 5-6 cycles of the counter's own cost and of the rays' divisions still finishing).
    """
    shared = True
    for a in range(3):
        origin, negative = rays[_at(R_ORIGIN + a, 0)], rays[_at(R_INVERSE + a, 0)] < 0.0
        for r in range(n):
            inverse = load_at(rays, _at(R_INVERSE + a, r))
            same_origin = load_at(rays, _at(R_ORIGIN + a, r)) == origin
            shared &= ((abs(inverse) < math.inf) & (same_origin | (not one_origin))
                       & ((inverse < 0.0) == negative))
    return shared


@jit_inline
def _test_ray(rays, axes, r):
    """Ray ``r`` as :func:`~core.image_order.kernels.intrinsics.triangle4.triangle_test4x2` takes it."""
    return (_three(axes, A_AXES, r) + _three(rays, R_SHEARED_ORIGIN, r) + _three(rays, R_SHEAR, r)
            + (load_at(rays, _at(R_T_MIN, r)), load_at(rays, _at(R_BEST_T, r))))


@jit_inline
def _take(crossings, rays, axes, r, rows, leaves, leaf, count):
    """Keep ray ``r``'s closest crossing among ``crossings``, its vector test of the ``count``
    triangles of the leaf whose row is at ``leaf`` (:func:`_keep`); whether it came nearer."""
    if crossings[4] == 0:  # nothing in the group comes nearer (padding lanes repeat the last)
        return False
    first = load_at(leaves, leaf)
    o, d, shear, t_min, before = ray_of(rays, axes, r)
    best_t, best_k, best_w = closest_in_group(crossings, rows, o, shear, first, count, t_min, before, -1,
                                              NO_WEIGHTS)
    return _keep(rays, axes, r, before, best_t, best_k, best_w)


@jit_inline
def _keep(rays, axes, r, before, best_t, best_k, best_w):
    """Store ray ``r``'s closest hit if it came nearer than ``before``; whether it did."""
    if best_t < before:
        store_at(rays, _at(R_BEST_T, r), best_t)
        store_at(axes, _at(A_BEST_K, r), best_k)
        for a in range(4):
            store_at(rays, _at(R_WEIGHTS + a, r), best_w[a])
        return True
    return False


@jit_inline
def packet_closest(n, rays, axes, bvh, n_spheres, stack, stack_t, counters):
    """Find the closest crossing of each of the packet's rays ``0 .. n-1`` (:func:`can_share_walk`
    holds); each ray's ``R_BEST_T`` and ``A_BEST_K`` then name it (``A_BEST_K`` -1: none).

    ``stack`` (int64) and ``stack_t`` (float64) hold ``3 * depth + 2`` entries, as for one ray.
    """
    wide, refs, leaves, groups, order, rows = bvh
    ox, oy, oz = _three(rays, R_ORIGIN, 0)
    ax, ay, az = _three(rays, R_INVERSE, 0)
    bx, by, bz = ax, ay, az
    t_low, t_high = rays[_at(R_T_MIN, 0)], rays[_at(R_BEST_T, 0)]
    for r in range(1, n):
        ix, iy, iz = _three(rays, R_INVERSE, r)
        ax, bx = min(ax, ix), max(bx, ix)
        ay, by = min(ay, iy), max(by, iy)
        az, bz = min(az, iz), max(bz, iz)
        t_low, t_high = min(t_low, rays[_at(R_T_MIN, r)]), max(t_high, rays[_at(R_BEST_T, r)])
    nx, ny, nz, fx, fy, fz = near_and_far_rows(ax, ay, az)  # all the rays' signs agree
    boxes = 0
    tests = 0
    top = 0
    node = 0
    enter = t_low
    slot = -1  # the node's box in its parent: parent * WIDTH + child (-1: the root has none)
    while True:
        if enter < t_high:  # some ray's closest hit so far lies beyond where the packet enters
            if node >= 0:
                at = node * WIDE_SIZE
                entries = slab_interval4(wide, at + nx, at + ny, at + nz, at + fx, at + fy, at + fz, ox, oy,
                                         oz, ax, ay, az, bx, by, bz, t_low, t_high)
                boxes += WIDTH
                near, near_t, top = nearest_child(entries, refs, at, stack, stack_t, top, node * WIDTH)
                for c in range(WIDTH):
                    if c != near and entries[c] < math.inf:
                        prefetch_child(wide, refs, groups, at, c)
                if near_t < math.inf:
                    node, enter, slot = load_at(refs, at + WIDE_REFS + near), near_t, node * WIDTH + near
                    continue
            else:
                p, leaf, group, count = _leaf_below(refs, leaves, node, slot)
                # only the rays that enter the leaf's box test what it holds
                entered = _rays_entering(wide, p, nx, ny, nz, fx, fy, fz, rays, R_BEST_T) & ((1 << n) - 1)
                boxes += n
                closer, leaf_tests = _leaf_for_rays(entered, rays, axes, bvh, n_spheres, leaf, group, count)
                tests += leaf_tests
                if closer != 0:  # the packet's farthest closest hit so far may have come nearer
                    t_high = load_at(rays, _at(R_BEST_T, 0))
                    for r in range(1, n):
                        t_high = max(t_high, load_at(rays, _at(R_BEST_T, r)))
        if top == 0:
            break
        top, node, slot, enter = _pop(stack, stack_t, top)
    counters[BOUNDS_TESTS] += boxes
    counters[PRIM_TESTS] += tests


@jit_inline
def _pop(stack, beside, top):
    """Take the last entry off a packet's stack of ``top`` entries: ``(top, node, slot, kept)``,
    ``kept`` what ``beside`` holds with it (where the packet enters the node, or the rays that
    entered it)."""
    top -= 1
    node, slot = from_stack_entry(load_at(stack, top))
    return top, node, slot, load_at(beside, top)


@jit_inline
def _leaf_below(refs, leaves, node, slot):
    """The leaf ``node`` (< 0) whose box is at ``slot`` of its parent (``parent * WIDTH +
    child``; the root is never a leaf): ``(p, leaf, group, count)``, the flat index of its box in
    the parent's row, the index of its own row, its group of triangles (-1: an analytic sphere's
    leaf) and how many primitives it holds.  A leaf of triangles is known from its parent's row,
    already read for its box: its own row is read only to name a crossing (:func:`_take`)."""
    leaf = LEAF_SIZE * ~node
    p = (slot // WIDTH) * WIDE_SIZE + slot % WIDTH
    packed = load_at(refs, p + WIDE_GROUPS)
    if packed != 0:
        group, count = from_leaf_group(packed)
    else:
        count, group = load_at(leaves, leaf + 1), load_at(leaves, leaf + 2)
    return p, leaf, group, count


@jit_inline
def _leaf_for_rays(entered, rays, axes, bvh, n_spheres, leaf, group, count):
    """The rays ``entered`` (a mask) test what the leaf whose row is at ``leaf`` holds (``group``
    and ``count``: its triangle group, -1 for an analytic sphere's leaf): ``(closer, tests)``, the
    mask of the rays whose closest hit came nearer (:func:`_keep`) and the primitive tests made.

    The rays go two at a time through a leaf of triangles, one vector test of eight lanes
    (:func:`~core.image_order.kernels.intrinsics.triangle4.triangle_test4x2`), where the two have
    one shear's axes, as neighbouring rays almost always have: the group's numbers are then
    loaded once for both.  A ray whose next one has other axes goes alone (four lanes), and a
    sphere's leaf is tested by each ray alone.  Each ray's arithmetic is that of its lone walk.
    (A pair test of two rays on other axes, a second copy of the test in the walk's loop, served
    so few pairs that without it the walks took less time: the bench's shadow rays 0.97-0.99 of
    it at 10,000 and 100,000 triangles and on the lecture scene, its primary rays 0.98 at
    100,000, the primary stage of both Whitted frames 0.94-0.96; one thread, alternating with the
    code before in one process, both orders; the same hits and images bit for bit.)
    """
    wide, refs, leaves, groups, order, rows = bvh
    closer = 0
    tests = 0
    while entered != 0:
        r = lowest_bit(entered)
        entered &= entered - 1
        if group < 0:  # an analytic sphere's leaf, tested one by one
            tests += count
            o, d, shear, t_min, before = ray_of(rays, axes, r)
            okx, oky, okz = _three(rays, R_SHEARED_ORIGIN, r)
            # The closest hit so far goes in as none: test_leaf gives it back only when the leaf
            # has nothing closer, and then nothing is stored.
            first = load_at(leaves, leaf)
            best_t, best_k, best_w = test_leaf(groups, rows, order, n_spheres, first, count, group, o, d,
                                               shear, okx, oky, okz, t_min, before, -1, NO_WEIGHTS)
            if _keep(rays, axes, r, before, best_t, best_k, best_w):
                closer |= 1 << r
        elif entered != 0 and _three(axes, A_AXES, r) == _three(axes, A_AXES, lowest_bit(entered)):
            # two rays on one shear's axes in one test (the leaf holds one group)
            q = lowest_bit(entered)
            entered &= entered - 1
            tests += 2 * count
            ray_r, ray_q = _test_ray(rays, axes, r), _test_ray(rays, axes, q)
            c = triangle_test4x2(groups, group * GROUP_SIZE, ray_r, ray_r[0:3] + ray_q[3:])
            if _take(c[0:5], rays, axes, r, rows, leaves, leaf, count):
                closer |= 1 << r
            if _take(c[5:10], rays, axes, q, rows, leaves, leaf, count):
                closer |= 1 << q
        else:
            tests += count
            kx, ky, kz, okx, oky, okz, sx, sy, sz, t_min, before = _test_ray(rays, axes, r)
            c = triangle_test4(groups, group * GROUP_SIZE, kx, ky, kz, okx, oky, okz, sx, sy, sz, t_min,
                               before)
            if _take(c, rays, axes, r, rows, leaves, leaf, count):
                closer |= 1 << r
    return closer, tests


@jit_inline
def _rays_entering(wide, p, nx, ny, nz, fx, fy, fz, rays, below):
    """Which of the packet's rays enter the box whose slot in its parent's row is at ``p``, each
    by its own test (:func:`~core.image_order.kernels.intrinsics.slabs4.slab_rays_mask`), with
    an entry below their numbers ``below`` (``R_BEST_T``, or ``R_NO_BOUND``)."""
    return slab_rays_mask(wide, p + nx, p + ny, p + nz, p + fx, p + fy, p + fz, rays, _at(R_ORIGIN, 0),
                          _at(R_ORIGIN + 1, 0), _at(R_ORIGIN + 2, 0), _at(R_INVERSE, 0),
                          _at(R_INVERSE + 1, 0), _at(R_INVERSE + 2, 0), _at(R_T_MIN, 0), _at(R_BEST_T, 0),
                          _at(below, 0))


#: At most this many rays in a node: each tests the node's four boxes on its own (one vector test
#: of four lanes a ray) rather than all sixteen lanes a box.  On the bench's 100,000-triangle
#: ball a packet's node holds 2.3 rays on average where it holds so few, 13 where it holds more.
_FEW_RAYS = 4


@jit_inline
def _children_entering(wide, at, sides, rays, inside, cone):
    """Which of the rays ``inside`` (a mask) enter each of the four boxes of the node at ``at``:
    four masks, each bit from that ray's own test, lane for lane its lone walk's
    (:func:`~core.image_order.kernels.intrinsics.slabs4.slab_mask4`).  ``sides``: the rows of
    the boxes' near and far sides (:func:`~core.image_order.kernels.bvh_traverse.near_and_far_rows`),
    ``cone``: the packet's :func:`_cone`.

    The tests cost what the rays inside need.  A few rays (:data:`_FEW_RAYS`, deep in the tree)
    each test the four boxes on their own.  Rays all in one half of the packet test each box
    eight lanes at a time
    (:func:`~core.image_order.kernels.intrinsics.slabs4.slab_half_mask`); else sixteen, and only
    the boxes that the packet's cone may enter (:func:`_cone_may_enter`): on the bench's rays a
    node higher up is entered by 1.5 to 2.4 of its four children and the cone lets 1.6 to 2.8
    through (10,000 to 1,000,000 triangles).
    """
    nx, ny, nz, fx, fy, fz = sides
    if bit_count(inside) <= _FEW_RAYS:
        return _each_ray_entering(wide, at, sides, rays, inside)
    if inside >> HALF == 0 or inside & ((1 << HALF) - 1) == 0:
        first = 0 if inside >> HALF == 0 else HALF
        return (_half_entering(wide, at, sides, rays, first) << first & inside,
                _half_entering(wide, at + 1, sides, rays, first) << first & inside,
                _half_entering(wide, at + 2, sides, rays, first) << first & inside,
                _half_entering(wide, at + 3, sides, rays, first) << first & inside)
    may = _cone_may_enter(wide, at, cone)
    return (_rays_entering(wide, at, nx, ny, nz, fx, fy, fz, rays, R_NO_BOUND) & inside if may & 1 else 0,
            _rays_entering(wide, at + 1, nx, ny, nz, fx, fy, fz, rays, R_NO_BOUND) & inside if may & 2 else 0,
            _rays_entering(wide, at + 2, nx, ny, nz, fx, fy, fz, rays, R_NO_BOUND) & inside if may & 4 else 0,
            _rays_entering(wide, at + 3, nx, ny, nz, fx, fy, fz, rays, R_NO_BOUND) & inside if may & 8 else 0)


@jit_inline
def _each_ray_entering(wide, at, sides, rays, inside):
    """:func:`_children_entering` ray by ray: each ray ``inside`` tests the four boxes as it does
    alone."""
    nx, ny, nz, fx, fy, fz = sides
    c0 = c1 = c2 = c3 = 0
    todo = inside
    while todo != 0:
        r = lowest_bit(todo)
        todo &= todo - 1
        ox, oy, oz = _three(rays, R_ORIGIN, r)
        ix, iy, iz = _three(rays, R_INVERSE, r)
        entered = slab_mask4(wide, at + nx, at + ny, at + nz, at + fx, at + fy, at + fz, ox, oy, oz, ix, iy,
                             iz, load_at(rays, _at(R_T_MIN, r)), load_at(rays, _at(R_BEST_T, r)))
        c0 |= (entered & 1) << r
        c1 |= ((entered >> 1) & 1) << r
        c2 |= ((entered >> 2) & 1) << r
        c3 |= ((entered >> 3) & 1) << r
    return c0, c1, c2, c3


@jit_inline
def _half_entering(wide, p, sides, rays, first):
    """:func:`_rays_entering` (no bound on the entry) for the ``HALF`` rays from ray ``first`` on,
    their bits from bit 0."""
    nx, ny, nz, fx, fy, fz = sides
    return slab_half_mask(wide, p + nx, p + ny, p + nz, p + fx, p + fy, p + fz, rays, _at(R_ORIGIN, first),
                          _at(R_ORIGIN + 1, first), _at(R_ORIGIN + 2, first), _at(R_INVERSE, first),
                          _at(R_INVERSE + 1, first), _at(R_INVERSE + 2, first), _at(R_T_MIN, first),
                          _at(R_BEST_T, first), _at(R_NO_BOUND, first))


#: How far the cone's boxes grow (:func:`_cone`) beyond the spread of the rays' far ends,
#: relative to the size of the rays' numbers: far more than all the rounding of both slab tests
#: (a few times 2**-53 of it).
_CONE_SLACK = 2.0**-40
#: The cone's rays end where the packet's rays start, at ``t = 1``: a little more to be safe.
_CONE_T = 1.0 + 2.0**-30


@jit_inline
def _cone(rays, n):
    """The cone of rays from one point, the far end of ray 0 (the light), to the origins of the
    packet's rays ``0 .. n-1``, as :func:`_cone_may_enter` takes it; its last number says
    whether it serves: every ray's far end is finite and lies within a small distance of the
    apex (the rays go to one light), and the cone's ``1 / d`` are finite and of one sign per axis.

    The cone holds every ray's segment: a point of a segment lies within the far ends' spread of
    the cone's ray to that origin.  So the cone's boxes grow by that spread, and by
    :data:`_CONE_SLACK` of the numbers' size for the rounding of both slab tests, which is why a
    ray whose own rounded test enters a box always leaves that box to the cone.
    """
    t_0 = load_at(rays, _at(R_BEST_T, 0))
    ox, oy, oz = _three(rays, R_ORIGIN, 0)
    dx, dy, dz = _three(rays, R_DIRECTION, 0)
    ex, ey, ez = ox + t_0 * dx, oy + t_0 * dy, oz + t_0 * dz
    apex = (ex, ey, ez)
    # Each ray's numbers side by side in the work rows, in a loop with no branch (four rays per
    # vector instruction; a lane past the packet's rays holds a number that changes no extreme),
    # then each row's least or greatest by halving it in registers.  The loop that carried the
    # extremes from ray to ray, and divided once a ray, waited on each step: on the lecture
    # scene's shadow rays it took a fifth of the time.
    for r in range(PACKET_SIZE):
        used = r < n
        t = load_at(rays, _at(R_BEST_T, r))
        spread = size = 0.0
        for a in range(3):
            o = load_at(rays, _at(R_ORIGIN + a, r))
            end = o + t * load_at(rays, _at(R_DIRECTION + a, r))
            store_at(rays, _at(R_CONE_LOW + a, r), o - apex[a] if used else math.inf)
            store_at(rays, _at(R_CONE_HIGH + a, r), o - apex[a] if used else -math.inf)
            spread, size = max(spread, abs(end - apex[a])), max(size, abs(o) + abs(end))
        store_at(rays, _at(R_CONE_SPREAD, r), spread if used else 0.0)
        store_at(rays, _at(R_CONE_SIZE, r), (size if abs(t) < math.inf else math.inf) if used else 0.0)
    low, high = _at(R_CONE_LOW, 0), _at(R_CONE_HIGH, 0)
    near_x, near_y, near_z = (row_least(rays, low), row_least(rays, low + PACKET_SIZE),
                              row_least(rays, low + 2 * PACKET_SIZE))
    far_x, far_y, far_z = (row_greatest(rays, high), row_greatest(rays, high + PACKET_SIZE),
                           row_greatest(rays, high + 2 * PACKET_SIZE))
    spread = row_greatest(rays, _at(R_CONE_SPREAD, 0))
    size = max(row_greatest(rays, _at(R_CONE_SIZE, 0)), abs(ex), abs(ey), abs(ez))
    ax, bx, ok_x = _cone_axis(near_x, far_x)
    ay, by, ok_y = _cone_axis(near_y, far_y)
    az, bz, ok_z = _cone_axis(near_z, far_z)
    ok = ok_x and ok_y and ok_z and spread <= _CONE_SLACK * 2.0**20 * size and size < math.inf
    margin = spread * (1.0 + 2.0**-20) + _CONE_SLACK * size
    # The near sides' distances are taken from the apex moved away from them, the far sides'
    # from the apex moved towards them: the boxes grow by the margin on every side.
    px, py, pz = math.copysign(margin, ax), math.copysign(margin, ay), math.copysign(margin, az)
    return (near_and_far_rows(ax, ay, az), (ex + px, ey + py, ez + pz), (ex - px, ey - py, ez - pz),
            (ax, ay, az), (bx, by, bz), ok)


@jit_inline
def _cone_axis(low, high):
    """The least and greatest ``1 / d`` of the cone's rays on one axis, ``d`` the rays' components
    from ``low`` to ``high``, and whether they are finite and of one sign.

    Where all the components have one sign, ``1 / d`` falls as ``d`` grows, and rounding keeps
    that order: the least of the rays' rounded ``1 / d`` is ``1 / high`` rounded, the greatest
    ``1 / low``, so two divisions give what one a ray gave.
    """
    a, b = 1.0 / high, 1.0 / low
    ok = (low > 0.0 or high < 0.0) and abs(a) < math.inf and abs(b) < math.inf
    return a, b, ok


@jit_inline
def _cone_may_enter(wide, at, cone):
    """Which of the four boxes of the node at ``at`` the packet's :func:`_cone` may enter (bit
    ``c`` for box ``c``; all four where the cone does not serve)."""
    (nx, ny, nz, fx, fy, fz), near, far, low, high, ok = cone
    if not ok:
        return (1 << WIDTH) - 1
    return slab_cone_mask4(wide, at + nx, at + ny, at + nz, at + fx, at + fy, at + fz, near[0], near[1],
                           near[2], far[0], far[1], far[2], low[0], low[1], low[2], high[0], high[1], high[2],
                           0.0, _CONE_T)


@jit_inline
def packet_occluded(n, rays, axes, bvh, n_spheres, stack, stack_rays, counters):
    """Whether each of the packet's shadow rays ``0 .. n-1`` crosses anything (rays that
    :func:`can_share_walk` without one origin); a blocked ray's ``A_BEST_K`` and ``R_BEST_T`` then
    name its blocker (:func:`packet_blocker`).

    The packet walks the tree as a lone shadow ray does
    (:func:`~core.image_order.kernels.bvh_traverse.bvh_occluded`): the children entered in the
    order of their slots, nothing sorted.  Its rays start at different points (the hits of
    neighbouring pixels, all going to one light).  At a node every ray that entered it and is not
    yet blocked tests the four children's boxes on its own (:func:`_children_entering`, lane for
    lane the lone ray's test, in vectors as wide as the rays inside need); a child is visited with
    the rays that enter it, and a leaf's triangles are tested by those rays, two at a time, as in
    :func:`packet_closest`.  So each ray meets the very nodes and leaves it would meet alone, in
    the same order, and names the same blocker; the packet reads each node once for all its rays.
    The walk ends when every ray is blocked.  The rays come from :func:`set_rays`, their shear
    not yet made: the walk makes it (:func:`shear_rays`) at its first leaf.  ``stack`` and
    ``stack_rays`` (int64, the rays that entered each pushed node) hold ``3 * depth + 2`` entries.
    """
    wide, refs, leaves, groups, order, rows = bvh
    sides = near_and_far_rows(*_three(rays, R_INVERSE, 0))  # all the rays' signs agree
    cone = _cone(rays, n)
    boxes = 0
    tests = 0
    top = 0
    node, slot = 0, -1
    unblocked = (1 << n) - 1
    inside = unblocked  # the rays that entered the node's box
    sheared = False  # set_rays left the shear to be made (shear_rays) at the first leaf
    while True:
        inside &= unblocked
        if inside != 0:
            if node >= 0:
                at = node * WIDE_SIZE
                boxes += WIDTH * bit_count(inside)
                children = _children_entering(wide, at, sides, rays, inside, cone)
                near, near_rays = -1, 0
                for c in range(WIDTH - 1, -1, -1):  # pushed so that they come out in slot order
                    entered = children[c]
                    if entered != 0:
                        if near >= 0:
                            store_at(stack, top, stack_entry(load_at(refs, at + WIDE_REFS + near),
                                                             node * WIDTH + near))
                            store_at(stack_rays, top, near_rays)
                            top += 1
                        near, near_rays = c, entered
                if near >= 0:
                    node, slot, inside = load_at(refs, at + WIDE_REFS + near), node * WIDTH + near, near_rays
                    continue
            else:
                if not sheared:
                    shear_rays(rays, axes, n)
                    sheared = True
                _, leaf, group, count = _leaf_below(refs, leaves, node, slot)
                blocked, leaf_tests = _leaf_for_rays(inside, rays, axes, bvh, n_spheres, leaf, group, count)
                tests += leaf_tests
                unblocked &= ~blocked
                if unblocked == 0:
                    break
        if top == 0:
            break
        top, node, slot, inside = _pop(stack, stack_rays, top)
    counters[BOUNDS_TESTS] += boxes
    counters[PRIM_TESTS] += tests


@jit_inline
def packet_blocker(rays, axes, r, bvh):
    """Ray ``r``'s blocker after :func:`packet_occluded`: ``(prim, t)``, as
    :func:`~core.image_order.kernels.bvh_traverse.bvh_occluded` gives it for the ray alone
    (``(-1, inf)``: none)."""
    k = load_at(axes, _at(A_BEST_K, r))
    return (bvh[4][k], load_at(rays, _at(R_BEST_T, r))) if k >= 0 else (-1, math.inf)


@jit_inline
def packet_hit(rays, axes, r, bvh):
    """Ray ``r``'s closest hit after :func:`packet_closest`: ``(prim, t, b0, b1, b2)`` (prim -1: none)."""
    return hit_record(bvh[4], load_at(axes, _at(A_BEST_K, r)), load_at(rays, _at(R_BEST_T, r)),
                      _four(rays, R_WEIGHTS, r))


@jit_inline
def packet_depth(rays, r, t):
    """The view depth of ray ``r``'s point at ``t``
    (:func:`~core.image_order.ray_casting.view_depth`, bit for bit)."""
    return load_at(rays, _at(R_DEPTH, r)) + t * load_at(rays, _at(R_DEPTH + 1, r))
