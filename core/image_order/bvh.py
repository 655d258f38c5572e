"""A bounding volume hierarchy (BVH): boxes within boxes around the scene's primitives.

The lecture's bounding spheres put one simple solid around each object; a
BVH carries the idea on: a box around the whole scene holds two smaller
boxes, each holds two smaller ones, down to leaves of at most four
triangles, or one analytic sphere.  A ray that misses a box skips
everything inside it, so a ray typically tests a few dozen boxes and a handful
of triangles instead of every triangle.

The tree is built top-down with the binned surface area heuristic
(:mod:`core.image_order.kernels.bvh_build`) and stored flat, like pbrt's
``LinearBVHNode`` array, except that the two children of a node always sit
next to each other (a node stores the index of its first child), so one fetch
from memory brings both boxes.  Leaves point into ``order``, and the
primitive rows are copied in that order, so the triangles of one leaf lie
next to each other in memory.

The binary tree is what the app shows.  The traversal reads a four-wide
form of it (:func:`core.image_order.kernels.bvh_build.widen`): every wide node holds the
boxes of four children side by side, so one step tests all four at once
with vector instructions (:mod:`core.image_order.kernels.intrinsics.slabs4`) and a ray takes
about half as many steps as in the binary tree.  The triangles of each leaf
are copied side by side into one group of four, tested at once the same way
(:mod:`core.image_order.kernels.intrinsics.triangle4`).  Traversal:
:mod:`core.image_order.kernels.bvh_traverse`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).


@dataclass(frozen=True, eq=False)
class Bvh:
    """A flattened BVH over the primitives of a :class:`core.image_order.flat_scene.Geometry`.

    Attributes
    ----------
    nodes : (N, 8) float64
        Per node: box ``lo`` (3) and ``hi`` (3), world space; then for a leaf
        the index of its first entry in ``order`` and its primitive count
        (> 0), for an inner node the index of its first child (the second
        follows it) and ``-(axis + 1)`` of its split axis.
    order : (P,) int64, primitive indices in leaf order.
    rows : (P, 9) float64, the primitive rows in leaf order.
    depth : int, number of levels.
    wide : (M, WIDE_SIZE) float32
        What the traversal reads: the four-wide tree (root first), per node
        the children's boxes rounded *outwards* to float32 and their
        references as int32 (read through ``wide.view(np.int32)``): a wide
        node's index, or ``~leaf`` for a leaf; then, for a leaf of triangles,
        its group and count (:func:`~core.image_order.kernels.bvh_build.leaf_groups`,
        int32, 0 for the others).  The primitive tests stay in
        float64, so the hits are exactly those of the float64 boxes.
    leaves : (L, 3) int64
        Per leaf of the wide tree: its first entry in ``order``, its number of
        primitives, and its first triangle group (-1 when it holds an
        analytic sphere, alone: it is tested on its own).
    groups : (G, GROUP_SIZE) float64
        The leaves' triangles in groups of four (see
        :func:`~core.image_order.kernels.bvh_build.group_triangles`).
    primitive_size : float
        The median diagonal of the primitives' boxes (``inf`` without primitives): how large
        a typical triangle or sphere is, for :meth:`packets_pay`.
    """

    nodes: np.ndarray
    order: np.ndarray
    rows: np.ndarray
    depth: int
    wide: np.ndarray
    leaves: np.ndarray
    groups: np.ndarray
    primitive_size: float = math.inf

    def packets_pay(self, camera) -> bool:
        """Whether the primary rays should walk the tree in packets
        (:mod:`core.image_order.kernels.bvh_packet`).

        A packet pays while the patch its rays cover, where they meet the scene, is smaller
        than a typical primitive: its rays then cross mostly the same leaves.  Over larger
        patches each ray's own tests of the leaf boxes cost more than the shared walk saves (on
        the 100,000-triangle benchmark at 64 x 48 pixels the packets took twice the time of
        lone rays; at 640 x 480 they took about three quarters).  The patch is the packet's
        width in pixels, as an angle, times the distance from the eye to the centre of the
        scene's box; an orthographic camera's rays cannot share a walk at all.
        """
        from core.image_order.kernels.bvh_packet import PACKET_COLS

        if camera.projection == "orthographic" or len(self.nodes) == 0:
            return False
        half_height = camera.half_extent(1.0)[1]
        centre = (self.nodes[0, 0:3] + self.nodes[0, 3:6]) / 2.0
        distance = float(np.linalg.norm(centre - np.asarray(camera.eye, dtype=float)))
        patch = PACKET_COLS * 2.0 * half_height / camera.height * distance
        return patch < self.primitive_size

    def kernel_tuple(self) -> tuple:
        return (self.wide.reshape(-1), self.wide.view(np.int32), self.leaves, self.groups.reshape(-1),
                self.order, self.rows)

    @property
    def is_leaf(self) -> np.ndarray:
        """(N,) bool."""
        return self.nodes[:, 7] > 0

    def levels(self) -> np.ndarray:
        """(N,) int64: depth of every node, the root at 0."""
        n = len(self.nodes)
        level = np.zeros(n, dtype=np.int64)
        inner = np.flatnonzero(~self.is_leaf)
        frontier = inner[:1] if n else inner
        while frontier.size:
            first = self.nodes[frontier, 6].astype(np.int64)
            children = np.concatenate([first, first + 1])
            level[children] = level[frontier[0]] + 1
            frontier = children[~self.is_leaf[children]]
        return level

    def node_boxes(self, level: int | None = None) -> np.ndarray:
        """(K, 2, 3) float64: ``(lo, hi)`` of the nodes at ``level`` (all nodes if ``None``)."""
        boxes = self.nodes[:, :6].reshape(-1, 2, 3)
        return boxes if level is None else boxes[self.levels() == level]


def empty_kernel_tuple() -> tuple:
    """The kernels' stand-in when no BVH is used."""
    from core.image_order.kernels.bvh_build import WIDE_SIZE

    wide = np.zeros((0, WIDE_SIZE), np.float32)
    return (wide.reshape(-1), wide.view(np.int32), np.zeros((0, 3), np.int64), np.zeros(0),
            np.zeros(0, np.int64), np.zeros((0, 9)))


