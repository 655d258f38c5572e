"""Primary rays through the BVH in packets: one walk of the tree for 4 x 4 neighbouring pixels.

The rays of a perspective camera all start at the eye, and neighbouring
pixels' rays point almost the same way, so they enter almost the same boxes.
A packet walks the tree once for all of them.  At an inner node one
*interval* slab test
(:func:`~core.image_order.kernels.intrinsics.slabs4.slab_interval4`) asks
whether any ray of the packet can enter each child box: per axis it uses the
smallest and largest ``1 / d`` of the packet, and because rounding is
monotonic it never rejects a box that one of the rays would enter by its own
test.  At a leaf, each ray whose closest hit so far lies beyond the packet's
entry tests the leaf's box on its own (the very test a lone ray makes) and,
if it enters, the leaf's primitives, with exactly the arithmetic of a lone
ray (:func:`~core.image_order.kernels.bvh_traverse.test_leaf`).

So each ray finds the crossing that it would find alone, bit for bit: it
tests every leaf that it would test alone.  What the packet saves is the
walk.  On the 100,000-triangle benchmark at 640 x 480 a packet visits about
12 nodes where a lone ray visits about 9: one interval test serves 16 rays.
The rays' own tests of the leaf boxes are what a packet adds; they pay where
the packet spans more than a leaf (small images, tiny triangles: at 64 x 48
a packet without them would make each ray test 17 times the triangles), and
where nearly every ray enters the leaves anyway a packet stops making them
(``_TRIAL``).  Where two triangles are crossed at the very same ``t`` (a ray
through their shared edge), either is the answer; a packet may test them in
another order than a lone ray and name the other one.

A packet needs one origin and one sign of ``d`` per axis for all its rays,
with no direction parallel to an axis plane (``1 / d`` finite).  Where that
fails (an orthographic camera, whose rays start side by side on the near
plane; a packet straddling the plane where one component of ``d`` changes
sign), its rays go through the tree one at a time
(:func:`~core.image_order.kernels.bvh_traverse.bvh_closest`).

A packet is kept in two small per-thread arrays: ``rays`` (PACKET_SIZE x
RAY_FIELDS floats) and ``axes`` (PACKET_SIZE x AXIS_FIELDS integers), with
the columns named below.
"""

from __future__ import annotations

import math

from core.image_order.intersect_triangle import ray_shear
from core.image_order.kernels.bvh_build import LEAF_SIZE, WIDE_REFS, WIDE_SIZE, WIDTH
from core.image_order.kernels.bvh_traverse import (
    from_stack_entry,
    hit_record,
    near_and_far_rows,
    nearest_child,
    test_leaf,
)
from core.image_order.kernels.intrinsics.slabs4 import slab_interval4, slab_test4
from core.image_order.kernels.intrinsics.unchecked import load_at, store_at
from core.image_order.kernels.jit import jit, jit_inline
from core.image_order.kernels.layout import BOUNDS_TESTS, PRIM_TESTS

#: Pixels of a packet: rows and columns.
PACKET_ROWS = PACKET_COLS = 4
PACKET_SIZE = PACKET_ROWS * PACKET_COLS
# Columns of a packet's ray: origin, 1 / d, t_min, the closest hit so far (t_max to start), the
# shear of the watertight triangle test, the origin on its axes, the direction.
R_ORIGIN, R_INVERSE, R_T_MIN, R_BEST_T, R_SHEAR, R_SHEARED_ORIGIN, R_DIRECTION = 0, 3, 6, 7, 8, 11, 14
RAY_FIELDS = 17
# ... and its integer columns: the shear's axes kx, ky, kz, the closest primitive in leaf order (-1: none).
A_AXES, A_BEST_K = 0, 3
AXIS_FIELDS = 4
#: A packet's rays test a leaf's box each on their own before its primitives (see the module's
#: docstring), as long as that pays: for the first ``_TRIAL`` tests, and after them while at least
#: 2 in 5 rays are turned away (a box test costs about 2/5 of a test of four triangles).
_TRIAL = 32


@jit_inline
def set_ray(rays, axes, r, o, d, t_min, t_max):
    """Make ``o + t d`` (``t_min <= t < t_max``) ray ``r`` of the packet."""
    kx, ky, kz, sx, sy, sz = ray_shear(d[0], d[1], d[2])
    b = r * RAY_FIELDS
    for a in range(3):
        rays[b + R_ORIGIN + a] = o[a]
        rays[b + R_INVERSE + a] = 1.0 / d[a]
        rays[b + R_DIRECTION + a] = d[a]
    rays[b + R_T_MIN], rays[b + R_BEST_T] = t_min, t_max
    rays[b + R_SHEAR], rays[b + R_SHEAR + 1], rays[b + R_SHEAR + 2] = sx, sy, sz
    rays[b + R_SHEARED_ORIGIN], rays[b + R_SHEARED_ORIGIN + 1] = o[kx], o[ky]
    rays[b + R_SHEARED_ORIGIN + 2] = o[kz]
    c = r * AXIS_FIELDS
    axes[c + A_AXES], axes[c + A_AXES + 1], axes[c + A_AXES + 2], axes[c + A_BEST_K] = kx, ky, kz, -1


@jit_inline
def ray_of(rays, axes, r):
    """Ray ``r`` of the packet: ``(o, d, shear, t_min, t_max)`` (``t_max``: its closest hit so far)."""
    b, c = r * RAY_FIELDS, r * AXIS_FIELDS
    shear = _three(axes, c + A_AXES) + _three(rays, b + R_SHEAR)
    return (_three(rays, b + R_ORIGIN), _three(rays, b + R_DIRECTION), shear, load_at(rays, b + R_T_MIN),
            load_at(rays, b + R_BEST_T))


