"""The window as a user drives it: move the observer, see the frustum and image follow."""

import json
import re
import threading

import numpy as np
import pytest
from PySide6.QtCore import Qt, QTimer
from PySide6.QtWidgets import QApplication, QMessageBox
from window_helpers import RENDER_TIMEOUT_MS, open_scene_file

from core import presets
from core.presets_trace import PRESETS_TRACE
from views.images.image_view import mask_outline


def _image(win):
    return win.tab("image order").widget.image.rgb


def _drawn_frustum(win):
    return np.array(win.scene_view.frustum.points)


def _move_and_wait(qtbot, win, action):
    """Do ``action``, then wait until the visible tab shows the full image of the new scene."""
    action()
    title = win.current.title
    qtbot.waitUntil(lambda: win.showing_full(title), timeout=RENDER_TIMEOUT_MS)
    return win.last_result


def test_start_shows_the_lecture_scene_and_its_image(window):
    cam = window.model.camera
    assert np.allclose(_drawn_frustum(window), cam.frustum_corners())
    image = _image(window)
    assert image.shape == (cam.height, cam.width, 3)
    # The cube, the cone and the plane are all in view: more than the background shows.
    colours = {tuple(c) for c in np.round(image.reshape(-1, 3), 1)}
    assert len(colours) > 5
    assert "rays" in window.status_caption.text()


def test_every_dock_has_a_name_of_its_own_for_scripts_and_saved_layouts(window):
    # A GUI-driven test or a script finds a dock by its object name, and QMainWindow.saveState needs
    # one; the Controls dock had none.
    from PySide6.QtWidgets import QDockWidget

    names = {dock.windowTitle(): dock.objectName() for dock in window.findChildren(QDockWidget)}
    assert names["Controls"] == "controls"
    assert all(names.values()) and len(set(names.values())) == len(names)


def test_each_menus_alt_letters_are_its_own(window):
    # Alt+F then S chose between "Save scene" and "Save scene as…", L between "Lecture scene" and
    # "Open lesson…", E between "Examples" and "Export": Qt cycles through entries sharing a letter
    # instead of opening one.
    def letters(menu):
        found = []
        for action in menu.actions():
            text = action.text().replace("&&", "")
            if "&" in text:
                found.append(text[text.index("&") + 1].lower())
            if action.menu() is not None:
                letters(action.menu())
        assert len(found) == len(set(found)), (menu.title(), found)

    for top in window.menuBar().actions():
        letters(top.menu())
    file_menu = window.menuBar().actions()[0].menu()
    assert [a.text() for a in file_menu.actions() if "&" in a.text()][:3] == [
        "&Open scene…", "&Save scene", "Save scene &as…"]


def test_the_status_line_gives_a_traced_images_total_first_then_the_stages_that_took_time(window):
    caption = window.status_caption.text()
    found = re.fullmatch(r"(\d+) × (\d+) pixels · ([\d,]+) rays · total (\d+) ms(?: \((.*) ms\))?", caption)
    assert found, caption
    cam = window.model.camera
    assert (int(found[1]), int(found[2])) == (cam.width, cam.height)
    stages = {name: int(ms) for name, ms in (part.rsplit(" ", 1) for part in found[5].split(" · "))}
    assert "primary" in stages and "shading" in stages
    assert all(ms >= 1 for ms in stages.values())  # a stage under a millisecond is left to the table
    assert sum(stages.values()) <= int(found[4]) + len(stages)  # each rounded by half a millisecond at most


def test_yaw_slider_walks_the_observer_and_everything_follows(qtbot, window):
    before_cam, before_img = window.model.camera, _image(window).copy()
    before_frustum = _drawn_frustum(window)
    _move_and_wait(qtbot, window, lambda: window.camera_panel.yaw.slider.setValue(
        round(before_cam.yaw_deg) + 40))
    cam = window.model.camera
    assert cam.yaw_deg == pytest.approx(round(before_cam.yaw_deg) + 40)
    assert cam.distance == pytest.approx(before_cam.distance)
    assert np.allclose(_drawn_frustum(window), cam.frustum_corners())
    assert not np.allclose(_drawn_frustum(window), before_frustum)
    assert np.abs(_image(window) - before_img).mean() > 0.01
    assert window.camera_panel.eye[0].value() == pytest.approx(cam.eye[0], abs=0.01)


