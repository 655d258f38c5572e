"""File → Export in the window, as a user works: choose an entry, name the file, get the picture.

The file dialog is the only thing replaced (:func:`_save_as` answers it with a
path); every entry is triggered from the menu as a user would.
"""

import json
from dataclasses import replace
from pathlib import Path

import imageio.v3 as iio
import numpy as np
import pytest
from PySide6.QtCore import QStandardPaths, Qt, QThreadPool
from PySide6.QtWidgets import QFileDialog, QMessageBox, QProgressDialog, QPushButton, QWidget
from window_helpers import RENDER_TIMEOUT_MS

from app.export.pane_pictures import PanePicture
from app.export.picture_sheet import MARGIN, TITLE_ROW
from app.window.main_window import MainWindow
from core import presets
from core.presets_trace import PRESETS_TRACE
from core.srgb import to_srgb8

EXPORT_TIMEOUT_MS = 120_000


def _save_as(monkeypatch, path, asked=None):
    """Answer the next file dialogs with ``path``, recording the folder each one started in."""
    def dialog(parent, title, start, filters):
        if asked is not None:
            asked.append(start)
        return str(path), filters.split(";;")[0]

    monkeypatch.setattr(QFileDialog, "getSaveFileName", dialog)


def _export(qtbot, window, entry):
    window.exports.refresh()  # what opening the menu does
    action = window.exports.actions[entry]
    assert action.isEnabled(), action.toolTip()
    action.trigger()
    qtbot.waitUntil(lambda: not window.exports.writing(), timeout=EXPORT_TIMEOUT_MS)  # encoded off the GUI


def _show_full(qtbot, window, tab):
    window.show_tab(tab)
    qtbot.waitUntil(lambda: window.showing_full(tab), timeout=RENDER_TIMEOUT_MS)


def _background8(scene):
    return to_srgb8(np.asarray(scene.background)).astype(int)


def test_the_traced_image_is_saved_pixel_for_pixel_and_the_folder_is_remembered(qtbot, window, tmp_path,
                                                                                 monkeypatch):
    asked = []
    _save_as(monkeypatch, tmp_path / "traced.png", asked)
    _export(qtbot, window, "Image order/Image")
    pixels = iio.imread(tmp_path / "traced.png")
    cam = window.model.camera
    assert pixels.shape == (cam.height, cam.width, 3)  # the image's resolution, not the pane's size
    background = _background8(window.model.scene)
    assert (np.abs(pixels[0, 0].astype(int) - background) <= 1).all()  # sky in the top corner
    assert np.abs(pixels.astype(int) - background).max(axis=2).mean() > 10  # the ground, cube and cone
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 50
    assert "traced.png" in window.statusBar().currentMessage()

    _export(qtbot, window, "3D pane")  # the next dialog opens where the last file went
    assert Path(asked[-1]).parent == tmp_path


def test_the_zbuffer_is_saved_with_its_scale_as_distances_between_near_and_far(qtbot, window, tmp_path,
                                                                                monkeypatch):
    _show_full(qtbot, window, "object order")
    _save_as(monkeypatch, tmp_path / "z.png")
    _export(qtbot, window, "Object order/z-buffer with its scale")
    cam = window.model.camera
    sheet = iio.imread(tmp_path / "z.png")
    top = MARGIN + TITLE_ROW
    panel = sheet[top:top + cam.height, MARGIN:MARGIN + cam.width, 0].astype(int)
    depth = window.tab("object order").widget.result.depth
    # The lecture's grey scale: level (d - near) / (far - near), white where nothing was drawn.
    expected = np.round(np.clip((depth - cam.near) / (cam.far - cam.near), 0, 1) * 255)
    assert np.abs(panel - expected).max() <= 1
    assert sheet.shape[0] > top + cam.height + 20  # the scale and its labels under the image