@jit_inline
def _three(array, at):
    return load_at(array, at), load_at(array, at + 1), load_at(array, at + 2)


@jit
def can_share_walk(rays, n):
    """Whether rays ``0 .. n-1`` have one origin, one sign of ``d`` per axis and finite ``1 / d``."""
    for r in range(n):
        b = r * RAY_FIELDS
        for a in range(3):
            inverse = rays[b + R_INVERSE + a]
            if not abs(inverse) < math.inf:
                return False
            if rays[b + R_ORIGIN + a] != rays[R_ORIGIN + a] or (inverse < 0.0) != (rays[R_INVERSE + a] < 0.0):
                return False
    return True


@jit
def packet_closest(n, rays, axes, bvh, n_spheres, stack, stack_t, counters):
    """Find the closest crossing of each of the packet's rays ``0 .. n-1`` (:func:`can_share_walk`
    holds); each ray's ``R_BEST_T`` and ``A_BEST_K`` then name it (``A_BEST_K`` -1: none).

    ``stack`` (int64) and ``stack_t`` (float64) hold ``3 * depth + 2`` entries, as for one ray.
    """
    wide, refs, leaves, groups, order, rows = bvh
    ox, oy, oz = rays[R_ORIGIN], rays[R_ORIGIN + 1], rays[R_ORIGIN + 2]
    ax, ay, az = rays[R_INVERSE], rays[R_INVERSE + 1], rays[R_INVERSE + 2]
    bx, by, bz = ax, ay, az
    t_low, t_high = rays[R_T_MIN], rays[R_BEST_T]
    for r in range(1, n):
        b = r * RAY_FIELDS
        ax, bx = min(ax, rays[b + R_INVERSE]), max(bx, rays[b + R_INVERSE])
        ay, by = min(ay, rays[b + R_INVERSE + 1]), max(by, rays[b + R_INVERSE + 1])
        az, bz = min(az, rays[b + R_INVERSE + 2]), max(bz, rays[b + R_INVERSE + 2])
        t_low, t_high = min(t_low, rays[b + R_T_MIN]), max(t_high, rays[b + R_BEST_T])
    nx, ny, nz, fx, fy, fz = near_and_far_rows(ax, ay, az)  # all the rays' signs agree
    boxes = 0
    tests = 0
    top = 0
    node = 0
    enter = t_low
    checked = rejected = 0
    slot = -1  # the node's box in its parent: parent * WIDTH + child (-1: the root has none)
    while True:
        if enter < t_high:  # some ray's closest hit so far lies beyond where the packet enters
            if node >= 0:
                at = node * WIDE_SIZE
                entries = slab_interval4(wide, at + nx, at + ny, at + nz, at + fx, at + fy, at + fz, ox, oy,
                                         oz, ax, ay, az, bx, by, bz, t_low, t_high)
                boxes += WIDTH
                near, near_t, top = nearest_child(entries, refs, at, stack, stack_t, top, node * WIDTH)
                if near_t < math.inf:
                    node, enter, slot = load_at(refs, at + WIDE_REFS + near), near_t, node * WIDTH + near
                    continue
            else:
                leaf = LEAF_SIZE * ~node
                first, count = load_at(leaves, leaf), load_at(leaves, leaf + 1)
                group = load_at(leaves, leaf + 2)
                p, box = (slot // WIDTH) * WIDE_SIZE, slot % WIDTH  # the parent's row, the leaf's box in it
                t_high = -math.inf
                for r in range(n):
                    o, d, shear, t_min, best_t = ray_of(rays, axes, r)
                    b = r * RAY_FIELDS
                    if enter < best_t and slot >= 0 and (checked < _TRIAL or 5 * rejected > 2 * checked):
                        # Only the rays that enter the leaf's box themselves test what it holds.
                        ix, iy, iz = _three(rays, b + R_INVERSE)
                        own = slab_test4(wide, p + nx, p + ny, p + nz, p + fx, p + fy, p + fz, ox, oy, oz,
                                         ix, iy, iz, t_min, best_t)
                        boxes += WIDTH
                        enters = own[box] < math.inf
                        checked += 1
                        rejected += not enters
                    else:
                        enters = enter < best_t
                    if enters:
                        tests += count
                        best_k = load_at(axes, r * AXIS_FIELDS + A_BEST_K)
                        okx, oky, okz = _three(rays, b + R_SHEARED_ORIGIN)
                        best_t, best_k = test_leaf(groups, rows, order, n_spheres, first, count, group, o, d,
                                                   shear, okx, oky, okz, t_min, best_t, best_k)
                        store_at(rays, b + R_BEST_T, best_t)
                        store_at(axes, r * AXIS_FIELDS + A_BEST_K, best_k)
                    t_high = max(t_high, best_t)
        if top == 0:
            break
        top -= 1
        node, slot = from_stack_entry(load_at(stack, top))
        enter = load_at(stack_t, top)
    counters[BOUNDS_TESTS] += boxes
    counters[PRIM_TESTS] += tests


@jit_inline
def packet_hit(rays, axes, r, bvh, n_spheres):
    """Ray ``r``'s closest hit after :func:`packet_closest`: ``(prim, t, b0, b1, b2)`` (prim -1: none)."""
    o, d, shear, t_min, _ = ray_of(rays, axes, r)
    best_k = load_at(axes, r * AXIS_FIELDS + A_BEST_K)
    return hit_record(bvh[5], bvh[4], n_spheres, best_k, o, d, shear, t_min)