def test_wider_viewing_angle_widens_the_frustum(qtbot, window):
    def far_width(win):
        corners = _drawn_frustum(win)
        return np.linalg.norm(corners[5] - corners[4])

    before = far_width(window)
    _move_and_wait(qtbot, window, lambda: window.camera_panel.fov.spin.setValue(70.0))
    assert window.model.camera.fov_y_deg == 70.0
    assert far_width(window) > before * 1.5


def test_keyboard_p_switches_to_orthographic(qtbot, window):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    _move_and_wait(qtbot, window, lambda: qtbot.keyClick(window, Qt.Key.Key_P))
    assert window.model.camera.projection == "orthographic"
    corners = _drawn_frustum(window)
    # A parallel projection's frustum is a box: near and far rectangles are the same size.
    assert np.linalg.norm(corners[1] - corners[0]) == pytest.approx(
        np.linalg.norm(corners[5] - corners[4]))
    assert window.camera_panel.projection.currentText() == "orthographic"


def test_near_beyond_far_is_refused_and_the_panel_restored(qtbot, window):
    before = window.model.camera
    window.camera_panel.near.setValue(before.far + 5)
    assert window.model.camera == before
    assert window.camera_panel.near.value() == pytest.approx(before.near)
    assert "far" in window.statusBar().currentMessage()


def test_bad_scene_file_shows_a_dialog_and_keeps_the_scene(qtbot, window, tmp_path, monkeypatch):
    """The dialog names the file once, then its problems, then its folder: it read "bad.json:" and
    below it "scene file /tmp/.../bad.json: 2 problems: ...", the full path broken in the middle
    by the narrow message box."""
    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda *args: shown.append(args[1:3]))
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps({"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}],
                               "lights": [{"position": [1, 2, "three"]}]}))
    before = window.model.scene
    assert not open_scene_file(qtbot, window, bad)
    assert window.model.scene == before
    ((title, text),) = shown
    assert title == "Cannot open scene" and text.count("bad.json") == 1
    first, *problems, blank, folder = text.splitlines()
    assert first == "bad.json: 2 problems:" and blank == "" and folder == f"in {tmp_path.resolve()}"
    assert sorted(p.strip().split(":")[0] for p in problems) == ["lights[0].position", "objects[0].radius"]

def test_a_scene_file_is_read_while_the_window_goes_on(qtbot, window, tmp_path):
    """A scene naming a 180,000-triangle mesh took most of a second to read on the GUI thread, the
    window frozen meanwhile: it is read off it, the status bar says so, the old scene stays until
    the new one is read, and the window keeps handling events."""
    n = 300  # a grid of n x n vertices, two triangles a square
    rows = [f"v {i / n} {j / n} 0\n" for j in range(n) for i in range(n)]
    rows += [f"f {a} {a + 1} {a + n}\nf {a + 1} {a + n + 1} {a + n}\n"
             for j in range(n - 1) for i in range(n - 1) for a in [j * n + i + 1]]
    (tmp_path / "grid.obj").write_text("".join(rows))
    path = tmp_path / "grid.json"
    path.write_text(json.dumps({"objects": [{"type": "mesh_file", "name": "grid", "path": "grid.obj"}]}))
    before = window.model.scene
    turns = []
    QTimer.singleShot(0, lambda: turns.append(window.model.scene is before))
    with qtbot.waitSignal(window.scene_file_done, timeout=30_000) as done:
        window.open_scene(path)
        assert window.model.scene is before
        assert window.statusBar().currentMessage() == "Opening grid.json…"
    assert turns == [True]  # the event loop turned while the file was read
    assert done.args == [str(path), True]
    assert window.model.scene.objects[0].triangles.shape == (2 * (n - 1) ** 2, 3)


