"""The frames of the two animations export writes: the z-buffer's steps and an orbit of the observer.

- *z-buffer steps*: frame 0 shows the cleared buffers (image memory holds the
  background, the z-buffer the far plane); frame k the buffers after the
  first k polygons, the fragments of polygon k outlined (magenta where they
  passed the z-test, cyan where they failed; inside, the polygon keeps its
  own colour) and a frame counter under them.
- *orbit*: the observer walks once around the target, yaw growing by
  360° / frames; each frame is one pane's picture from there.

Frames are linear RGB (H, W, 3), produced one at a time (generators), so an
MP4 never holds more than one; the caller shows the progress and stops early.
Before anything is rendered, :func:`steps_problem` says when the steps would
make no sensible animation.  Imports neither Qt nor VTK.
"""

from __future__ import annotations

from collections.abc import Callable, Iterator
from dataclasses import replace

import numpy as np

from app.export.picture_sheet import Panel, compose, depth_grey, depth_ramp, sheet_shape

MAX_FRAMES = 1000
"""The most frames an animation may have (100 s at 10 frames a second)."""
PASSED_TINT, FAILED_TINT = (1.0, 0.1, 0.8), (0.0, 0.8, 1.0)
CAPTION_LINES = 4  # under every frame of the steps, so all frames have one size
RAMP_ROWS = 8


def _step_panels(color, depth, near, far) -> list[Panel]:
    return [Panel("image memory", color),
            Panel("z-buffer", depth, depth_ramp(near, far, depth.shape[1], RAMP_ROWS),
                  (f"near {near:g}", f"far {far:g}"))]


def polygons_at_most(scene) -> int:
    """How many polygons the z-buffer may draw for ``scene``: its triangles, spheres tessellated.

    Culling only removes polygons and clipping keeps one polygon per
    triangle, so the steps never outnumber this.
    """
    from core import budget

    spheres, triangles = budget.count_primitives(scene)
    return triangles + spheres * budget.SPHERE_TRIANGLES_RASTER


def steps_problem(scene, extension: str, limit: int) -> str | None:
    """Why the z-buffer steps of ``scene`` make no sensible animation; ``None`` when they do.

    Checked before anything is rendered: up to one frame per triangle (and
    one for the cleared buffers) must stay within :data:`MAX_FRAMES`, and a
    GIF, which holds all its frames until it is written, within ``limit``
    bytes.  The message names what to reduce.
    """
    from core import budget

    polygons = polygons_at_most(scene)
    spheres, _ = budget.count_primitives(scene)
    if polygons + 1 > MAX_FRAMES:
        each = "its sphere" if spheres == 1 else f"each of its {spheres} spheres"
        tessellated = (f", {each} tessellated into {budget.SPHERE_TRIANGLES_RASTER:,} triangles" if spheres
                       else "")
        return (f"the scene has {polygons:,} triangles{tessellated}, hence up to {polygons:,} steps; "
                f"an animation shows at most {MAX_FRAMES - 1:,}; use a scene with fewer objects "
                "or triangles")
    cam = scene.camera
    blank = np.broadcast_to(0.0, (cam.height, cam.width, 3))
    h, w = sheet_shape(_step_panels(blank, blank, cam.near, cam.far), 2, CAPTION_LINES)
    need = (polygons + 1) * h * w * 3
    if extension == ".gif" and need > limit:
        return (f"a GIF of up to {polygons + 1:,} frames of {w} × {h} pixels needs about "
                f"{budget.format_bytes(need)}, more than the {budget.format_bytes(limit)} allowed; "
                "write an MP4, or use a smaller image or fewer triangles")
    return None


def zbuffer_steps(scene, settings) -> tuple[int, Iterator[np.ndarray]]:
    """Render ``scene`` in object order with every step recorded; the number of frames and the frames.

    ``settings`` is a :class:`core.object_order.pipeline.RasterSettings`
    (its ``record_steps`` is switched on here).
    """
    from core.object_order import zbuffer
    from core.object_order.pipeline import render_raster

    cam = scene.camera
    result = render_raster(scene, replace(settings, record_steps=True))
    history = result.history
    n = history.n_steps
    names = [o.name for o in scene.objects]
    ortho = cam.projection == "orthographic"

    def frames():
        for k in range(n + 1):
            color, zbuf = history.buffers(k)
            distance = zbuffer.distance_from_window_depth(zbuf, cam.near, cam.far, ortho)
            depth = depth_grey(np.where(zbuf < zbuffer.FAR_DEPTH, distance, np.inf), cam.near, cam.far)
            if k == 0:
                text = "cleared buffers: image memory holds the background, the z-buffer the far plane"
            else:
                p = k - 1
                cols, rows, _, passed = history.polygon_fragments(p)
                for image in (color, depth):
                    _outline(image, cols[passed], rows[passed], PASSED_TINT)
                    _outline(image, cols[~passed], rows[~passed], FAILED_TINT)
                text = (f"polygon {k} of {names[history.object_index[p]]} (triangle "
                        f"{history.triangle_index[p]}): {int(passed.sum()):,} fragments passed the "
                        f"z-test (outlined magenta), {int((~passed).sum()):,} failed (cyan)")
            yield compose(_step_panels(color, depth, cam.near, cam.far), 2,
                          [f"frame {k} / {n}, step {k}: {text}"], lines=CAPTION_LINES)

    return n + 1, frames()


def _outline(image: np.ndarray, cols, rows, color) -> None:
    """Paint ``color`` on the pixels ``(rows, cols)`` that border a pixel outside them (or the
    image's edge); the pixels inside keep their colour."""
    mask = np.zeros(image.shape[:2], bool)
    mask[rows, cols] = True
    padded = np.pad(mask, 1)
    inside = padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
    image[mask & ~inside] = color


def orbit_frames(scene, frames: int, picture: Callable) -> Iterator[np.ndarray]:
    """The observer walks once around the target in ``frames`` steps; each frame is ``picture(scene)``."""
    cam = scene.camera
    for i in range(frames):
        moved = cam.orbit(cam.yaw_deg + 360.0 * i / frames, cam.pitch_deg)
        yield picture(replace(scene, camera=moved))
