"""A polygon with a corner behind the eye: projected as it is, or clipped before the divide.

The perspective divide by ``w`` is only meaningful in front of the eye.  A
corner behind it has ``w < 0``; dividing sends it to the mirrored side of
the screen, and the triangle drawn from the divided corners is a wrong shape
smeared across the image.  The app's pipeline clips in homogeneous clip
space first (:mod:`core.object_order.clipping`), so every corner it divides
has ``w >= near``.  Both renders come from the app's rasterizer
(:func:`core.object_order.pipeline.render_raster`, clipping on and off); the
reference is the ray caster (:mod:`core.hard_cases.ray_cast_reference`).
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.hard_cases.ray_cast_reference import reference
from core.hard_cases.result import CaseImage, CaseResult, Parameter, Row
from core.object_order.pipeline import RasterSettings, render_raster
from core.object_order.zbuffer import FAR_DEPTH
from core.scene import Material, Mesh, Scene

CAMERA = Camera(eye=(0.0, 1.0, 5.0), target=(0.0, 1.0, 0.0), fov_y_deg=50.0, near=0.5, far=30.0,
                width=120, height=90)
FRONT = ((-1.8, 0.2, 1.0), (1.5, 0.6, 0.0))
COLOR = (0.95, 0.7, 0.2)


def triangle_behind(behind: float) -> np.ndarray:
    """(3, 3) world-space corners: two in front of the eye, one ``behind`` units behind it."""
    eye = np.asarray(CAMERA.eye)
    return np.array([*FRONT, eye + (0.7, 0.9, behind)], dtype=float)


def _render(corners: np.ndarray, clipping: bool):
    mesh = Mesh(corners, [[0, 1, 2]], Material(color=COLOR, ambient=1.0, diffuse=0.0), "triangle")
    scene = Scene(camera=CAMERA, objects=(mesh,), background=(0.05, 0.06, 0.1))
    settings = RasterSettings(back_face_culling=False, frustum_culling=False, clipping=clipping)
    return render_raster(scene, settings)


def behind_the_eye(behind: float = 2.0) -> CaseResult:
    """A triangle reaching ``behind`` units behind the eye, drawn without and with clipping.

    Parameters
    ----------
    behind : float > 0, scene units along the eye's backward axis.
    """
    corners = triangle_behind(behind)
    naive, robust = _render(corners, False), _render(corners, True)
    seen, certain = reference(CAMERA, corners[None])
    should = seen >= 0
    wrong = {name: int((((r.zbuffer < FAR_DEPTH) != should) & certain).sum())
             for name, r in (("naive", naive), ("robust", robust))}
    w_behind = float((CAMERA.clip_from_world @ np.append(corners[2], 1.0))[3])
    divided = (CAMERA.clip_from_world @ np.append(corners[2], 1.0))
    ndc = divided[:3] / divided[3]
    rows = (
        Row("pixels wrong (against the ray caster)", wrong["naive"], wrong["robust"], 0),
        Row("w of the corner behind the eye", w_behind, w_behind, w_behind),
        Row("that corner divided by w: NDC x, y", f"({ndc[0]:.3g}, {ndc[1]:.3g})",
            "cut off before the divide", "none: no ray from the eye reaches it", compare=False),
        Row("pixels covered", int((naive.zbuffer < FAR_DEPTH).sum()),
            int((robust.zbuffer < FAR_DEPTH).sum()), int(should.sum())),
        Row("polygons after clipping", len(naive.draw), len(robust.draw), 1),
    )
    return CaseResult(
        name="behind_eye", title="7. A corner behind the eye: mirrored without clipping",
        parameter=Parameter("behind", "how far the third corner lies behind the eye", behind, 0.05, 50.0),
        naive_method="divide by w, then rasterize", robust_method="clip at the near plane, then divide",
        reference_method="ray cast per pixel, depth in [near, far]",
        rows=rows, naive_error=float(wrong["naive"]), robust_error=float(wrong["robust"]),
        error_unit="pixels wrong", tolerance=0.0,
        tolerance_reason="pixels within 1/64 pixel of an edge are left out; all others must agree",
        explanation=(
            "Behind the eye w is negative, so dividing by it flips the corner through the centre of "
            "the image: the triangle drawn from the divided corners points the wrong way and sweeps "
            "over pixels the polygon never covers, while missing ones it does. Clipping against "
            "-w <= z in clip space first cuts the polygon where it crosses the near plane; what is "
            "left lies in front of the eye and projects correctly."
        ),
        images=(CaseImage("the triangle as drawn", naive.color, robust.color),),
    )