def test_arrow_keys_walk_around_the_target(qtbot, window):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    before = window.model.camera
    _move_and_wait(qtbot, window, lambda: qtbot.keyClick(window, Qt.Key.Key_Left))
    assert window.model.camera.yaw_deg == pytest.approx(before.yaw_deg - 5.0)
    _move_and_wait(qtbot, window, lambda: qtbot.keyClick(window, Qt.Key.Key_Up))
    assert window.model.camera.pitch_deg == pytest.approx(before.pitch_deg + 5.0)
    assert window.model.camera.distance == pytest.approx(before.distance)


def _show_tab(qtbot, win, name):
    win.show_tab(name)
    qtbot.waitUntil(lambda: win.showing_full(name), timeout=RENDER_TIMEOUT_MS)


def test_the_whole_z_buffer_picture_singles_out_no_polygon(qtbot, window):
    # A lesson showing the lecture's figure whole (no z-buffer step chosen) outlined the last
    # polygon drawn in magenta in the 3D pane and both buffers, over the figure's own colours.
    window.model.set_scene(presets.zbuffer_three_polygons())
    window.model.set_step(None)
    _show_tab(qtbot, window, "object order")
    panel = window.tab("object order").widget
    assert panel.scrubber.step == panel.result.history.n_steps > 0
    assert "polygon" not in window.scene_view.overlay_names()
    assert panel.image._highlight is None and panel.depth.image._highlight is None
    window.model.set_step(1)  # a step chosen: its polygon is outlined once its picture is made
    qtbot.waitUntil(lambda: panel.image._highlight is not None)
    assert "polygon" in window.scene_view.overlay_names()


def test_a_new_scene_and_step_at_once_show_that_step_and_leave_the_old_render_alone(
        qtbot, window, monkeypatch):
    # A lesson step sets its scene (a new render starts) and then its z-buffer step. The panel used
    # to make that step's picture, on the GUI thread, of the old scene's render the new one replaces.
    from views.panels import object_order_panel

    _show_tab(qtbot, window, "object order")
    pictured = []  # (scene, step) of each picture made on the GUI thread
    real = object_order_panel.step_picture
    monkeypatch.setattr(object_order_panel, "step_picture",
                        lambda result, scene, k: pictured.append((scene, k)) or real(result, scene, k))
    scene = presets.zbuffer_three_polygons()
    window.model.set_scene(scene)
    window.model.set_step(2)
    qtbot.waitUntil(lambda: window.showing_full("object order"), timeout=RENDER_TIMEOUT_MS)
    panel = window.tab("object order").widget
    assert panel.scrubber.step == 2
    assert panel.step_caption.text().startswith(f"Step 2 of {panel.result.history.n_steps}: polygon 2 ")
    color, _ = panel.result.history.buffers(2)  # the image memory after two polygons
    assert np.allclose(panel.image.rgb, color)
    assert "polygon" in window.scene_view.overlay_names()
    # The worker pictures the step the model has once it has rendered; the GUI thread only when the
    # render ended before the step was set, and then of the new scene.
    assert all(s is scene for s, _ in pictured)


def _record_step_pictures(monkeypatch) -> list:
    """Record (step, made on the GUI thread) of each step picture the object-order panel makes."""
    from views.panels import object_order_panel

    made, real = [], object_order_panel.step_picture
    monkeypatch.setattr(object_order_panel, "step_picture", lambda result, scene, k: made.append(
        (k, threading.current_thread() is threading.main_thread())) or real(result, scene, k))
    return made


