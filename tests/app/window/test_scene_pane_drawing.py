"""How the 3D pane is drawn: cheaply, and the same picture as VTK's most careful way."""

from dataclasses import replace

import numpy as np
import pytest
from PySide6.QtGui import QSurface
from qt_fixtures import rgb_pixels
from window_helpers import RENDER_TIMEOUT_MS

from core import presets
from core.lessons.lesson_file import shipped_lessons


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
    painted = rgb_pixels(view.plotter.grab().toImage()).astype(int)
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


def _objects_drawn(view):
    """The 3D pane's object actors and the colour each is drawn in."""
    return [(actor, actor.prop.color.float_rgb) for name, actor in view.plotter.renderer.actors.items()
            if name.startswith("object:")]


def test_the_same_scene_loaded_again_keeps_its_drawing_and_a_changed_object_shows_its_change(qtbot, window):
    """A lesson's next step loads its scene anew, often the same objects seen by another observer:
    the pane keeps what it drew of them, as after an edit; an object that differs is drawn as it
    now is."""
    view = window.scene_view
    before = _objects_drawn(view)
    assert len(before) == len(window.model.scene.objects)
    scene = presets.lecture_scene()  # made again: equal objects, not the same ones
    window.model.set_scene(replace(scene, camera=scene.camera.replace(fov_y_deg=scene.camera.fov_y_deg + 5)))
    again = _objects_drawn(view)
    assert len(again) == len(before) and all(a is b for (a, _), (b, _) in zip(again, before, strict=True))
    scene = presets.lecture_scene()
    first = scene.objects[0]
    green = (0.1, 0.9, 0.2)
    recoloured = replace(first, material=replace(first.material, color=green))
    window.model.set_scene(replace(scene, objects=(recoloured, *scene.objects[1:])))
    after = _objects_drawn(view)
    assert len(after) == len(before)
    assert sum(np.allclose(colour, green, atol=0.5 / 255) for _, colour in after) == 1
    assert sum(any(a is b for b, _ in before) for a, _ in after) == len(before) - 1


def test_while_the_window_paints_nothing_the_pane_draws_nothing_and_it_draws_once_the_window_paints(
        qtbot, window):
    # A new text size, or entering presentation mode, is laid out with the window's painting off and
    # painted once at its end: a draw of the 3D pane meanwhile was never seen, and made those turns longer.
    qtbot.waitUntil(window.scene_view.plotter.renderer.GetUseFXAA, timeout=RENDER_TIMEOUT_MS)  # at rest
    view = window.scene_view.view
    draws, tries = [], []
    view.plotter.ren_win.AddObserver("EndEvent", lambda *_: draws.append(view.plotter.renderer.GetUseFXAA()))
    view._render_timer.timeout.connect(lambda: tries.append(True))
    window.setUpdatesEnabled(False)
    cam = window.model.camera
    window.model.set_camera(cam.orbit(cam.yaw_deg + 10, cam.pitch_deg))
    qtbot.waitUntil(lambda: len(tries) >= 3 or bool(draws))  # the draw was due three times
    assert draws == []
    window.setUpdatesEnabled(True)
    qtbot.waitUntil(lambda: bool(draws), timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: any(draws), timeout=RENDER_TIMEOUT_MS)  # and drawn smooth once at rest
    assert view.plotter.picture is not None
