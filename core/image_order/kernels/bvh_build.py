"""Compiled construction of a bounding volume hierarchy with the binned surface area heuristic.

See :mod:`core.image_order.bvh` for what the hierarchy is and how it is laid out.  The
build works top-down: a node's primitives are split in two by a plane
perpendicular to one axis, and the plane is chosen by the *surface area
heuristic* (SAH): a ray that hits a box hits a smaller box inside it with
probability about (area of the small box) / (area of the big box), so the
expected work below the node after a split is ::

    (G_left A_left + G_right A_right) / A_node

in vector triangle tests, where ``G`` is the number of groups of four a
side's primitives fill (the traversal tests four triangles at once, so five
cost as much as eight; Embree's builder prices its SIMD blocks the same
way).  Candidate planes are the borders between ``BINS`` equal bins of the
primitives' centroids along each axis (Wald's binned SAH), so one pass over
the primitives evaluates all of them.  A node of at most ``MAX_LEAF``
triangles, one group, is a leaf: one vector test costs less than visiting
children.  An analytic sphere gets a leaf of its own: a sphere is tested on
its own anyway, and in a shared leaf every ray that enters it for the other
primitives would pay for the sphere too (in the mirror-and-glass scene the
two balls shared a leaf with the ground, whose box nearly every ray enters:
a quarter of the frame's time went to testing them).  A larger node whose
centroids all coincide (no plane separates them) is split in the middle of
its list.

:func:`widen` then collapses the binary tree into the four-wide one the
traversal reads: a wide node takes the two children of a binary node and
keeps replacing its largest inner child by that child's two children until
it has four (Wald et al.'s collapse, as Embree builds its wide trees).
:func:`group_triangles` lays out the triangles of every leaf in groups of
four for the vector triangle test (:mod:`core.image_order.kernels.intrinsics.triangle4`).
"""

from __future__ import annotations

import numpy as np

from core.image_order.kernels.intrinsics.triangle4 import AXIS_STRIDE, CORNER_STRIDE, GROUP_SIZE, LANES
from core.image_order.kernels.jit import jit, jit_allocating, jit_inline

BINS = 16
#: A leaf holds at most one group of four primitives (a node with more is always split).  Against
#: leaves of up to eight priced per primitive, the 100,000-triangle benchmark's tree shrinks from
#: 12 to 10 MB and its primary rays run about a tenth faster beside Embree (less to fetch into cache).
MAX_LEAF = LANES
#: Children of a node of the wide tree.
WIDTH = 4
#: Columns of a row of the packed wide tree (:attr:`core.image_order.bvh.Bvh.wide`): the children's ``lo``
#: sides (x, y, z rows of WIDTH), their ``hi`` sides, their references (int32), their
#: :func:`leaf_group` s (int32; 128 bytes in all).
WIDE_LO, WIDE_HI, WIDE_REFS, WIDE_GROUPS, WIDE_SIZE = 0, 3 * WIDTH, 6 * WIDTH, 7 * WIDTH, 8 * WIDTH
#: Bits of a :func:`leaf_group` that hold the leaf's triangle count.
_COUNT_BITS = 3
#: Columns of a row of the leaves (:attr:`core.image_order.bvh.Bvh.leaves`): first primitive, count, group.
LEAF_SIZE = 3


@jit
def _area(lx, ly, lz, hx, hy, hz):
    dx, dy, dz = hx - lx, hy - ly, hz - lz
    return 2.0 * (dx * dy + dy * dz + dz * dx)


@jit
def _groups(n):
    """Groups of four that ``n`` primitives fill."""
    return (n + LANES - 1) // LANES


