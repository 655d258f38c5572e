"""A bounding volume hierarchy (BVH): boxes within boxes around the scene's primitives.

The lecture's bounding spheres put one simple solid around each object; a
BVH carries the idea on: a box around the whole scene holds two smaller
boxes, each holds two smaller ones, down to leaves of a few primitives
(triangles and analytic spheres alike).  A ray that misses a box skips
everything inside it, so a ray typically tests a few dozen boxes and a handful
of triangles instead of every triangle.

The tree is built top-down with the binned surface area heuristic
(:mod:`core.kernels.bvh_build`) and stored flat, like pbrt's
``LinearBVHNode`` array, except that the two children of a node always sit
next to each other (a node stores the index of its first child), so one fetch
from memory brings both boxes.  Leaves point into ``order``, and the
primitive rows are copied in that order, so the triangles of one leaf lie
next to each other in memory.  Traversal: :mod:`core.kernels.bvh_traverse`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.kernels.bvh_build import build_bvh as _build


@dataclass(frozen=True, eq=False)
class Bvh:
    """A flattened BVH over the primitives of a :class:`core.trace_scene.Geometry`.

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
    packed : (N, 8) float32
        What the traversal reads: the boxes rounded *outwards* to float32 and
        the two integers of each node stored as int32 in columns 6 and 7 (read
        through ``packed.view(np.int32)``).  A node takes 32 bytes, so the two
        children of a node share one 64-byte cache line; the primitive tests
        stay in float64, so the hits are exactly those of the float64 boxes.
    """

    nodes: np.ndarray
    order: np.ndarray
    rows: np.ndarray
    depth: int
    packed: np.ndarray

    def kernel_tuple(self) -> tuple:
        return self.packed, self.packed.view(np.int32), self.order, self.rows

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
    packed = np.zeros((0, 8), np.float32)
    return packed, packed.view(np.int32), np.zeros(0, np.int64), np.zeros((0, 9))


def pack_nodes(nodes: np.ndarray) -> np.ndarray:
    """The float32 form of ``nodes`` (see :attr:`Bvh.packed`)."""
    lo, hi = nodes[:, 0:3], nodes[:, 3:6]
    lo32, hi32 = lo.astype(np.float32), hi.astype(np.float32)
    lo32 = np.where(lo32 > lo, np.nextafter(lo32, np.float32(-np.inf)), lo32)
    hi32 = np.where(hi32 < hi, np.nextafter(hi32, np.float32(np.inf)), hi32)
    packed = np.zeros((len(nodes), 8), np.float32)
    packed[:, 0:3], packed[:, 3:6] = lo32, hi32
    packed.view(np.int32)[:, 6:8] = nodes[:, 6:8].astype(np.int32)
    return packed


def build_bvh(geometry) -> Bvh:
    """Build the BVH over every primitive of ``geometry`` (a :class:`core.trace_scene.Geometry`)."""
    nodes, order, depth = _build(geometry.lo, geometry.hi)
    return Bvh(nodes, order, np.ascontiguousarray(geometry.rows[order]), int(depth), pack_nodes(nodes))
