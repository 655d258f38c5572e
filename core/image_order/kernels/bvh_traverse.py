"""Compiled traversal of the bounding volume hierarchy (see :mod:`core.image_order.bvh`).

A ray walks the four-wide tree from the root with a small stack.  At an
inner node it tests the boxes of all four children at once
(:func:`~core.image_order.kernels.intrinsics.slabs4.slab_test4`), goes on into the nearest child
it hits and pushes the others, farther first, each with the distance where
the ray enters it; a pushed subtree whose entry lies beyond the closest hit
found meanwhile is dropped unvisited.  A shadow ray (any hit) walks for its own
question (:func:`bvh_occluded`): it takes the children it hits in the order of their
slots (:func:`any_child`), since any blocker will do, and leaving out the search for
the nearest and the sorted pushes costs a shadow ray about a sixth to a third less
time (``bench trace``'s bumpy balls, one thread's CPU time; the boxes and triangles
it tests grow by 0-4%); and it tests a leaf's triangles from what the leaf's parent
says of them, reading the leaf's own row only to name a blocker (about a tenth less
time again, the same rays, blockers and counts).  At a leaf it tests the triangles four
at a time (:func:`~core.image_order.kernels.intrinsics.triangle4.triangle_test4`); a sphere
has a leaf of its own and its own test.  Boxes are only tested against the
part of the ray before the closest hit so far, so far subtrees fall away
quickly.

:func:`bvh_closest` is inlined into the render's loops of secondary rays,
into the shadow rays of shading and into the primary rays that cannot go in
a packet (:mod:`core.image_order.kernels.bvh_packet`, which shares
:func:`test_leaf`, :func:`hit_record` and :func:`nearest_child`), where a call passing
the tree's arrays would cost about a fifth of the traversal itself; every
other caller goes through one compiled copy
(:mod:`core.image_order.kernels.closest_hit`).
"""

from __future__ import annotations

import math

from core.image_order.flat_layout import BOUNDS_TESTS, PRIM_TESTS
from core.image_order.kernels.bvh_build import (
    LEAF_SIZE,
    WIDE_GROUPS,
    WIDE_HI,
    WIDE_LO,
    WIDE_REFS,
    WIDE_SIZE,
    WIDTH,
    from_leaf_group,
)
from core.image_order.kernels.intersect import triangle_hit
from core.image_order.kernels.intrinsics.bits import lowest_bit
from core.image_order.kernels.intrinsics.slabs4 import slab_mask4, slab_test4
from core.image_order.kernels.intrinsics.triangle4 import GROUP_SIZE, LANES, UNSURE, triangle_test4
from core.image_order.kernels.intrinsics.unchecked import load_at, prefetch_at, store_at
from core.image_order.kernels.jit import jit_inline
from core.image_order.kernels.primitives import no_hit, prim_hit

_OTHER_SIDE = WIDE_LO + WIDE_HI
_LINE = 8  # float64 numbers in a cache line of 64 bytes


@jit_inline
def _push(stack, stack_t, bottom, top, ref, t):
    """Put ``ref`` entered at ``t`` on the stack above ``bottom`` so that nearer entries lie higher."""
    at = top
    while at > bottom and load_at(stack_t, at - 1) < t:
        store_at(stack, at, load_at(stack, at - 1))
        store_at(stack_t, at, load_at(stack_t, at - 1))
        at -= 1
    store_at(stack, at, ref)
    store_at(stack_t, at, t)
    return top + 1


@jit_inline
def near_and_far_rows(ix, iy, iz):
    """Offsets within a wide node of the rows holding its boxes' near and far sides per axis, for
    a ray with ``1 / d = (ix, iy, iz)``: ``lo`` is near where the direction is positive."""
    side_x = WIDE_HI if ix < 0.0 else WIDE_LO
    side_y = WIDE_HI if iy < 0.0 else WIDE_LO
    side_z = WIDE_HI if iz < 0.0 else WIDE_LO
    return (side_x, side_y + WIDTH, side_z + 2 * WIDTH,
            _OTHER_SIDE - side_x, _OTHER_SIDE - side_y + WIDTH, _OTHER_SIDE - side_z + 2 * WIDTH)