def test_a_chosen_step_is_pictured_off_the_gui_thread_with_its_polygon_outlined(qtbot, window, monkeypatch):
    # Each lesson step and scrubber move replayed the buffers on the GUI thread, holding the window.
    window.model.set_scene(presets.zbuffer_three_polygons())
    _show_tab(qtbot, window, "object order")
    panel = window.tab("object order").widget
    made = _record_step_pictures(monkeypatch)
    window.model.set_step(2)
    assert panel.scrubber.step == 2  # the scrubber follows at once, the buffers once pictured
    qtbot.waitUntil(lambda: panel.step_caption.text().startswith("Step 2 "))
    assert made == [(2, False)]
    history = panel.result.history
    color, _ = history.buffers(2)
    assert np.allclose(panel.image.rgb, color)
    cols, rows, _, _ = history.polygon_fragments(1)  # the polygon drawn at step 2 is outlined
    polygon = np.zeros((history.height, history.width), bool)
    polygon[rows, cols] = True
    outline = panel.image._highlight  # segments (x0, y0, x1, y1) between pixel corners
    assert outline is not None and len(outline) and np.array_equal(outline, mask_outline(polygon))
    assert outline[:, [0, 2]].min() == cols.min() and outline[:, [0, 2]].max() == cols.max() + 1
    assert "polygon" in window.scene_view.overlay_names()


def test_a_hidden_object_order_panel_pictures_its_step_once_shown(qtbot, window, monkeypatch):
    window.model.set_scene(presets.zbuffer_three_polygons())
    _show_tab(qtbot, window, "object order")
    panel = window.tab("object order").widget
    _show_tab(qtbot, window, "image order")
    made = _record_step_pictures(monkeypatch)
    window.model.set_step(1)  # a lesson step on the image-order tab
    assert made == [] and not panel.pending
    window.show_tab("object order")
    qtbot.waitUntil(lambda: panel.step_caption.text().startswith("Step 1 "))
    assert made == [(1, False)]
    color, _ = panel.result.history.buffers(1)
    assert np.allclose(panel.image.rgb, color)


def test_object_order_steps_through_the_z_buffer(qtbot, window):
    _show_tab(qtbot, window, "object order")
    panel = window.tab("object order").widget
    history = panel.result.history
    assert panel.scrubber.step == history.n_steps > 0
    panel.scrubber.first()
    qtbot.waitUntil(lambda: panel.step_caption.text().startswith("Step 0"))
    background = np.asarray(window.model.scene.background)
    assert np.allclose(panel.image.rgb, background)  # step 0: image memory cleared
    assert "polygon" not in window.scene_view.overlay_names()
    panel.scrubber.set_step(5)
    qtbot.waitUntil(lambda: "Step 5" in panel.step_caption.text())
    assert "polygon" in window.scene_view.overlay_names()  # the 4th polygon highlighted in 3D
    # Click the pixel at the centre of the image memory: its history lists fragments in order.
    panel.scrubber.last()
    cam = window.model.camera
    x, y = cam.width // 2, cam.height // 2
    qtbot.mouseClick(panel.image, Qt.MouseButton.LeftButton, pos=panel.image.widget_pos(x, y).toPoint())
    assert panel.picked == (x, y)
    events = history.pixel_history(x, y)
    assert panel.history.rowCount() == len(events) > 0
    assert panel.history.item(0, 0).text() == str(events[0].polygon + 1)
    assert "Nz" in panel.numbers.toPlainText()


def test_switching_a_stage_off_rerenders_with_it_off(qtbot, window):
    _show_tab(qtbot, window, "object order")
    panel = window.tab("object order").widget
    _move_and_wait(qtbot, window, lambda: panel.switches["back_face_culling"].setChecked(False))
    assert panel.result.settings.back_face_culling is False
    assert panel.result.stats["faces_culled"] == 0


def test_four_views_show_front_side_top_and_observer(qtbot, window):
    _show_tab(qtbot, window, "four views")
    grid = window.tab("four views").widget
    images = {k: v.rgb for k, v in grid.views.items()}
    assert set(images) == {"front", "side", "top", "observer"}
    assert not np.allclose(images["front"], images["top"])
    assert not np.allclose(images["front"], images["side"])