def test_the_four_views_are_saved_as_one_picture(qtbot, window, tmp_path, monkeypatch):
    _show_full(qtbot, window, "four views")
    _save_as(monkeypatch, tmp_path / "four.png")
    _export(qtbot, window, "Four views/All 4 panes as one picture")
    cam = window.model.camera
    sheet = iio.imread(tmp_path / "four.png")
    assert sheet.shape[0] >= 2 * cam.height + 2 * TITLE_ROW and sheet.shape[1] >= 2 * cam.width + 3 * MARGIN
    observer = sheet[-cam.height - MARGIN:-MARGIN, -cam.width - MARGIN:-MARGIN]
    assert np.abs(observer.astype(int) - _background8(window.model.scene)).max(axis=2).mean() > 10


def test_entries_with_nothing_to_export_are_disabled_and_say_why(window):
    window.exports.refresh()
    actions = window.exports.actions
    assert not actions["Ray tree/JSON"].isEnabled()
    assert "picked pixel" in actions["Ray tree/JSON"].toolTip()
    assert not actions["Four views/All 4 panes as one picture"].isEnabled()  # that tab has not rendered
    assert "Nothing shown yet" in actions["Four views/All 4 panes as one picture"].toolTip()
    window.load_preset("lone sphere", PRESETS_TRACE["lone_sphere"][1])  # a sphere: 3,968 triangles
    window.exports.refresh()
    steps = window.exports.actions["z-buffer steps"]
    assert not steps.isEnabled() and "fewer objects or triangles" in steps.toolTip()


def test_a_tab_whose_render_was_refused_exports_nothing_and_no_orbit_over_the_budget(qtbot, window, tmp_path,
                                                                                   monkeypatch):
    """Over the memory budget the traced image is not rendered and the tab is covered: its export
    wrote the previous scene's image as this one's, and an orbit of frames each over the budget was
    made anyway. Both entries are now disabled with the tab's reason, and the orbit is refused."""
    _show_full(qtbot, window, "Image order")  # the lecture scene's image, 320 x 240
    window.model.memory_limit = 30_000_000
    scene = window.model.scene
    big = replace(scene, camera=scene.camera.replace(width=1600, height=1200))
    window.model.set_scene(big)
    qtbot.waitUntil(lambda: window.progress.format() == "Image order: not rendered, over the memory budget")
    window.exports.refresh()
    for entry in ("Image order/Image", "Orbit/Image order"):
        action = window.exports.actions[entry]
        assert not action.isEnabled(), entry
        assert "the budget is 30 MB" in action.toolTip() or "not of the current scene" in action.toolTip()
    boxes = []
    monkeypatch.setattr(QMessageBox, "critical", lambda parent, title, text: boxes.append(text))
    path = tmp_path / "orbit.gif"
    assert not window.exports.export_orbit("Image order", 3, str(path))
    assert not path.exists() and "the budget is 30 MB" in boxes[0]
    assert window.exports.actions["Orbit/Object order"].isEnabled() is False  # its frames as large


def test_zbuffer_steps_gif_has_one_frame_per_polygon_after_the_cleared_buffers(qtbot, window, tmp_path,
                                                                             monkeypatch):
    window.load_preset("three polygons", presets.zbuffer_three_polygons)
    _save_as(monkeypatch, tmp_path / "steps.gif")
    with qtbot.waitSignal(window.exports.exported, timeout=EXPORT_TIMEOUT_MS) as written:
        _export(qtbot, window, "z-buffer steps")
        assert any(d.isVisible() for d in window.findChildren(QProgressDialog))  # rendered in the background
    assert written.args == [str(tmp_path / "steps.gif")]
    assert not any(d.isVisible() for d in window.findChildren(QProgressDialog))
    frames = iio.imread(tmp_path / "steps.gif", index=None)
    assert len(frames) == 3 + 1  # the lecture's three polygons, after step 0
    scene = window.model.scene
    w, h = scene.camera.width, scene.camera.height
    memory = frames[:, MARGIN + TITLE_ROW:MARGIN + TITLE_ROW + h, MARGIN:MARGIN + w, :3].astype(int)
    assert np.abs(memory[0] - _background8(scene)).max() <= 3  # cleared: the background (GIF palette)
    for before, after in zip(memory[:-1], memory[1:], strict=True):
        assert np.abs(after - before).max() > 20  # each step draws (and tints) one more polygon


