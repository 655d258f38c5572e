"""Back-face culling alone on a non-convex solid, against the z-buffer.

On a convex solid every face turned towards the observer is entirely
visible, so dropping the back faces solves visibility.  The notched prism
(:func:`core.shapes.notched_prism`, the lecture's Fig. VII.4b) is not
convex: the inner wall of its notch faces the observer, yet the solid's
other arm hides part of it.  Drawn with culling alone, polygon after polygon
with the later one painted over the earlier, that wall shows where it should
be hidden.  The app's rasterizer with the z-buffer
(:func:`core.object_order.pipeline.render_raster`) resolves it; the ray
caster (:mod:`core.hard_cases.ray_cast_reference`) says which wall each pixel
really shows.
"""

from __future__ import annotations

import numpy as np

from core import shapes
from core.camera import Camera
from core.hard_cases.ray_cast_reference import reference
from core.hard_cases.result import CaseImage, CaseResult, Parameter, Row
from core.object_order import rasterization
from core.object_order.pipeline import render_raster
from core.object_order.stages import back_face_culling
from core.scene import Material, Mesh, Scene

BACKGROUND = np.array([0.05, 0.06, 0.1])
TARGET = np.array([0.0, 0.7, 0.0])


def _camera(yaw_deg: float) -> Camera:
    base = Camera(eye=(2.5, 3.2, 6.5), target=tuple(TARGET), fov_y_deg=28.0, near=1.0, far=20.0,
                  width=160, height=120)
    return base.orbit(yaw_deg, base.pitch_deg)


def _walls(mesh: Mesh) -> np.ndarray:
    """(T,) int64: triangles in the same plane with the same outward normal form one wall."""
    n = np.round(mesh.normals, 9)
    offset = np.round(np.einsum("tk,tk->t", mesh.normals, mesh.corners[:, 0]), 9)
    _, wall = np.unique(np.column_stack([n, offset]), axis=0, return_inverse=True)
    return wall.ravel()


#: One linear-RGB colour per wall (no yellow: that marks wrong pixels).
PALETTE = np.array([(0.05, 0.25, 0.8), (0.1, 0.6, 0.15), (0.7, 0.08, 0.08), (0.45, 0.1, 0.6),
                    (0.05, 0.5, 0.55), (0.6, 0.25, 0.05), (0.3, 0.3, 0.3), (0.75, 0.4, 0.6)])
WRONG = np.array([1.0, 0.85, 0.0])


def painters_culling_only(corners: np.ndarray, camera: Camera) -> np.ndarray:
    """Culling alone: the front faces drawn in order, each over the earlier ones, no depth test.

    Parameters
    ----------
    corners : (T, 3, 3) float64, world space.

    Returns
    -------
    (H, W) int64, the triangle shown per pixel (-1: none).
    """
    view = np.column_stack([corners.reshape(-1, 3), np.ones(3 * len(corners))]) @ camera.view_from_world.T
    faces = back_face_culling(view[:, :3], np.arange(3 * len(corners)).reshape(-1, 3), False)
    clip = view @ camera.clip_from_view.T
    xy, _ = rasterization.window_coordinates(clip, camera.width, camera.height)
    shown = np.full((camera.height, camera.width), -1)
    for t in np.flatnonzero(faces.visible):
        covered = rasterization.coverage(rasterization.snap(xy[3 * t:3 * t + 3]), camera.width, camera.height)
        shown[covered] = t
    return shown


def _zbuffer_walls(mesh: Mesh, wall: np.ndarray, camera: Camera, palette: np.ndarray) -> np.ndarray:
    """The app's rasterizer (culling and z-buffer), one flat colour per wall; the wall seen per pixel."""
    objects = tuple(
        Mesh(mesh.vertices, mesh.triangles[wall == w], Material(color=tuple(palette[w]), ambient=1.0,
                                                                 diffuse=0.0), f"wall {w}")
        for w in range(len(palette))
    )
    image = render_raster(Scene(camera=camera, objects=objects, background=tuple(BACKGROUND))).color
    colors = np.vstack([palette, BACKGROUND])
    nearest = np.argmin(((image[:, :, None, :] - colors[None, None]) ** 2).sum(axis=-1), axis=-1)
    return np.where(nearest == len(palette), -1, nearest)


def _picture(walls_seen: np.ndarray, palette: np.ndarray, wrong: np.ndarray) -> np.ndarray:
    image = np.where(walls_seen[..., None] >= 0, palette[np.maximum(walls_seen, 0)], BACKGROUND)
    image[wrong] = WRONG
    return image


def non_convex_culling(yaw_deg: float = 45.0) -> CaseResult:
    """The notched prism seen from the culling lesson's camera, orbited by ``yaw_deg``.

    Parameters
    ----------
    yaw_deg : float, degrees the observer is moved around the prism's vertical axis.
    """
    camera = _camera(yaw_deg)
    mesh = shapes.notched_prism((0.0, 0.0, 0.0), (2.6, 1.6, 2.2), (1.2, 1.0))
    wall = _walls(mesh)
    palette = PALETTE[:int(wall.max()) + 1]
    seen, certain = reference(camera, mesh.corners)
    truth = np.where(seen >= 0, wall[np.maximum(seen, 0)], -1)
    painted = painters_culling_only(mesh.corners, camera)
    naive = np.where(painted >= 0, wall[np.maximum(painted, 0)], -1)
    robust = _zbuffer_walls(mesh, wall, camera, palette)
    wrong_naive = (naive != truth) & certain
    wrong_robust = (robust != truth) & certain
    view = mesh.vertices @ camera.view_from_world[:3, :3].T + camera.view_from_world[:3, 3]
    faces = back_face_culling(view, mesh.triangles, False)
    rows = (
        Row("pixels showing the wrong wall", int(wrong_naive.sum()), int(wrong_robust.sum()), 0),
        Row("faces drawn (front faces)", int(faces.visible.sum()), int(faces.visible.sum()),
            int(faces.visible.sum())),
        Row("pixels covered", int((naive >= 0).sum()), int((robust >= 0).sum()), int((truth >= 0).sum())),
    )
    return CaseResult(
        name="culling", title="10. Back-face culling alone on a non-convex solid",
        parameter=Parameter("yaw_deg", "observer moved around the prism (degrees)", yaw_deg, 0.0, 90.0,
                            log=False),
        naive_method="back-face culling, painted in order", robust_method="culling and the z-buffer",
        reference_method="ray cast per pixel (nearest wall)",
        rows=rows, naive_error=float(wrong_naive.sum()), robust_error=float(wrong_robust.sum()),
        error_unit="pixels wrong", tolerance=0.0,
        tolerance_reason="pixels within 1/64 pixel of an edge are left out; all others must agree",
        explanation=(
            "The back-face test looks at one face at a time: the notch's inner wall faces the observer, "
            "so it passes, even though the prism's other arm stands in front of part of it. Painted "
            "in order, whichever face comes later covers the earlier one, right or wrong (yellow). "
            "The z-buffer compares depths pixel by pixel and keeps the nearest, whatever the order."
        ),
        images=(CaseImage("one colour per wall; pixels showing the wrong wall in yellow",
                          _picture(naive, palette, wrong_naive), _picture(robust, palette, wrong_robust)),),
    )
