"""How the 3D pane is drawn: cheaply, and the same picture as VTK's most careful way."""

import numpy as np
import pytest
from PySide6.QtGui import QImage, QSurface
from window_helpers import RENDER_TIMEOUT_MS

from core import presets
from core.files.lesson_file import shipped_lessons


def _drawn(view):
    """The pane drawn now, as (H, W, 3) ints (a screenshot alone shows the last draw)."""
    view.plotter.render()
    return view.plotter.screenshot(None, return_img=True).astype(int)


@pytest.mark.parametrize("build", [presets.lecture_scene, presets.transparent_panes])
def test_translucent_surfaces_look_as_with_vtks_order_independent_translucency(qtbot, window, build):
    window.model.set_scene(build())
    view = window.scene_view
    renderer = view.plotter.renderer
    qtbot.waitUntil(renderer.GetUseFXAA)  # at rest: the frustum's translucent faces are drawn too
    assert not renderer.GetUseOIT()
    ours = _drawn(view)
    renderer.SetUseOIT(True)  # the reference: VTK's order-independent translucency
    reference = _drawn(view)
    renderer.SetUseOIT(False)
    levels = np.abs(ours - reference).max(axis=2)
    assert np.percentile(levels, 99) <= 8  # 8-bit levels; edges of overlapping panes may differ more


def test_repaints_of_the_window_never_go_through_opengl(window):
    # One OpenGL widget anywhere would make Qt compose the whole window through OpenGL at every repaint.
    assert window.windowHandle().surfaceType() == QSurface.SurfaceType.RasterSurface


def test_the_pane_shows_what_vtk_draws_background_and_all(qtbot, window):
    view = window.scene_view
    qtbot.waitUntil(view.plotter.renderer.GetUseFXAA)  # at rest: anti-aliased, frustum faces drawn
    view.plotter.render()
    shown = view.plotter.grab().toImage().convertToFormat(QImage.Format.Format_RGB888)
    h, w = shown.height(), shown.width()
    rows = np.frombuffer(shown.constBits(), np.uint8).reshape(h, shown.bytesPerLine())
    painted = rows[:, :3 * w].reshape(h, w, 3).astype(int)
    drawn_by_vtk = _drawn(view)[..., :3]  # VTK draws the gradient background itself here
    levels = np.abs(painted - drawn_by_vtk).max(axis=2)
    assert np.mean(levels <= 2) >= 0.95  # all but the anti-aliased edges against the background


def test_every_polygon_the_frustum_cut_is_outlined_and_all_are_one_actor(qtbot, window):
    lesson = next(i for i, lesson in enumerate(shipped_lessons()) if lesson.id == "frustum")
    window.lesson_panel.select(lesson, 0)
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    cut = window.tab("object order").widget.result.clipping.clipped_polygons()
    assert len(cut) > 50  # the lesson's spheres cross the frustum's planes
    qtbot.waitUntil(lambda: bool(window.scene_view.overlay_parts("clipped")))
    (outlines,) = window.scene_view.overlay_parts("clipped")  # one actor: each was a millisecond a draw
    assert outlines.n_lines == len(cut)
    assert np.allclose(outlines.points, np.vstack(cut))
    cells = outlines.lines
    start = 0
    for polygon in cut:  # each polygon's corners in order, back to the first
        n = cells[start]
        ids = cells[start + 1:start + 1 + n]
        assert n == len(polygon) + 1 and ids[0] == ids[-1]
        assert np.allclose(outlines.points[ids[:-1]], polygon)
        start += n + 1