@jit_inline
def nearest_child(entries, refs, at, stack, stack_t, top, slots):
    """Of the children of the node at ``at`` with the entries ``entries`` (``inf``: missed), the
    nearest, ``(child, entry, top)``, after pushing the others that were hit, farther first.

    With ``slots >= 0`` each pushed entry also carries ``slots + child``, the slot of its box
    (:func:`stack_entry`); with -1 it is the plain node reference.
    """
    near, near_t = 0, entries[0]
    for c in range(1, WIDTH):
        if entries[c] < near_t:
            near, near_t = c, entries[c]
    if near_t < math.inf:
        bottom = top
        for c in range(WIDTH):
            if c != near and entries[c] < math.inf:
                ref = load_at(refs, at + WIDE_REFS + c)
                if slots >= 0:
                    ref = stack_entry(ref, slots + c)
                top = _push(stack, stack_t, bottom, top, ref, entries[c])
    return near, near_t, top


@jit_inline
def any_child(entered, refs, at, stack, top):
    """For an any-hit walk: of the children of the node at ``at`` that the ray enters (bit ``c``
    of ``entered``, :func:`~core.image_order.kernels.intrinsics.slabs4.slab_mask4`), the first in
    slot order, ``(child, top)``, after pushing the other ones entered so that they come next in
    slot order, each as a :func:`stack_entry` with its
    :func:`~core.image_order.kernels.bvh_build.leaf_groups` number; ``child`` is -1 when none is
    entered.

    Unlike :func:`nearest_child` nothing is sorted: a shadow ray stops at its first blocker, so
    it may meet a farther one first (and name that one)."""
    near = -1
    for c in range(WIDTH - 1, -1, -1):
        if entered >> c & 1:
            if near >= 0:
                store_at(stack, top, stack_entry(load_at(refs, at + WIDE_REFS + near),
                                                 load_at(refs, at + WIDE_GROUPS + near)))
                top += 1
            near = c
    return near, top


