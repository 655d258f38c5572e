"""The uniform grid: the scene's box cut into equal cuboids, each listing what it holds.

The lecture: "enclose the whole scene in a cuboid; divide it into smaller
cuboids; for each, create the list of objects that entirely or at least
partially belong to it.  During the analysis of the path of the ray find the
smaller cuboids crossed by the ray; further calculations concern only the
objects associated with them."

Here the lists hold primitives (analytic spheres and single triangles), and a
primitive belongs to every cell its (padded) bounding box overlaps; that may
list a large slanted triangle in a few cells it only passes near, which costs
tests but never a hit.  The ray walks the cells it crosses in order with the
3D-DDA of Amanatides and Woo (:mod:`core.image_order.kernels.accel_grid`) and stops at the
first cell whose far wall lies beyond the closest hit found so far.  A
primitive listed in several cells is tested at most once per ray (mailboxing).

Resolution (pbrt-v1's rule): about ``3 P^(1/3)`` cells along the longest side
for ``P`` primitives, proportionally fewer along the shorter sides, at most
``MAX_RESOLUTION`` per axis.

Cell ``(i, j, k)`` counts along x, y, z from the grid's ``lo`` corner; its flat
index is ``(k * ny + j) * nx + i``.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

# Kernels are imported where they are used, so importing this module does not load numba
# (core.compiling.jitable).

MAX_RESOLUTION = 64


@dataclass(frozen=True, eq=False)
class UniformGrid:
    """A uniform grid over a scene's primitives.

    Attributes
    ----------
    lo, hi : (3,) float64, world-space corners of the grid's box.
    cell_size : (3,) float64, edge lengths of one cell (scene units).
    resolution : (3,) int64, number of cells along x, y, z.
    cell_start : (C + 1,) int64, cell ``c`` lists ``cell_prims[cell_start[c]:cell_start[c + 1]]``.
    cell_prims : (M,) int64, primitive indices (see :mod:`core.image_order.flat_scene`).
    """

    lo: np.ndarray
    hi: np.ndarray
    cell_size: np.ndarray
    resolution: np.ndarray
    cell_start: np.ndarray
    cell_prims: np.ndarray

    @property
    def n_cells(self) -> int:
        return int(np.prod(self.resolution))

    def kernel_tuple(self) -> tuple:
        return self.lo, self.hi, self.cell_size, self.resolution, self.cell_start, self.cell_prims

    def cell_counts(self) -> np.ndarray:
        """(nz, ny, nx) int64: how many primitives each cell lists."""
        nx, ny, nz = self.resolution
        return np.diff(self.cell_start).reshape(nz, ny, nx)

    def occupied_cells(self) -> np.ndarray:
        """(K, 3) int64: ``(i, j, k)`` of every cell that lists at least one primitive."""
        k, j, i = np.nonzero(self.cell_counts())
        return np.column_stack([i, j, k])

    def cell_boxes(self, cells) -> np.ndarray:
        """(K, 2, 3) float64: world-space ``(lo, hi)`` corners of cells ``(i, j, k)``."""
        cells = np.asarray(cells, dtype=float).reshape(-1, 3)
        lo = self.lo + cells * self.cell_size
        return np.stack([lo, lo + self.cell_size], axis=1)

    def prims_in_cell(self, i: int, j: int, k: int) -> np.ndarray:
        """Primitive indices listed in cell ``(i, j, k)``."""
        nx, ny, _ = self.resolution
        c = (k * ny + j) * nx + i
        return self.cell_prims[self.cell_start[c]:self.cell_start[c + 1]]


def empty_kernel_tuple() -> tuple:
    """The kernels' stand-in when no grid is used (one empty cell)."""
    z = np.zeros(3)
    return z, z, np.ones(3), np.zeros(3, np.int64), np.zeros(1, np.int64), np.zeros(0, np.int64)


def build_grid(geometry) -> UniformGrid:
    """Cut the box around ``geometry``'s primitives into cells and list them per cell."""
    n = geometry.n_prims
    if n == 0:
        z = np.zeros(3)
        return UniformGrid(z, z, np.ones(3), np.zeros(3, np.int64), np.zeros(1, np.int64),
                           np.zeros(0, np.int64))
    lo, hi = geometry.lo.min(axis=0), geometry.hi.max(axis=0)
    extent = hi - lo
    per_unit = 3.0 * n ** (1.0 / 3.0) / extent.max()
    resolution = np.clip(np.round(extent * per_unit), 1, MAX_RESOLUTION).astype(np.int64)
    cell_size = extent / resolution
    # Cells overlapped by each primitive's box: first and last index per axis.
    first = np.clip(np.floor((geometry.lo - lo) / cell_size), 0, resolution - 1).astype(np.int64)
    last = np.clip(np.floor((geometry.hi - lo) / cell_size), 0, resolution - 1).astype(np.int64)
    span = last - first + 1
    counts = span.prod(axis=1)
    prim = np.repeat(np.arange(n), counts)
    local = np.arange(counts.sum()) - np.repeat(np.cumsum(counts) - counts, counts)
    sx, sy = span[prim, 0], span[prim, 1]
    i = first[prim, 0] + local % sx
    j = first[prim, 1] + (local // sx) % sy
    k = first[prim, 2] + local // (sx * sy)
    nx, ny, nz = resolution
    cell = (k * ny + j) * nx + i
    order = np.argsort(cell, kind="stable")
    cell_start = np.zeros(nx * ny * nz + 1, dtype=np.int64)
    np.cumsum(np.bincount(cell, minlength=nx * ny * nz), out=cell_start[1:])
    return UniformGrid(lo, hi, cell_size, resolution, cell_start, prim[order].astype(np.int64))


def cells_on_ray(grid: UniformGrid, origin, direction, t_min: float = 0.0,
                 t_max: float = np.inf) -> np.ndarray:
    """The cells the ray ``o + t d``, ``t_min <= t <= t_max``, crosses, in order.

    This is the same 3D-DDA walk the tracer uses, so for a traced ray with
    ``t_max`` set to its hit distance it lists the cells whose primitives were
    tested.

    Returns
    -------
    (K, 3) int64, ``(i, j, k)`` per cell.
    """
    o = tuple(float(x) for x in origin)
    d = tuple(float(x) for x in direction)
    from core.image_order.kernels.accel_grid import walk_cells

    out = np.empty((int(grid.resolution.sum()) + 3, 3), dtype=np.int64)
    count = walk_cells(o, d, float(t_min), float(t_max), grid.kernel_tuple(), out)
    return out[:count].copy()
