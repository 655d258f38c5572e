"""What the object-order panel shows at one step of a recorded render, made in any thread.

Replaying the buffers, encoding them for the screen and wording the caption take
tens of milliseconds at 320 × 240; a worker makes the picture of the step the
panel will show with the render itself, so showing it costs the window little.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from core.in_words import counted
from core.object_order import zbuffer
from core.object_order.pipeline import RasterResult
from core.scene import Scene
from views.images.depth_view import depth_to_grey
from views.images.image_view import DisplayImage, display_image, mask_outline


@dataclass(frozen=True)
class StepPicture:
    """The buffers after the first ``step`` polygons, ready to paint.

    Attributes
    ----------
    step : polygons drawn so far.
    image : the image memory.
    depth : (H, W) distances along the viewing axis, +inf where nothing was drawn.
    depth_image : the z-buffer as a grey scale (near dark, far white).
    mask : (H, W) bool, the fragments of the polygon drawn at this step (``None`` at step 0).
    caption : what happened at this step, in words.
    polygon : (N, 3) world vertices of that polygon (``None`` at step 0).
    outline : the mask's outline (:func:`views.images.image_view.mask_outline`), for both buffers.
    coming : at step 0, (N, 3) world vertices of the first polygon, drawn next (``None`` otherwise,
        or when there is none): its edges show over the empty grid which pixel centres it will cover.
    """

    step: int
    image: DisplayImage
    depth: np.ndarray
    depth_image: DisplayImage
    mask: np.ndarray | None
    caption: str
    polygon: np.ndarray | None
    outline: np.ndarray | None = None
    coming: np.ndarray | None = None


def polygon_name(result: RasterResult, scene: Scene, p: int) -> str:
    draw = result.draw
    name = scene.objects[int(draw.object_index[p])].name
    return f"{name}, triangle {int(draw.triangle_index[p])}"


def step_picture(result: RasterResult, scene: Scene, k: int) -> StepPicture:
    """The picture of step ``k`` of ``result``, rendered from ``scene``."""
    history = result.history
    color, zbuf = history.buffers(k)
    distance = zbuffer.distance_from_window_depth(zbuf, history.near, history.far, history.orthographic)
    depth = np.where(zbuf >= zbuffer.FAR_DEPTH, np.inf, distance)
    depth_image = display_image(depth_to_grey(depth, history.near, history.far), linear=False)
    if k == 0:
        caption = (f"Step 0 of {history.n_steps}: image memory cleared to the background, "
                   f"z-buffer cleared to the far plane ({history.far:g}).")
        coming = result.draw.polygons.world_vertices(0) if history.n_steps else None
        return StepPicture(k, display_image(color), depth, depth_image, None, caption, None, coming=coming)
    p = k - 1
    cols, rows, _, passed = history.polygon_fragments(p)
    mask = np.zeros((history.height, history.width), bool)
    mask[rows, cols] = True
    draw = result.draw
    kind = "transparent, blended" if draw.transparent[p] else "opaque"
    caption = (f"Step {k} of {history.n_steps}: polygon {k} — {polygon_name(result, scene, p)} ({kind}): "
               f"{counted(len(cols), 'fragment')}, {int(passed.sum()):,} passed the z-test, "
               f"{int((~passed).sum()):,} failed.")
    return StepPicture(k, display_image(color), depth, depth_image, mask, caption,
                       draw.polygons.world_vertices(p), mask_outline(mask))