def test_cancel_stops_an_orbit_and_writes_nothing(qtbot, window, tmp_path):
    out = tmp_path / "orbit.gif"
    assert window.exports.export_orbit("Image order", 500, str(out))
    dialog = next(d for d in window.findChildren(QProgressDialog) if d.isVisible())
    qtbot.waitUntil(lambda: dialog.value() > 0, timeout=EXPORT_TIMEOUT_MS)  # frames are being made
    qtbot.mouseClick(dialog.findChild(QPushButton), Qt.MouseButton.LeftButton)  # Cancel
    assert not dialog.isVisible()
    assert QThreadPool.globalInstance().waitForDone(30_000)
    assert list(tmp_path.iterdir()) == []  # no file, no temporary file left
    assert "cancelled" in window.statusBar().currentMessage()


def test_the_picked_pixels_ray_tree_is_saved_as_json_and_as_the_3d_pane(qtbot, window, tmp_path,
                                                                       monkeypatch):
    cam = window.model.camera
    x, y = cam.width // 2, cam.height * 2 // 3
    window.pick_ray_tree(x, y)
    qtbot.waitUntil(lambda: window.ray_tree is not None, timeout=RENDER_TIMEOUT_MS)
    _save_as(monkeypatch, tmp_path / "tree.json")
    _export(qtbot, window, "Ray tree/JSON")
    document = json.loads((tmp_path / "tree.json").read_text())
    root = document["tree"]
    assert document["pixel"] == [x, y]
    assert root["kind"] == "primary"
    assert np.allclose(root["origin"], cam.eye)  # the primary ray starts at the eye
    assert np.linalg.norm(root["direction"]) == pytest.approx(1.0)
    assert root["hit"]["name"] in {o.name for o in window.model.scene.objects}
    assert np.allclose(root["point"], np.add(root["origin"], root["t"] * np.asarray(root["direction"])))
    shown = window.tab("image order").widget.image.rgb[y, x]
    assert np.allclose(document["pixel_colour"], shown, atol=1e-6)  # the pixel the user clicked

    def rays(node):
        yield node
        for child in node["children"]:
            yield from rays(child)

    # The colours from the last hits back to the first add up to the pixel.
    parts = [r["colour"]["to_pixel"] for r in rays(root) if r["colour"]["to_pixel"] is not None]
    assert np.allclose(np.clip(np.sum(parts, axis=0), 0, 1), document["pixel_colour"])

    _save_as(monkeypatch, tmp_path / "tree.png")
    plotter, taken = window.scene_view.plotter, []
    picture_at = plotter.picture_at

    def sized_picture(*args, **kwargs):  # the pane's size when the picture is taken
        taken.append(tuple(plotter.ren_win.GetSize()))  # (the docks may settle a few pixels later)
        return picture_at(*args, **kwargs)

    monkeypatch.setattr(plotter, "picture_at", sized_picture)
    window.model.set_overlay("frustum", True)
    qtbot.waitUntil(lambda: "frustum" in window.scene_view.overlay_names())
    shown = set(window.scene_view.overlay_names())
    _export(qtbot, window, "Ray tree/3D pane")
    assert set(window.scene_view.overlay_names()) == shown  # the pane shows what it showed (the frustum went)
    picture = iio.imread(tmp_path / "tree.png")
    [(width, height)] = taken
    assert picture.shape == (2 * height, 2 * width, 3)  # twice the pane's size
    assert len(np.unique(picture.reshape(-1, 3), axis=0)) > 50


def test_a_file_that_cannot_be_written_shows_a_dialog_naming_it(qtbot, window, tmp_path, monkeypatch):
    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda parent, title, text, *rest: shown.append(text))
    out = tmp_path / "no-such-folder" / "traced.png"
    _save_as(monkeypatch, out)
    _export(qtbot, window, "Image order/Image")
    assert len(shown) == 1 and str(out) in shown[0] and "does not exist" in shown[0]
    assert not out.parent.exists()


