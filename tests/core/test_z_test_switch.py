"""The z-test switch: without it, back-face culling alone shows the lecture's wrong picture.

On a convex solid back-face culling alone decides what is seen; on the
non-convex notched prism (Fig. VII.4b) a front-facing wall is partly hidden by
the solid's other arm, and only the z-buffer's depth comparison hides that
part.  The reference for "what is really seen" is the ray caster (image
order): the first hit of each pixel's ray.
"""

from __future__ import annotations

import brute_force
import numpy as np

from core import presets
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.object_order.pipeline import RasterSettings, render_raster


def _nearest_triangle(scene, dx: float, dy: float) -> np.ndarray:
    """(H, W) index of the mesh triangle each pixel's ray hits first, the ray shifted
    by ``(dx, dy)`` pixels from the pixel centre (-1: nothing), by brute force."""
    cam, mesh = scene.camera, scene.objects[0]
    hw, hh = cam.half_extent(1.0)
    xs = ((np.arange(cam.width) + 0.5 + dx) / cam.width * 2 - 1) * hw
    ys = (1 - (np.arange(cam.height) + 0.5 + dy) / cam.height * 2) * hh
    px, py = np.meshgrid(xs, ys)
    d = np.stack([px, py, -np.ones_like(px)], -1).reshape(-1, 3) @ cam.world_from_view[:3, :3].T
    o = np.broadcast_to(np.asarray(cam.eye, dtype=float), d.shape)
    best, winner = np.full(len(d), np.inf), np.full(len(d), -1)
    for k, tri in enumerate(mesh.vertices[mesh.triangles]):
        t = brute_force.hit_triangle(o, d, *tri)
        closer = t < best
        best[closer], winner[closer] = t[closer], k
    return winner.reshape(cam.height, cam.width)


def _wrongly_visible(scene, settings) -> tuple[int, int]:
    """Pixels where the rasterizer shows a surface behind the ray caster's first hit,
    counted over the pixels that are not at an edge; and how many pixels were compared.

    A pixel is at an edge when moving its ray by 1/20 pixel changes the triangle it
    hits first (the rasterizer snaps corners to 1/256 pixel, the ray caster does not).
    """
    traced = render_trace(scene, TraceSettings(mode="raycast"))
    raster = render_raster(scene, settings)
    shifts = [_nearest_triangle(scene, dx, dy) for dx, dy in ((0.05, 0), (-0.05, 0), (0, 0.05), (0, -0.05))]
    sure = np.all([s == shifts[0] for s in shifts], axis=0) & (shifts[0] >= 0)
    assert np.all(traced.object_index[sure] == 0)  # the ray caster sees the prism there too
    assert np.all(np.isfinite(raster.depth[sure]))  # and the rasterizer draws something
    behind = raster.depth > traced.depth * (1 + 1e-9)
    return int(np.sum(behind & sure)), int(sure.sum())


def test_culling_alone_shows_the_hidden_part_of_the_notch_wall():
    scene = presets.culling_notched()
    wrong, compared = _wrongly_visible(scene, RasterSettings(back_face_culling=True, z_test=False))
    assert compared > 10_000
    assert wrong > 100  # the notch's inner wall, drawn after the arm that hides it


def test_the_z_test_hides_it_again():
    scene = presets.culling_notched()
    wrong, compared = _wrongly_visible(scene, RasterSettings(back_face_culling=True, z_test=True))
    assert compared > 10_000
    assert wrong == 0


def test_without_the_z_test_every_fragment_is_written_in_drawing_order():
    scene = presets.culling_notched()
    result = render_raster(scene, RasterSettings(back_face_culling=False, z_test=False, record_steps=True))
    assert result.stats["fragments_failed"] == 0
    assert result.stats["settings"]["z_test"] is False
    # The image is what the last polygon drawn at each pixel left there (all opaque).
    history, last = result.history, {}
    for p in range(history.n_steps):
        cols, rows, _, passed = history.polygon_fragments(p)
        assert passed.all()
        for x, y in zip(cols.tolist(), rows.tolist(), strict=True):
            last[y, x] = p
    for (y, x), p in list(last.items())[::97]:
        assert np.array_equal(result.color[y, x], result.draw.color[p])
        events = history.pixel_history(x, y)
        assert events[-1].polygon == p and all(e.passed for e in events)


def test_on_a_convex_solid_culling_alone_is_enough_and_without_it_the_picture_is_worse():
    convex = presets.culling_pyramid()
    assert _wrongly_visible(convex, RasterSettings(back_face_culling=True, z_test=False))[0] == 0
    notched = presets.culling_notched()
    culled, _ = _wrongly_visible(notched, RasterSettings(back_face_culling=True, z_test=False))
    neither, _ = _wrongly_visible(notched, RasterSettings(back_face_culling=False, z_test=False))
    assert neither > 10 * culled  # back faces drawn over front ones wherever they come later