def pack_wide(boxes: np.ndarray, refs: np.ndarray, leaf_groups: np.ndarray) -> np.ndarray:
    """The float32 rows of :attr:`Bvh.wide` from :func:`~core.image_order.kernels.bvh_build.widen`
    and :func:`~core.image_order.kernels.bvh_build.leaf_groups`."""
    from core.image_order.kernels.bvh_build import WIDE_GROUPS, WIDE_HI, WIDE_LO, WIDE_REFS, WIDE_SIZE, WIDTH

    lo, hi = boxes[:, 0:3, :], boxes[:, 3:6, :]
    lo32, hi32 = lo.astype(np.float32), hi.astype(np.float32)
    lo32 = np.where(lo32 > lo, np.nextafter(lo32, np.float32(-np.inf)), lo32)
    hi32 = np.where(hi32 < hi, np.nextafter(hi32, np.float32(np.inf)), hi32)
    wide = np.zeros((len(boxes), WIDE_SIZE), np.float32)
    wide[:, WIDE_LO:WIDE_HI] = lo32.reshape(len(boxes), WIDE_HI - WIDE_LO)
    wide[:, WIDE_HI:WIDE_REFS] = hi32.reshape(len(boxes), WIDE_REFS - WIDE_HI)
    wide.view(np.int32)[:, WIDE_REFS:WIDE_REFS + WIDTH] = refs
    wide.view(np.int32)[:, WIDE_GROUPS:WIDE_GROUPS + WIDTH] = leaf_groups
    return wide


def build_bvh(geometry) -> Bvh:
    """Build the BVH over every primitive of ``geometry`` (a flat_scene ``Geometry``)."""
    from core.image_order.kernels.bvh_build import build_bvh as _build
    from core.image_order.kernels.bvh_build import group_triangles, leaf_groups, widen

    nodes, order, depth = _build(geometry.lo, geometry.hi, geometry.n_spheres)
    rows = np.ascontiguousarray(geometry.rows[order])
    boxes, refs, leaves = widen(nodes)
    groups = group_triangles(leaves, rows, order, geometry.n_spheres)
    sizes = np.linalg.norm(geometry.hi - geometry.lo, axis=1)
    size = float(np.median(sizes)) if len(sizes) else math.inf
    return Bvh(nodes, order, rows, int(depth), pack_wide(boxes, refs, leaf_groups(refs, leaves)),
               leaves, groups, size)