def test_an_animation_that_cannot_be_written_shows_a_dialog_naming_it(qtbot, window, tmp_path,
                                                                        monkeypatch):
    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda parent, title, text, *rest: shown.append(text))
    window.load_preset("three polygons", presets.zbuffer_three_polygons)
    folder = tmp_path / "slides"
    folder.mkdir()
    out = folder / "steps.mp4"
    assert window.exports.export_steps(str(out))
    folder.rmdir()  # the folder goes away while the frames are made
    qtbot.waitUntil(lambda: bool(shown), timeout=EXPORT_TIMEOUT_MS)
    assert str(out) in shown[0] and "No such file or directory" in shown[0]
    assert shown[0].count(str(out)) == 1 and "OutputError" not in shown[0]  # the path once, no class name
    assert not any(d.isVisible() for d in window.findChildren(QProgressDialog))


def test_a_tab_can_offer_its_own_pictures(qtbot, window, tmp_path, monkeypatch):
    class Slides:
        title, overlays = "Slides", ()

        def __init__(self):
            self.widget = QWidget()

        def job(self, scene, preview):
            return None

        def show(self, result):
            return ""

        def pictures(self):
            return [PanePicture(self.title, "Grey card", lambda: np.full((10, 20, 3), 0.5)),
                    PanePicture(self.title, "Later", None, "Not yet")]

    window.add_tab(Slides())
    window.exports.refresh()
    assert not window.exports.actions["Slides/Later"].isEnabled()
    assert window.exports.actions["Slides/Later"].toolTip() == "Not yet"
    _save_as(monkeypatch, tmp_path / "card.png")
    _export(qtbot, window, "Slides/Grey card")
    assert (iio.imread(tmp_path / "card.png") == to_srgb8(np.full(3, 0.5))).all()


def test_the_remembered_folder_survives_a_new_window(qtbot, window, tmp_path, monkeypatch):
    slides = tmp_path / "slides"
    slides.mkdir()
    _save_as(monkeypatch, slides / "traced.png")
    _export(qtbot, window, "Image order/Image")
    window.close()

    asked = []
    _save_as(monkeypatch, slides / "scene-3d.png", asked)
    again = MainWindow(presets.lecture_scene())  # as after a restart
    qtbot.addWidget(again)
    again.show()
    _export(qtbot, again, "3D pane")
    assert Path(asked[-1]).parent == slides  # the dialog opens where the last file went

    for written in slides.iterdir():
        written.unlink()
    slides.rmdir()  # a folder that is gone: the dialog starts in the user's Documents (or home) instead
    monkeypatch.setattr(QFileDialog, "getSaveFileName",
                        lambda parent, title, start, filters: (asked.append(start), ("", ""))[1])  # Cancel
    _export(qtbot, again, "3D pane")
    documents = QStandardPaths.writableLocation(QStandardPaths.StandardLocation.DocumentsLocation)
    assert Path(asked[-1]).parent in {Path(documents), Path.home()}


def test_the_hard_cases_pictures_are_named_after_their_method(qtbot, window, tmp_path, monkeypatch):
    panel = window.tab("hard cases").widget
    window.show_tab("hard cases")  # the first case, the tangent ray, has numbers but no picture
    qtbot.waitUntil(lambda: panel.result is not None, timeout=RENDER_TIMEOUT_MS)
    with qtbot.waitSignal(panel.result_shown, timeout=RENDER_TIMEOUT_MS):
        panel.select("behind_eye")  # a triangle drawn with and without clipping
    window.exports.refresh()
    entries = [key for key in window.exports.actions if key.startswith("Hard cases/")]
    assert entries == ["Hard cases/Picture of the textbook method", "Hard cases/Picture of the robust method"]
    _save_as(monkeypatch, tmp_path / "textbook.png")
    _export(qtbot, window, "Hard cases/Picture of the textbook method")
    pixels = iio.imread(tmp_path / "textbook.png")
    assert pixels.shape[:2] == panel.result.images[0].naive.shape[:2]  # the case's image, pixel for pixel
    assert len(np.unique(pixels.reshape(-1, 3), axis=0)) > 1

    with qtbot.waitSignal(panel.result_shown, timeout=RENDER_TIMEOUT_MS):
        panel.select("tangent")  # back to a case without a picture: the last one is not offered
    window.exports.refresh()
    textbook = window.exports.actions["Hard cases/Picture of the textbook method"]
    assert not textbook.isEnabled() and "Not part of what the tab shows" in textbook.toolTip()