@jit_inline
def prefetch_child(wide, refs, groups, at, c):
    """Ask the caches for what a walk first reads of child ``c`` of the node at ``at`` (its row of
    the tree, or the leaf's triangle group: every line it spans), while the walk works elsewhere.

    A packet of primary rays asks it for the children it will visit later (those it pushes): on
    the 1,000,000-triangle benchmark, whose tree and triangles (about 90 MB) are larger than the
    machine's caches, the primary stage took 1/1.06 of its time (one thread, 70 ms against 74);
    at 100,000 triangles, whose tree fits, no change.  A packet of shadow rays does not ask:
    there it saved 1% at 1,000,000 triangles on two threads and nothing on one, and cost 0.3-1.7%
    at 10,000 and 100,000 (the bench's batch, alternating in one process).  A lone ray's walk
    gains nothing from it: it reaches its next node sooner than the line arrives.
    """
    ref = load_at(refs, at + WIDE_REFS + c)
    if ref >= 0:
        for word in (0, WIDE_SIZE // 2, WIDE_SIZE - 1):
            prefetch_at(wide, ref * WIDE_SIZE + word)
    else:
        packed = load_at(refs, at + WIDE_GROUPS + c)
        if packed != 0:
            start = from_leaf_group(packed)[0] * GROUP_SIZE
            for number in range(0, GROUP_SIZE, _LINE):
                prefetch_at(groups, start + number)
            prefetch_at(groups, start + GROUP_SIZE - 1)


_SLOT, _HALF = 1 << 32, 1 << 31  # node references are int32


@jit_inline
def stack_entry(ref, slot):
    """A node reference (negative for a leaf) and a number of 31 bits that goes with it, packed in
    one stack entry: for a packet, the slot of its box in its parent (``parent * WIDTH + child``);
    for a shadow ray, its :func:`~core.image_order.kernels.bvh_build.leaf_groups` number."""
    return slot * _SLOT + (ref + _HALF)


@jit_inline
def from_stack_entry(entry):
    """``(ref, slot)`` of a :func:`stack_entry`."""
    return entry % _SLOT - _HALF, entry // _SLOT


@jit_inline
def bvh_closest(o, d, shear, t_min, t_max, any_hit, bvh, n_spheres, stack, stack_t, counters):
    """The closest crossing with ``t_min <= t < t_max`` (or any, for shadow rays), through the BVH.

    Parameters
    ----------
    o, d : (3,) tuples, the ray; ``shear`` its :func:`~core.image_order.intersect_triangle.ray_shear`.
    t_min, t_max : float, the admissible range of ``t``.
    any_hit : bool, stop at the first crossing found (shadow rays; :func:`bvh_occluded` answers).
    bvh : tuple ``(wide, refs, leaves, groups, order, rows)`` of
        :meth:`core.image_order.bvh.Bvh.kernel_tuple`.
    n_spheres : int, primitives below this index are spheres.
    stack : (D,) int64 and ``stack_t`` (D,) float64 scratch, ``D >= 3 * depth + 2``.
    counters : (N_COUNTERS,) int64, box and primitive tests are added.

    Returns
    -------
    (prim, t, b0, b1, b2) : the primitive index (-1 for none) and the crossing; with ``any_hit``
        the barycentric weights are left 0 (``t`` is the crossing's, as the tests compute it exactly).
    """
    if any_hit:
        return bvh_occluded(o, d, shear, t_min, t_max, bvh, n_spheres, stack, counters)
    wide, refs, leaves, groups, order, rows = bvh
    if wide.shape[0] == 0:
        return no_hit()
    ox, oy, oz = o
    kx, ky, kz = shear[0], shear[1], shear[2]
    okx, oky, okz = o[kx], o[ky], o[kz]
    ix, iy, iz = 1.0 / d[0], 1.0 / d[1], 1.0 / d[2]
    # Rows of the near and far sides per axis: lo is near where the direction is positive.
    nx, ny, nz, fx, fy, fz = near_and_far_rows(ix, iy, iz)
    best_t = t_max
    best_k = -1
    best_w = NO_WEIGHTS
    boxes = 0
    tests = 0
    top = 0
    node = 0
    enter = t_min  # the root's own box is never tested, its children's are
    while True:
        if enter < best_t:
            if node >= 0:
                at = node * WIDE_SIZE
                entries = slab_test4(wide, at + nx, at + ny, at + nz, at + fx, at + fy, at + fz, ox, oy, oz,
                                     ix, iy, iz, t_min, best_t)
                boxes += WIDTH
                near, near_t, top = nearest_child(entries, refs, at, stack, stack_t, top, -1)
                if near_t < math.inf:
                    node, enter = load_at(refs, at + WIDE_REFS + near), near_t
                    continue
            else:
                leaf = LEAF_SIZE * ~node
                first, count = load_at(leaves, leaf), load_at(leaves, leaf + 1)
                group = load_at(leaves, leaf + 2)
                tests += count
                best_t, best_k, best_w = test_leaf(groups, rows, order, n_spheres, first, count, group, o, d,
                                                   shear, okx, oky, okz, t_min, best_t, best_k, best_w)
        if top == 0:
            break
        top -= 1
        node, enter = load_at(stack, top), load_at(stack_t, top)
    counters[BOUNDS_TESTS] += boxes
    counters[PRIM_TESTS] += tests
    return hit_record(order, best_k, best_t, best_w)


@jit_inline
def bvh_occluded(o, d, shear, t_min, t_max, bvh, n_spheres, stack, counters):
    """Any crossing with ``t_min <= t < t_max`` (a shadow ray's blocker), through the BVH:
    :func:`bvh_closest` with ``any_hit``, which it answers, walked for that question alone.

    Nothing is sorted and nothing is dropped on the way: until the first crossing the ray's part
    of ``t`` stays ``[t_min, t_max)``, so every box it entered still counts when its turn comes,
    and the stack holds no entry distances.  The children it enters are taken in the order of
    their slots (:func:`any_child`).  A leaf of triangles is tested with what its parent's row
    says of it (:func:`~core.image_order.kernels.bvh_build.leaf_groups`); the leaf's own row,
    one more read from memory before the test could start, is read only when a triangle is hit
    or too close to call, to name it (the group's test is not made again).  Returns
    ``(prim, t, 0, 0, 0)`` (no weights; ``t`` exact).
    """
    wide, refs, leaves, groups, order, rows = bvh
    if wide.shape[0] == 0:
        return no_hit()
    ox, oy, oz = o
    kx, ky, kz, sx, sy, sz = shear
    okx, oky, okz = o[kx], o[ky], o[kz]
    ix, iy, iz = 1.0 / d[0], 1.0 / d[1], 1.0 / d[2]
    nx, ny, nz, fx, fy, fz = near_and_far_rows(ix, iy, iz)
    best_t, best_k = t_max, -1
    boxes = 0
    tests = 0
    top = 0
    node, packed = 0, 0
    while True:
        if node >= 0:
            at = node * WIDE_SIZE
            entered = slab_mask4(wide, at + nx, at + ny, at + nz, at + fx, at + fy, at + fz, ox, oy, oz, ix,
                                 iy, iz, t_min, t_max)
            boxes += WIDTH
            near, top = any_child(entered, refs, at, stack, top)
            if near >= 0:
                node, packed = load_at(refs, at + WIDE_REFS + near), load_at(refs, at + WIDE_GROUPS + near)
                continue
        else:
            leaf = LEAF_SIZE * ~node
            if packed != 0:
                group, count = from_leaf_group(packed)
                tests += count
                crossings = triangle_test4(groups, group * GROUP_SIZE, kx, ky, kz, okx, oky, okz, sx, sy, sz,
                                           t_min, t_max)
                # Lanes past the count repeat the last triangle: they add no crossing of their own.
                if crossings[4] != 0:  # a crossing, or UNSURE (-inf)
                    first = load_at(leaves, leaf)
                    best_t, best_k, _ = closest_in_group(crossings, rows, o, shear, first, count, t_min,
                                                         best_t, best_k, NO_WEIGHTS)
            else:
                first, count = load_at(leaves, leaf), load_at(leaves, leaf + 1)
                tests += count
                best_t, best_k, _ = test_leaf(groups, rows, order, n_spheres, first, count,
                                              load_at(leaves, leaf + 2), o, d, shear, okx, oky, okz, t_min,
                                              best_t, best_k, NO_WEIGHTS)
            if best_k >= 0:
                break
        if top == 0:
            break
        top -= 1
        node, packed = from_stack_entry(load_at(stack, top))
    counters[BOUNDS_TESTS] += boxes
    counters[PRIM_TESTS] += tests
    return (order[best_k], best_t, 0.0, 0.0, 0.0) if best_k >= 0 else no_hit()


#: The weights of no crossing yet (:func:`test_leaf`).
NO_WEIGHTS = (0.0, 0.0, 0.0, 1.0)


@jit_inline
def test_leaf(groups, rows, order, n_spheres, first, count, group, o, d, shear, okx, oky, okz, t_min, best_t,
              best_k, best_w):
    """Test the primitives of one leaf: ``(best_t, best_k, best_w)``, the closest crossing before
    ``best_t``, its place in the leaf order and its weights (unchanged if none is closer).
    ``okx, oky, okz`` are the origin's coordinates on the shear's axes.

    The weights ``(w0, w1, w2, w)`` give the crossing's barycentric weights ``w_i / w``
    (:func:`hit_record`): a triangle decided by the vector test keeps its edge functions and their
    sum, the very numbers the scalar test divides; one decided by the scalar test keeps its
    weights over 1 (a division by 1 is exact), a sphere zeros over 1.  So the walk that found the
    crossing also gives its weights, and the triangle is not tested again for them.
    """
    if group < 0:
        return _leaf_one_by_one(rows, order, n_spheres, first, count, o, d, shear, t_min, best_t, best_k,
                                best_w)
    kx, ky, kz, sx, sy, sz = shear
    for j in range(0, count, LANES):
        start = (group + j // LANES) * GROUP_SIZE
        crossings = triangle_test4(groups, start, kx, ky, kz, okx, oky, okz, sx, sy, sz, t_min, best_t)
        best_t, best_k, best_w = closest_in_group(crossings, rows, o, shear, first + j, min(LANES, count - j),
                                                  t_min, best_t, best_k, best_w)
    return best_t, best_k, best_w


@jit_inline
def closest_in_group(crossings, rows, o, shear, first, count, t_min, best_t, best_k, best_w):
    """:func:`test_leaf`'s closest crossing after the vector test of one group,
    ``crossings`` (:func:`~core.image_order.kernels.intrinsics.triangle4.triangle_test4`), whose
    first ``count`` lanes hold the primitives from ``first`` on in the leaf order.

    The vector test also gives the lanes that can matter (a crossing before its ``t_max``, or
    ``UNSURE``) as the bits of one number, from one vector comparison, and only those lanes are
    visited, in lane order; most groups have none.  numba picks the lane of a tuple at a
    changing index with a branch per lane, which a loop over every lane paid for each group.
    With the packets' pairs of rays, visiting only the lanes of a mask made of four scalar
    comparisons took the primary stage on the 1,000,000-triangle benchmark from 95 to 85 ms of
    one thread's CPU (100,000: 33 to 30), and the vector comparison to 79 (28).
    """
    lanes, e0s, e1s, e2s, candidates = crossings
    candidates &= (1 << count) - 1
    while candidates != 0:
        lane = lowest_bit(candidates)
        candidates &= candidates - 1
        t = lanes[lane]
        if t == UNSURE:
            t, b0, b1, b2 = triangle_hit(o, shear, rows, first + lane, t_min, best_t)
            if t < best_t:
                best_t, best_k, best_w = t, first + lane, (b0, b1, b2, 1.0)
        elif t < best_t:
            e0, e1, e2 = e0s[lane], e1s[lane], e2s[lane]
            best_t, best_k, best_w = t, first + lane, (e0, e1, e2, e0 + e1 + e2)
    return best_t, best_k, best_w


@jit_inline
def hit_record(order, best_k, best_t, best_w):
    """``(prim, t, b0, b1, b2)`` of the crossing at ``best_t`` with the primitive at ``best_k`` in
    the leaf order (-1: none) and the weights ``best_w`` of :func:`test_leaf`."""
    if best_k < 0:
        return no_hit()
    w0, w1, w2, w = best_w
    return order[best_k], best_t, w0 / w, w1 / w, w2 / w


@jit_inline
def _leaf_one_by_one(rows, order, n_spheres, first, count, o, d, shear, t_min, best_t, best_k, best_w):
    """Test the primitives of a leaf without a triangle group (a sphere's) one by one:
    ``(best_t, best_k, best_w)`` updated as by :func:`test_leaf`.

    Inlined, though meshes never come here: in a scene of balls a sphere's leaf is where most
    secondary rays end (a glass ball's rays inside it, a mirror ball's reflections testing
    their own ball), and as a call, passing the tree's arrays and the ray, it took about a
    tenth of their closest-hit search (mirror and glass, one thread's CPU).
    """
    for k in range(first, first + count):
        t, b0, b1, b2 = prim_hit(rows, k, order[k] < n_spheres, o, d, shear, t_min, best_t)
        if t < best_t:
            best_t, best_k, best_w = t, k, (b0, b1, b2, 1.0)
    return best_t, best_k, best_w
