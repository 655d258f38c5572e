"""Outlines over a z-buffer image: the edges an engineering drawing would ink.

A face seen exactly edge-on covers no pixel centre, so the z-buffer draws
nothing of it: in the front view the ground plane vanishes.  Drawings keep
such faces, and the shapes' corners, visible by their edges.  Here, after
the z-buffer render, every *feature edge* of every mesh is drawn on top:

- boundary edges (a side of only one triangle, such as the ground's rim),
- creases (two faces meeting at more than :data:`CREASE_DEG`, the box's edges),
- silhouettes (one face turned to the observer, the other away).

An edge is sampled finer than a pixel and each sample is inked only where
nothing nearer was drawn: it must not lie behind the surface the z-buffer
kept there (by more than about a pixel, the depth a surface may change
within one pixel near its own edge).  The ink is the object's colour,
darkened over light pixels and lightened over dark ones, so an outline
stands out and says which object it belongs to.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.projection import pixel_from_ndc
from core.scene import Mesh
from core.srgb import LUMINANCE

CREASE_DEG = 30.0
"""Faces meeting at a larger angle than this have their shared edge drawn."""
INK = 0.2
"""An outline's colour over a light pixel: the object's colour times this (over a dark pixel,
half-way from the object's colour to white)."""
DARK = 0.18
"""Pixels of lower luminance (linear RGB) than this are dark."""
SAMPLES_PER_PIXEL = 2.0
"""Samples along an edge for every pixel it crosses."""
DEPTH_SLACK_PX = 1.5
"""A sample may lie this many pixel widths behind the surface drawn at its pixel and still show."""


def feature_edges(mesh: Mesh, camera: Camera) -> np.ndarray:
    """The edges of ``mesh`` worth drawing as seen from ``camera``, (E, 2, 3) world-space end points.

    Corners at the same place are joined first, so a mesh stored with one
    vertex per face corner has its edges found all the same.
    """
    tris = np.asarray(mesh.triangles)
    if not len(tris):
        return np.zeros((0, 2, 3))
    scale = max(float(np.abs(mesh.vertices).max()), 1.0)
    _, weld = np.unique(np.round(mesh.vertices / (scale * 1e-9)), axis=0, return_inverse=True)
    corners = mesh.vertices[tris]
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1)
    keep = lengths > 0  # degenerate triangles have no normal and draw nothing
    tris, corners, normals = tris[keep], corners[keep], normals[keep] / lengths[keep, None]
    if not len(tris):  # every triangle degenerate, e.g. a sphere of radius 1e-300
        return np.zeros((0, 2, 3))
    if camera.projection == "orthographic":
        facing = normals @ -camera.forward > 0
    else:
        facing = np.einsum("ij,ij->i", normals, np.asarray(camera.eye) - corners[:, 0]) > 0
    ids = weld.reshape(-1)[tris]
    pairs = np.concatenate([ids[:, [0, 1]], ids[:, [1, 2]], ids[:, [2, 0]]])
    owner = np.tile(np.arange(len(tris)), 3)
    ends = np.concatenate([tris[:, [0, 1]], tris[:, [1, 2]], tris[:, [2, 0]]])
    key = np.sort(pairs, axis=1)
    order = np.lexsort((key[:, 1], key[:, 0]))
    key, owner, ends = key[order], owner[order], ends[order]
    same = np.all(key[1:] == key[:-1], axis=1)  # sorted: an edge's two triangles sit side by side
    starts = np.flatnonzero(np.concatenate([[True], ~same]))  # each edge's first (or only) triangle
    shared = np.zeros(len(starts), bool)
    shared[starts < len(key) - 1] = same[starts[starts < len(key) - 1]]
    a, b = owner[starts], owner[np.minimum(starts + 1, len(key) - 1)]
    crease = np.einsum("ij,ij->i", normals[a], normals[b]) < np.cos(np.radians(CREASE_DEG))
    drawn = starts[~shared | crease | (facing[a] != facing[b])]
    return mesh.vertices[ends[drawn]]


def outlined(color: np.ndarray, depth: np.ndarray, meshes, camera: Camera) -> np.ndarray:
    """``color`` with the feature edges of ``meshes`` inked where nothing nearer hides them.

    Parameters
    ----------
    color : (H, W, 3) the z-buffer render's image memory (linear RGB).
    depth : (H, W) its distances along the viewing axis, +inf where nothing was drawn.
    meshes : the meshes that were drawn (spheres already tessellated), each with a material.
    camera : the camera of the render.

    Returns
    -------
    (H, W, 3) a new image.
    """
    out = np.array(color, dtype=float, copy=True)
    h, w = depth.shape
    view_from_world, clip_from_view = camera.view_from_world, camera.clip_from_view
    for mesh in meshes:
        edges = feature_edges(mesh, camera)
        if not len(edges):
            continue
        ends_view = np.einsum("ij,ekj->eki", view_from_world[:3, :3], edges) + view_from_world[:3, 3]
        ends_px = _pixels(ends_view, clip_from_view, w, h)
        span = np.nan_to_num(np.linalg.norm(ends_px[:, 1] - ends_px[:, 0], axis=1), nan=0.0)
        steps = np.clip(np.ceil(span * SAMPLES_PER_PIXEL), 1, 4 * (w + h)).astype(int)
        edge = np.repeat(np.arange(len(edges)), steps + 1)
        t = np.concatenate([np.linspace(0.0, 1.0, n + 1) for n in steps])[:, None]
        points = ends_view[edge, 0] * (1 - t) + ends_view[edge, 1] * t  # sampled in view space
        px = _pixels(points[:, None], clip_from_view, w, h)[:, 0]
        distance = -points[:, 2]
        ok = np.isfinite(px).all(axis=1) & (distance >= camera.near) & (distance <= camera.far)
        col = np.floor(px[:, 0]).astype(np.int64, copy=False)
        row = np.floor(px[:, 1]).astype(np.int64, copy=False)
        ok &= (col >= 0) & (col < w) & (row >= 0) & (row < h)
        col, row, distance = col[ok], row[ok], distance[ok]
        slack = DEPTH_SLACK_PX * _pixel_size(camera, distance)
        seen = distance <= depth[row, col] + slack
        row, col = row[seen], col[seen]
        tint = np.asarray(mesh.material.color, float)
        dark = out[row, col] @ LUMINANCE < DARK
        out[row, col] = np.where(dark[:, None], 0.5 + 0.5 * tint, INK * tint)
    return out


def _pixels(view_points: np.ndarray, clip_from_view: np.ndarray, width: int, height: int) -> np.ndarray:
    """(..., 3) view-space points to (..., 2) pixel coordinates; NaN behind the eye."""
    clip = np.einsum("ij,...j->...i", clip_from_view[:, :3], view_points) + clip_from_view[:, 3]
    w = clip[..., 3:4]
    with np.errstate(divide="ignore", invalid="ignore"):
        ndc = np.where(w > 0, clip[..., :2] / w, np.nan)
    return pixel_from_ndc(ndc, width, height)


def _pixel_size(camera: Camera, distance: np.ndarray) -> np.ndarray:
    """The height of one pixel, in scene units, at ``distance`` along the viewing axis."""
    if camera.projection == "orthographic":
        return np.full_like(distance, camera.ortho_height / camera.height)
    return 2.0 * distance * np.tan(np.radians(camera.fov_y_deg) / 2.0) / camera.height