@jit_allocating
def build_bvh(lo, hi, n_spheres):
    """Build the hierarchy over primitives with bounding boxes ``lo``, ``hi``.

    Parameters
    ----------
    lo, hi : (P, 3) float64
        Corners of each primitive's axis-aligned bounding box, world space.
    n_spheres : int
        Primitives below this index are analytic spheres: each gets a leaf of its own.

    Returns
    -------
    nodes : (N, 8) float64
        The root first; the two children of a node are always stored next to
        each other, so one memory fetch brings both boxes.  Columns 0-5: the
        node's box ``(lo, hi)``.  Column 7: for a leaf the number of
        primitives (> 0) and column 6 the index of its first entry in
        ``order``; for an inner node ``-(axis + 1)`` of its split axis and
        column 6 the index of its first child (the second follows it).
    order : (P,) int64
        Primitive indices in leaf order.
    depth : int
        Number of levels (1 for a lone leaf): a traversal stack of this size suffices.
    """
    n_prims = lo.shape[0]
    order = np.arange(n_prims)
    nodes = np.zeros((max(2 * n_prims - 1, 0), 8))
    if n_prims == 0:
        return nodes, order, 0
    centroid = 0.5 * (lo + hi)
    # Pending nodes: (start, end, node index, level).
    stack = np.empty((2 * n_prims + 2, 4), np.int64)
    stack[0] = (0, n_prims, 0, 1)
    depth = 1
    max_level = 1
    n_nodes = 1
    bin_count = np.empty(BINS, np.int64)
    bin_box = np.empty((BINS, 6))
    right_area = np.empty(BINS)
    right_count = np.empty(BINS, np.int64)
    while depth > 0:
        depth -= 1
        start, end, node, level = stack[depth, 0], stack[depth, 1], stack[depth, 2], stack[depth, 3]
        max_level = max(max_level, level)
        # Bounds of the node and of its centroids.
        box = nodes[node]
        box[0:3] = np.inf
        box[3:6] = -np.inf
        cmin = np.full(3, np.inf)
        cmax = np.full(3, -np.inf)
        spheres = 0
        for k in range(start, end):
            p = order[k]
            spheres += p < n_spheres
            for a in range(3):
                box[a] = min(box[a], lo[p, a])
                box[3 + a] = max(box[3 + a], hi[p, a])
                cmin[a] = min(cmin[a], centroid[p, a])
                cmax[a] = max(cmax[a], centroid[p, a])
        count = end - start
        if count == 1 or (count <= MAX_LEAF and spheres == 0):
            box[6] = start
            box[7] = count
            continue
        node_area = _area(box[0], box[1], box[2], box[3], box[4], box[5])
        best_cost, best_axis, best_bin = np.inf, -1, -1
        for a in range(3):
            extent = cmax[a] - cmin[a]
            if extent <= 0.0:
                continue
            # Bin the centroids.
            bin_count[:] = 0
            bin_box[:, 0:3] = np.inf
            bin_box[:, 3:6] = -np.inf
            for k in range(start, end):
                p = order[k]
                b = min(int(BINS * (centroid[p, a] - cmin[a]) / extent), BINS - 1)
                bin_count[b] += 1
                for c in range(3):
                    bin_box[b, c] = min(bin_box[b, c], lo[p, c])
                    bin_box[b, 3 + c] = max(bin_box[b, 3 + c], hi[p, c])
            # Sweep from the right, then from the left, to price every plane.
            rl = np.full(3, np.inf)
            rh = np.full(3, -np.inf)
            n_right = 0
            for b in range(BINS - 1, 0, -1):
                n_right += bin_count[b]
                for c in range(3):
                    rl[c] = min(rl[c], bin_box[b, c])
                    rh[c] = max(rh[c], bin_box[b, 3 + c])
                right_count[b] = n_right
                right_area[b] = _area(rl[0], rl[1], rl[2], rh[0], rh[1], rh[2]) if n_right else 0.0
            ll = np.full(3, np.inf)
            lh = np.full(3, -np.inf)
            n_left = 0
            for b in range(BINS - 1):
                n_left += bin_count[b]
                for c in range(3):
                    ll[c] = min(ll[c], bin_box[b, c])
                    lh[c] = max(lh[c], bin_box[b, 3 + c])
                if n_left == 0 or right_count[b + 1] == 0:
                    continue
                left_area = _area(ll[0], ll[1], ll[2], lh[0], lh[1], lh[2])
                cost = (_groups(n_left) * left_area
                        + _groups(right_count[b + 1]) * right_area[b + 1]) / node_area
                if cost < best_cost:
                    best_cost, best_axis, best_bin = cost, a, b
        if best_axis < 0:
            # All centroids coincide: split the list in the middle.
            mid = (start + end) // 2
            best_axis = 0
        else:
            # Partition the primitives: bins <= best_bin go left.
            a = best_axis
            extent = cmax[a] - cmin[a]
            i, j = start, end - 1
            while i <= j:
                b = min(int(BINS * (centroid[order[i], a] - cmin[a]) / extent), BINS - 1)
                if b <= best_bin:
                    i += 1
                else:
                    order[i], order[j] = order[j], order[i]
                    j -= 1
            mid = i
        box[6] = n_nodes
        box[7] = -(best_axis + 1)
        stack[depth] = (mid, end, n_nodes + 1, level + 1)
        stack[depth + 1] = (start, mid, n_nodes, level + 1)
        n_nodes += 2
        depth += 2
    return nodes[:n_nodes].copy(), order, max_level