def test_clicking_a_pixel_shows_its_ray_tree(qtbot, window):
    panel = window.tab("image order").widget
    cam = window.model.camera
    cone = next(o for o in window.model.scene.objects if o.name == "cone")
    # A point on the cone's axis, half way up: the observer sees the cone there.
    x, y = (int(v) for v in cam.project(cone.vertices.mean(axis=0)).pixel)
    with qtbot.waitSignal(window._tree_renderer.finished, timeout=RENDER_TIMEOUT_MS):
        qtbot.mouseClick(panel.image, Qt.MouseButton.LeftButton, pos=panel.image.widget_pos(x, y).toPoint())
    x0, y0, root = window.ray_tree
    assert (x0, y0) == panel.image.picked  # the pixel under the mouse (the pane may shrink the image)
    assert abs(x0 - x) <= 1 and abs(y0 - y) <= 1
    assert root.kind == "primary" and root.hit_name == "cone"
    assert [c.kind for c in root.children] == ["shadow"]  # one light, no mirrors or glass
    assert "ray-tree" in window.scene_view.overlay_names()
    assert panel.tree.topLevelItem(0).text(1) == "cone"
    assert "back to the first" in panel.explanation.toPlainText()


def test_effects_plan_follows_the_scene(qtbot, window):
    assert "no reflection rays" in window.tab("image order").widget.plan.text()
    assert "reflection 0" in window.tab("image order").widget.rays.text()
    _move_and_wait(qtbot, window, lambda: window.load_preset(
        "mirror_and_glass", PRESETS_TRACE["mirror_and_glass"][1]))
    text = window.tab("image order").widget.plan.text()
    assert "reflection rays:" in text and "refraction rays" in text
    counts = window.tab("image order").widget.rays.text()
    assert "reflection 0" not in counts and "refraction 0" not in counts


def test_cancel_stops_a_render_and_keeps_the_window_usable(qtbot, window):
    window.activateWindow()
    qtbot.waitUntil(window.isActiveWindow)
    accel = window.tab("image order").widget.accel
    accel.setCurrentIndex(accel.findData("none"))
    renderer = window.tab("image order").renderer
    delivered = []
    window.full_image_shown.connect(delivered.append)
    window.camera_panel.resolution.setCurrentIndex(4)  # 960 x 720: a preview, then a longer render
    qtbot.waitUntil(lambda: "rendering" in window.progress.format(), timeout=RENDER_TIMEOUT_MS)
    assert renderer.busy and window.cancel_button.isEnabled()
    qtbot.mouseClick(window.cancel_button, Qt.MouseButton.LeftButton)
    assert not renderer.busy
    assert "cancelled" in window.progress.format()
    qtbot.keyClick(window, Qt.Key.Key_F5)  # render again on demand
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    assert len(delivered) == 1  # only the re-render: the cancelled one never arrives
    assert window.tab("image order").widget.image.rgb.shape == (720, 960, 3)


def test_3d_pane_shows_bounding_spheres_grid_and_the_walked_cells(qtbot, window):
    panel = window.tab("image order").widget
    panel.show_spheres.setChecked(True)
    panel.show_grid.setChecked(True)
    assert {"spheres", "grid"} <= set(window.scene_view.overlay_names())
    spheres = window.scene_view.overlay_parts("spheres")
    assert len(spheres) == len(window.model.scene.objects)  # the lecture scene: three meshes
    cam = window.model.camera
    with qtbot.waitSignal(window._tree_renderer.finished, timeout=RENDER_TIMEOUT_MS):
        window.pick_ray_tree(cam.width // 2, cam.height // 2)
    panel.show_walk.setChecked(True)
    assert "walk" in window.scene_view.overlay_names()
    panel.show_grid.setChecked(False)
    assert "grid" not in window.scene_view.overlay_names()


def test_the_whole_window_fits_a_1280_by_720_laptop_screen_also_with_larger_text(window):
    # Qt cannot shrink a window below its minimum size: a wider minimum would push panels off the screen.
    for larger in (False, True):
        if larger:
            window.scale_text(1.25)
            QApplication.processEvents()  # the controls are refitted once the new font has arrived
        hint = window.minimumSizeHint()
        assert hint.width() <= 1280 and hint.height() <= 720, (larger, hint)
    available = window.screen().availableGeometry()
    assert window.width() <= available.width() and window.height() <= available.height()