def _drawn_twice_as_large(plotter) -> np.ndarray:
    """pyvista's screenshot of the pane, its window twice as wide and tall for it: (H, W, 3) levels."""
    width, height = plotter.window_size
    return plotter.screenshot(None, return_img=True, window_size=(2 * width, 2 * height))[..., :3].astype(int)


def test_the_3d_pane_is_saved_as_vtk_drew_it_and_the_status_bar_says_so(qtbot, window, tmp_path,
                                                                        monkeypatch):
    # The picture is read back on the GUI thread, then encoded and written off it.
    _show_full(qtbot, window, "image order")  # the observer's screen in the 3D pane shows the full image
    _save_as(monkeypatch, tmp_path / "pane.png")
    pane = window.scene_view.view
    qtbot.waitUntil(lambda: pane._frustum_faces.GetVisibility(), timeout=RENDER_TIMEOUT_MS)  # at rest
    # What VTK draws at twice the pane's size, read in the same turn of the event loop as the export's.
    drawn = _drawn_twice_as_large(window.scene_view.plotter)
    _export(qtbot, window, "3D pane")
    saved = iio.imread(tmp_path / "pane.png").astype(int)
    assert saved.shape == drawn.shape
    # Linear in between, 8-bit sRGB in the file: each level comes back within one.
    assert np.abs(saved - drawn).max() <= 1
    assert "pane.png" in window.statusBar().currentMessage()


def test_the_3d_pane_exported_while_it_moves_has_its_see_through_frustum(qtbot, window, tmp_path,
                                                                          monkeypatch):
    # While the observer moves the pane draws the frustum by its edges only, and smooth once it
    # rests; an export taken meanwhile lacked the frustum's see-through faces the pane then shows.
    pane = window.scene_view.view
    _save_as(monkeypatch, tmp_path / "moving.png")
    cam = window.model.camera
    window.model.set_camera(cam.orbit(cam.yaw_deg + 5, cam.pitch_deg))
    assert not pane._frustum_faces.GetVisibility()  # the pane moves: drawn by the edges

    def drawn(faces: bool):
        """pyvista's picture at twice the pane's size, with or without the resting look."""
        pane.plotter.renderer.SetUseFXAA(faces)
        pane._frustum_faces.SetVisibility(faces)
        picture = _drawn_twice_as_large(pane.plotter)
        pane.plotter.renderer.SetUseFXAA(False)
        pane._frustum_faces.SetVisibility(False)
        return picture

    at_rest, edges_only = drawn(True), drawn(False)  # in the export's turn: the same pane size
    _export(qtbot, window, "3D pane")
    saved = iio.imread(tmp_path / "moving.png").astype(int)
    faces = np.abs(at_rest - edges_only).max(axis=2) > 2  # where the faces tint the picture
    assert faces.sum() > 1000
    assert np.abs(saved - at_rest).max() <= 1  # tinted there as the resting pane is


def test_a_picture_whose_writing_fails_off_the_gui_thread_shows_a_dialog_naming_it(qtbot, window, tmp_path,
                                                                                  monkeypatch):
    from app.export import export_menu
    from core.files.safe_files import OutputError

    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda parent, title, text, *rest: shown.append(text))

    def full_disk(path, rgb):
        raise OutputError(f"{path}: No space left on device")

    monkeypatch.setattr(export_menu, "write_image", full_disk)
    out = tmp_path / "pane.png"
    _save_as(monkeypatch, out)
    _export(qtbot, window, "3D pane")
    assert len(shown) == 1 and str(out) in shown[0] and "No space left" in shown[0]
    assert not out.exists() and "Exported" not in window.statusBar().currentMessage()