@jit_allocating
def widen(nodes):
    """Collapse the binary tree ``nodes`` (as returned by :func:`build_bvh`) into a four-wide tree.

    Returns
    -------
    boxes : (M, 6, WIDTH) float64
        Per wide node, rows ``lo x, lo y, lo z, hi x, hi y, hi z`` of its
        children's boxes; unused slots hold the empty box (``lo = inf``,
        ``hi = -inf``), which every ray misses.  The root is node 0.
    refs : (M, WIDTH) int64
        Per child: the index of a wide node (>= 0), or ``~leaf`` for a leaf.
    leaves : (L, 3) int64
        Per leaf: its first entry in ``order``, its number of primitives, and
        a third column for :func:`group_triangles` to fill.
    """
    n_inner = 0
    for i in range(nodes.shape[0]):
        if nodes[i, 7] <= 0:
            n_inner += 1
    m = max(n_inner, 1)
    boxes = np.empty((m, 6, WIDTH))
    boxes[:, 0:3, :] = np.inf
    boxes[:, 3:6, :] = -np.inf
    refs = np.zeros((m, WIDTH), np.int64)
    leaves = np.zeros((nodes.shape[0] - n_inner, LEAF_SIZE), np.int64)
    if nodes.shape[0] == 0:
        return boxes[:0], refs[:0], leaves
    pending = np.empty((m, 2), np.int64)  # (binary node, wide node)
    pending[0] = (0, 0)
    top = 1
    n_wide = 1
    n_leaves = 0
    kids = np.empty(WIDTH, np.int64)
    while top > 0:
        top -= 1
        binary, wide = pending[top, 0], pending[top, 1]
        if nodes[binary, 7] > 0:  # the whole tree is one leaf
            kids[0] = binary
            n_kids = 1
        else:
            kids[0] = int(nodes[binary, 6])
            kids[1] = kids[0] + 1
            n_kids = 2
        while n_kids < WIDTH:
            largest, largest_area = -1, -1.0
            for c in range(n_kids):
                node = nodes[kids[c]]
                if node[7] <= 0:
                    area = _area(node[0], node[1], node[2], node[3], node[4], node[5])
                    if area > largest_area:
                        largest, largest_area = c, area
            if largest < 0:
                break
            first = int(nodes[kids[largest], 6])
            kids[largest] = first
            kids[n_kids] = first + 1
            n_kids += 1
        for c in range(n_kids):
            node = nodes[kids[c]]
            for row in range(6):
                boxes[wide, row, c] = node[row]
            if node[7] > 0:
                refs[wide, c] = ~n_leaves
                leaves[n_leaves, 0] = int(node[6])
                leaves[n_leaves, 1] = int(node[7])
                n_leaves += 1
            else:
                refs[wide, c] = n_wide
                pending[top] = (kids[c], n_wide)
                top += 1
                n_wide += 1
    return boxes[:n_wide].copy(), refs[:n_wide].copy(), leaves


@jit_allocating
def leaf_groups(refs, leaves):
    """What each wide node's row says of its child leaves, so that a walk can test a leaf's
    triangles without reading the leaf's row first: per child (``refs`` of :func:`widen`), the
    leaf's triangle group and triangle count packed in one number (:func:`from_leaf_group`), and
    0 for an inner node or a leaf whose primitives are tested one by one (a sphere's)."""
    packed = np.zeros(refs.shape, np.int64)
    for wide in range(refs.shape[0]):
        for c in range(WIDTH):
            if refs[wide, c] < 0:
                leaf = ~refs[wide, c]
                if leaves[leaf, 2] >= 0:
                    packed[wide, c] = (leaves[leaf, 2] << _COUNT_BITS) + leaves[leaf, 1]
    return packed


@jit_inline
def from_leaf_group(packed):
    """``(group, count)`` of a nonzero number of :func:`leaf_groups`."""
    return packed >> _COUNT_BITS, packed & ((1 << _COUNT_BITS) - 1)


@jit_allocating
def group_triangles(leaves, rows, order, n_spheres):
    """Copy the triangles of every leaf into groups of ``LANES`` for the vector test.

    Fills ``leaves[:, 2]`` with the leaf's first group, or -1 for a leaf that
    holds an analytic sphere (its primitives are tested one by one).  A leaf's
    last group is padded with copies of its last triangle; the traversal
    ignores the padding lanes.

    Parameters
    ----------
    leaves : (L, 3) int64 from :func:`widen`.
    rows : (P, 9) float64, the primitive rows in leaf order; ``order`` their primitive indices.
    n_spheres : int, primitives below this index are spheres.

    Returns
    -------
    (G, GROUP_SIZE) float64, laid out as :mod:`core.image_order.kernels.intrinsics.triangle4` reads them.
    """
    n_groups = 0
    for leaf in range(leaves.shape[0]):
        first, count = leaves[leaf, 0], leaves[leaf, 1]
        leaves[leaf, 2] = n_groups
        for k in range(first, first + count):
            if order[k] < n_spheres:
                leaves[leaf, 2] = -1
        if leaves[leaf, 2] >= 0:
            n_groups += (count + LANES - 1) // LANES
    groups = np.empty((n_groups, GROUP_SIZE))
    for leaf in range(leaves.shape[0]):
        first, count, group = leaves[leaf, 0], leaves[leaf, 1], leaves[leaf, 2]
        if group < 0:
            continue
        for j in range(0, count, LANES):
            for lane in range(LANES):
                k = first + min(j + lane, count - 1)
                for corner in range(3):
                    for axis in range(3):
                        groups[group + j // LANES, corner * CORNER_STRIDE + axis * AXIS_STRIDE + lane] = \
                            rows[k, 3 * corner + axis]
    return groups
