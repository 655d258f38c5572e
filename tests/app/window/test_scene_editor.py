"""The scene editor as a user works with it: the Scene dock, the Edit menu, undo and redo, saving.

Dialogs (the colour dialog, the unsaved-changes question) are the real ones,
answered by a timer that clicks in them once they are open.
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import pytest
from PySide6.QtCore import QPointF, Qt, QTimer
from PySide6.QtGui import QColor
from PySide6.QtWidgets import QApplication, QColorDialog, QLineEdit, QMessageBox
from window_helpers import RENDER_TIMEOUT_MS, open_scene_file

from app.window import session
from app.window.main_window import MainWindow, run
from app.window.window_layout import in_front
from core import checked_edits, presets
from core.files import scene_file
from core.scene import Sphere
from views.panels.scene_tree_panel import show_value
from views.user_settings import user_settings


@pytest.fixture
def window(qtbot):
    """The window on the lecture scene; at the end its edits count as saved, so closing asks nothing.

    (Not closed by qtbot, which would close it before this fixture could mark the edits saved.)
    """
    win = MainWindow(presets.lecture_scene())
    win.show()
    qtbot.waitUntil(lambda: win.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: win.scene_view.view is not None, timeout=RENDER_TIMEOUT_MS)  # the 3D pane
    win.editor.dock.raise_()  # in front, as when a user edits (a covered dock takes no keys)
    qtbot.waitUntil(lambda: in_front(win.editor.dock))
    yield win
    win.editor.stack.setClean()
    win.close()
    win.deleteLater()


def _object_actors(win):
    """The 3D pane's actors of the scene's objects, by their colour."""
    actors = win.scene_view.plotter.renderer.actors
    return [a for name, a in actors.items() if name.startswith("object:")]


def _drawn_in(win, colour) -> bool:
    """Whether an object of the 3D pane is drawn in ``colour`` (VTK keeps 8 bits of each component)."""
    return any(np.allclose(a.prop.color.float_rgb, colour, atol=0.5 / 255) for a in _object_actors(win))


def _answer_modal(qtbot, answer):
    """Once a modal dialog is open, ``answer(dialog)``; returns a list that holds the dialog then."""
    seen = []

    def poll():
        dialog = QApplication.activeModalWidget()
        if dialog is None:
            QTimer.singleShot(20, poll)
            return
        seen.append(dialog)
        answer(dialog)

    QTimer.singleShot(0, poll)
    return seen


def _click(button):
    def answer(box):
        assert isinstance(box, QMessageBox)
        box.button(button).click()
    return answer


def _editor_action(win, text):
    """The Edit menu's action whose text starts with ``text`` (submenus included)."""
    edit = next(a.menu() for a in win.menuBar().actions() if a.text() == "&Edit")
    actions = [a for top in edit.actions() for a in (top.menu().actions() if top.menu() else [top])]
    return next(a for a in actions if a.text().replace("&", "").startswith(text))


def _type_into(qtbot, box: QLineEdit, text: str):
    box.setFocus()
    box.selectAll()
    qtbot.keyClick(box, Qt.Key.Key_Backspace)
    qtbot.keyClicks(box, text)
    qtbot.keyClick(box, Qt.Key.Key_Return)


def test_add_a_sphere_colour_it_undo_twice_redo_once(qtbot, window):
    editor, model = window.editor, window.model
    start = model.scene
    _editor_action(window, "sphere").trigger()
    assert [o.name for o in model.scene.objects] == ["cube", "cone", "ground", "sphere"]
    sphere = model.scene.objects[-1]
    assert isinstance(sphere, Sphere) and np.linalg.norm(np.subtract(sphere.center, model.camera.target)) < 3
    assert model.selection == ("object", 3)
    assert len(_object_actors(window)) == 4

    # The swatch opens the colour dialog (in sRGB); sRGB (255, 128, 0) is linear (1, 0.2159, 0).
    def pick(dialog):
        assert isinstance(dialog, QColorDialog)
        dialog.setCurrentColor(QColor(255, 128, 0))
        dialog.accept()

    seen = _answer_modal(qtbot, pick)
    editor.panel.fields["material.color"].swatch.click()
    assert seen
    green = ((128 / 255 + 0.055) / 1.055) ** 2.4  # the sRGB curve, worked by hand
    assert model.scene.objects[-1].material.color == (1.0, pytest.approx(green, abs=5e-5), 0.0)
    assert editor.undo_action.text() == "Undo Change colour of sphere"
    assert _drawn_in(window, model.scene.objects[-1].material.color)

    editor.undo_action.trigger()
    assert model.scene.objects[-1].material.color == (0.8, 0.8, 0.8)
    assert editor.undo_action.text() == "Undo Add sphere"
    assert editor.redo_action.text() == "Redo Change colour of sphere"
    editor.undo_action.trigger()
    assert model.scene.objects == start.objects
    assert len(_object_actors(window)) == 3
    assert not window.isWindowModified()

    editor.redo_action.trigger()
    assert [o.name for o in model.scene.objects][-1] == "sphere"
    assert model.scene.objects[-1].material.color == (0.8, 0.8, 0.8)
    assert len(_object_actors(window)) == 4 and not _drawn_in(window, (1.0, green, 0.0))
    assert window.isWindowModified() and "[*]" in window.windowTitle()
    assert editor.panel.fields["name"].boxes[0].text() == "sphere"  # the redone item is selected
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=60_000)  # and it was rendered


def test_at_1280x720_the_lecture_scenes_every_row_shows_in_the_tree(qtbot, window):
    window.setGeometry(0, 0, 1280, 720)
    window.editor.dock.raise_()
    tree = window.editor.panel.tree
    rows = []

    def walk(item):
        rows.append(item)
        for i in range(item.childCount()):
            walk(item.child(i))

    for i in range(tree.topLevelItemCount()):
        tree.topLevelItem(i).setExpanded(True)
        walk(tree.topLevelItem(i))
    assert len(rows) >= 6  # objects (3): cube, cone, ground; lights (1): light; and more

    def every_row_shown():
        last = tree.visualItemRect(rows[-1])
        assert tree.isVisible() and last.height() > 0
        assert last.bottom() <= tree.viewport().height(), (last, tree.viewport().height())

    qtbot.waitUntil(every_row_shown, timeout=5000)


def test_at_twice_the_text_size_the_trees_names_show_whole(qtbot, window):
    """The names' column kept its width at x1: at x2 "cube" read "c…" and "Objects (3)" "Obj…"."""
    window.editor.dock.raise_()
    tree = window.editor.panel.tree
    window.presentation.set_scale(2.0)
    # Qt's own measure of the column's widest name, its indentation and branch mark included.
    names_whole = lambda: tree.columnWidth(0) >= tree.sizeHintForColumn(0) > 0  # noqa: E731
    qtbot.waitUntil(names_whole, timeout=5000)
    window.presentation.set_scale(1.0)


def test_an_edit_redraws_only_what_it_changed_in_the_3d_pane(qtbot, window):
    editor, model = window.editor, window.model
    before = dict(window.scene_view.plotter.renderer.actors)
    kept = [before[n] for n in before if n.startswith(("object:", "light:"))]
    assert len(kept) == len(model.scene.objects) + len(model.scene.lights)
    assert editor.change_field(("object", 1), "material.color", [0.1, 0.9, 0.2])
    assert _drawn_in(window, (0.1, 0.9, 0.2))
    after = window.scene_view.plotter.renderer.actors.values()
    # The cube, the ground and the light keep their actors; the cone's is new, in its new colour.
    assert sum(any(a is k for a in after) for k in kept) == len(kept) - 1
    assert len(_object_actors(window)) == 3
    editor.undo_action.trigger()
    assert not _drawn_in(window, (0.1, 0.9, 0.2)) and len(_object_actors(window)) == 3


def test_a_bad_value_is_refused_with_the_loaders_message_and_the_scene_kept(qtbot, window):
    model, panel = window.model, window.editor.panel
    model.set_selection(("object", 0))
    before = model.scene
    _type_into(qtbot, panel.fields["material.opacity"].boxes[0], "1.5")
    assert model.scene is before
    assert window.editor.stack.count() == 0
    # The same value in a scene file, loaded by the loader:
    d = scene_file.to_dict(before)
    d["objects"][0].setdefault("material", {})["opacity"] = 1.5
    with pytest.raises(scene_file.SceneFileError) as info:
        scene_file.from_dict(d)
    assert panel.problem("material.opacity") == "\n".join(info.value.problems)
    assert panel.problem("material.opacity") == "objects[0].material.opacity: must be in [0, 1], got 1.5"
    assert panel.fields["material.opacity"].boxes[0].text() == "1.5"  # left for correcting

    _type_into(qtbot, panel.fields["material.opacity"].boxes[0], "0.5")
    assert model.scene.objects[0].material.opacity == 0.5
    assert panel.problem("material.opacity") == ""
    assert window.editor.undo_action.text() == "Undo Change opacity of cube"


def test_a_typed_centre_moves_the_object_and_text_is_refused(qtbot, window):
    model, panel = window.model, window.editor.panel
    model.set_selection(("object", 0))
    x, y, z = model.scene.objects[0].source["center"]
    _type_into(qtbot, panel.fields["center"].boxes[1], "abc")
    assert panel.problem("center") == f'objects[0].center: expected 3 numbers, got [{x}, "abc", {z}]'
    _type_into(qtbot, panel.fields["center"].boxes[1], "2")
    cube = model.scene.objects[0]
    assert np.allclose((cube.vertices.min(axis=0) + cube.vertices.max(axis=0)) / 2, (x, 2.0, z))
    assert window.editor.undo_action.text() == "Undo Change centre of cube"


def test_editing_one_component_leaves_the_others_exactly_as_they_were(qtbot, window):
    """A box shows 10 digits; editing y re-read x from its box, so x = 1.6641005886756874 became
    1.664100589."""
    model, panel = window.model, window.editor.panel
    x = 1.6641005886756874
    model.set_scene(replace(model.scene, objects=(*model.scene.objects, Sphere((x, 1.0, -0.5), 0.5))))
    model.set_selection(("object", 3))
    assert panel.fields["center"].boxes[0].text() == "1.664100589"
    _type_into(qtbot, panel.fields["center"].boxes[1], "2")
    assert model.scene.objects[3].center == (x, 2.0, -0.5)


def test_a_long_or_marked_up_name_keeps_the_fields_in_view_and_reads_as_typed(qtbot, window):
    """A 5000-character name without spaces widened the fields beyond the dock (the title above them
    cannot wrap it), and a name with "<" was read as markup."""
    model, panel = window.model, window.editor.panel
    cube, *others = model.scene.objects
    model.set_scene(replace(model.scene, objects=(replace(cube, name="x" * 5000), *others)), edit=True)
    model.set_selection(("object", 0))
    z = panel.fields["center"].boxes[2]

    def whole_in_view():
        right = z.mapTo(panel, z.rect().topRight()).x()
        return z.isVisible() and right <= panel.width()

    qtbot.waitUntil(whole_in_view)
    assert panel.fields["name"].boxes[0].text() == "x" * 5000  # the name's own box holds all of it
    marked = replace(cube, name="<i>crate</i> & co")
    model.set_scene(replace(model.scene, objects=(marked, *others)), edit=True)
    model.set_selection(("object", 0))
    assert "&lt;i&gt;crate&lt;/i&gt; &amp; co" in panel.title.text()


def test_the_old_value_typed_again_clears_the_red_problem(qtbot, window):
    model, panel = window.model, window.editor.panel
    model.set_selection(("object", 0))
    before = model.scene
    _type_into(qtbot, panel.fields["material.opacity"].boxes[0], "1.5")
    assert panel.problem("material.opacity")
    old = show_value(before.objects[0].material.opacity)
    _type_into(qtbot, panel.fields["material.opacity"].boxes[0], old)
    assert panel.problem("material.opacity") == ""  # the scene is as it was, and nothing is wrong
    assert model.scene is before and window.editor.stack.count() == 0


def test_a_problem_on_two_lines_is_shown_whole(qtbot, window):
    model, panel = window.model, window.editor.panel
    window.editor.dock.raise_()
    model.set_selection(("object", 0))
    _type_into(qtbot, panel.fields["center"].boxes[1], "abc")
    problem = panel.fields["center"].problem
    line = problem.fontMetrics().lineSpacing()

    def whole():
        assert problem.isVisible()
        lines = problem.fontMetrics().boundingRect(problem.contentsRect(), Qt.TextFlag.TextWordWrap,
                                                   problem.text()).height() / line
        assert lines >= 2, lines  # the message takes two lines in the narrow dock...
        assert problem.height() >= problem.heightForWidth(problem.width())  # ...and has room for them

    qtbot.waitUntil(whole, timeout=5000)


@pytest.mark.parametrize(("linear", "levels"), [
    ((1.0, 0.0, 0.0), (255, 0, 0)),
    # sRGB's curve: 1.055 * 0.5 ** (1 / 2.4) - 0.055 = 0.7354, 0.7354 * 255 = 187.5 -> 188;
    # 12.92 * 0.002 = 0.0258 -> 6.6 -> 7.
    ((0.5, 0.002, 0.0), (188, 7, 0)),
])
def test_the_colour_swatch_shows_the_colour_itself(qtbot, window, linear, levels):
    # Linear red (1, 0, 0) was drawn pink (252, 115, 115): the button's own shading was mixed in.
    model, panel, editor = window.model, window.editor.panel, window.editor
    window.editor.dock.raise_()
    model.set_selection(("object", 0))
    assert editor.change_field(("object", 0), "material.color", list(linear))
    swatch = panel.fields["material.color"].swatch
    qtbot.waitUntil(swatch.isVisible, timeout=5000)
    picture = swatch.grab().toImage()
    middle = QColor(picture.pixel(picture.width() // 2, picture.height() // 2))
    assert abs(middle.red() - levels[0]) <= 1 and abs(middle.green() - levels[1]) <= 1
    assert abs(middle.blue() - levels[2]) <= 1


def test_observer_moves_are_not_edits(qtbot, window):
    editor, model = window.editor, window.model
    model.set_selection(("light", 0))
    _type_into(qtbot, editor.panel.fields["intensity"].boxes[0], "0.5")
    cam = model.camera
    moved = cam.orbit(cam.yaw_deg + 30, cam.pitch_deg)
    model.set_camera(moved)
    assert editor.stack.count() == 1
    editor.undo_action.trigger()
    assert model.scene.lights[0].intensity == 1.0
    assert model.camera == moved  # undoing the light did not move the observer back


def test_rename_duplicate_delete_from_the_edit_menu(qtbot, window):
    editor, model, tree = window.editor, window.model, window.editor.panel.tree
    window.editor.dock.raise_()
    model.set_selection(("object", 1))
    _editor_action(window, "Duplicate").trigger()
    assert [o.name for o in model.scene.objects] == ["cube", "cone", "cone 2", "ground"]
    assert model.selection == ("object", 2)
    assert tree.currentItem().text(0) == "cone 2"

    _editor_action(window, "Rename").trigger()  # F2: the name becomes editable in the tree
    line = tree.findChild(QLineEdit)
    assert line is not None
    line.selectAll()
    qtbot.keyClicks(line, "spire")
    qtbot.keyClick(line, Qt.Key.Key_Return)  # the tree takes the name in the next turn of the loop
    qtbot.waitUntil(lambda: [o.name for o in model.scene.objects] == ["cube", "cone", "spire", "ground"])
    assert editor.undo_action.text() == "Undo Rename cone 2 to spire"
    _type_into(qtbot, editor.panel.fields["name"].boxes[0], "")
    assert editor.panel.problem("name") == "name: must not be empty"
    assert model.scene.objects[2].name == "spire" and editor.stack.count() == 2
    _type_into(qtbot, editor.panel.fields["name"].boxes[0], "cube")  # another object's name
    assert editor.panel.problem("name") == ("objects[2].name: 'cube' is already the name of objects[0]; "
                                            "each object needs a name of its own")
    _editor_action(window, "Rename").trigger()  # and in the tree
    # The tree's new editor: the first one, closed, may not be deleted yet (typed into, it crashed).
    qtbot.waitUntil(lambda: any(e.isVisible() for e in tree.findChildren(QLineEdit)))
    line = next(e for e in tree.findChildren(QLineEdit) if e.isVisible())
    line.selectAll()
    qtbot.keyClicks(line, "cone")
    qtbot.keyClick(line, Qt.Key.Key_Return)
    qtbot.waitUntil(lambda: tree.currentItem().text(0) == "spire")  # the tree reads the scene's name again
    assert [o.name for o in model.scene.objects] == ["cube", "cone", "spire", "ground"]
    assert editor.stack.count() == 2

    model.set_selection(("light", 0))
    _editor_action(window, "Duplicate").trigger()
    assert [light.name for light in model.scene.lights] == ["light", "light 2"]
    _editor_action(window, "Delete").trigger()
    assert [light.name for light in model.scene.lights] == ["light"]
    model.set_selection(("object", 0))
    _editor_action(window, "Delete").trigger()
    assert [o.name for o in model.scene.objects] == ["cone", "spire", "ground"]
    assert tree.topLevelItem(0).text(0) == "Objects (3)"
    for _ in range(4):
        editor.undo_action.trigger()
    assert [o.name for o in model.scene.objects] == ["cube", "cone", "cone 2", "ground"]
    model.set_selection(("background", 0))  # the background cannot be deleted or duplicated
    assert not _editor_action(window, "Delete").isEnabled()
    assert not _editor_action(window, "Duplicate").isEnabled()


def test_f2_with_the_editor_behind_another_tab_brings_it_forward_to_rename(qtbot, window):
    """The tree's name editor opened unseen behind the Exercises tab, and typing there renamed the
    object."""
    window.exercise_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.exercise_dock))
    window.model.set_selection(("object", 0))
    _editor_action(window, "Rename").trigger()  # F2
    qtbot.waitUntil(lambda: in_front(window.editor.dock))
    line = window.editor.panel.tree.findChild(QLineEdit)
    assert line is not None and line.isVisible() and line.text() == "cube"


def test_delete_in_a_field_edits_the_text_not_the_scene(qtbot, window):
    model, panel = window.model, window.editor.panel
    model.set_selection(("object", 0))
    box = panel.fields["name"].boxes[0]
    box.setFocus()
    box.setCursorPosition(0)
    qtbot.keyClick(box, Qt.Key.Key_Delete)
    assert box.text() == "ube"
    assert len(model.scene.objects) == 3


def test_every_primitive_and_a_light_can_be_added(qtbot, window):
    for name in ("sphere", "box", "cone", "pyramid", "quad", "uv sphere", "notched prism", "Light"):
        _editor_action(window, name).trigger()
    types = [getattr(o, "source", None) and o.source["type"] for o in window.model.scene.objects[3:]]
    assert types == [None, "box", "cone", "pyramid", "quad", "uv_sphere", "notched_prism"]
    assert [light.name for light in window.model.scene.lights] == ["light", "light 2"]
    assert len(_object_actors(window)) == 10


def _covered(scene) -> np.ndarray:
    """The pixels where the z-buffer keeps a surface, with their distances."""
    from core.object_order.pipeline import RasterSettings, render_raster

    return render_raster(scene, RasterSettings()).depth


@pytest.mark.parametrize("type_name", ["sphere", "box", "cone"])
def test_an_added_object_is_seen_by_the_observer_where_its_position_reads_as_typed(qtbot, window, type_name):
    # Edit > Add put the new object at the observer's target, which in the lecture scene lies
    # behind the cone: the new object was hidden.
    model = window.model
    before = model.scene
    assert window.editor.add_object(type_name)
    after = model.scene
    new = after.objects[-1]
    low, high = checked_edits.object_bounds(new)
    for other in before.objects:  # it takes a place of its own
        other_low, other_high = checked_edits.object_bounds(other)
        assert np.any(low >= other_high) or np.any(high <= other_low), other.name
    alone = np.isfinite(_covered(replace(after, objects=(new,))))  # where it would be seen alone
    seen = _covered(after) < _covered(before)  # where it is the nearest surface
    assert alone.sum() > 100
    assert (seen & alone).sum() >= 0.9 * alone.sum()  # seen whole (nothing in front of it)
    # and its position reads as a person would type it: hundredths of a unit for an object a unit
    # across (it read 1.664100589, 0.8, -1.109400392)
    typed = [box.text() for box in window.editor.panel.fields[
        "base_center" if type_name == "cone" else "center"].boxes]
    assert all(len(text.partition(".")[2]) <= 2 for text in typed), typed


def test_a_mesh_file_is_added_through_the_safe_reader(qtbot, window, tmp_path):
    good = tmp_path / "tetra.obj"
    good.write_text("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 3 2\nf 1 2 4\nf 1 4 3\nf 2 3 4\n")
    window.editor.add_mesh_file(good)
    qtbot.waitUntil(lambda: len(window.model.scene.objects) == 4)
    mesh = window.model.scene.objects[-1]
    assert mesh.name == "tetra" and len(mesh.triangles) == 4
    assert window.editor.undo_action.text() == "Undo Add tetra"
    assert window.model.selection == ("object", 3)
    _type_into(qtbot, window.editor.panel.fields["position"].boxes[0], "2.5")  # its bounding box's centre
    moved = window.model.scene.objects[-1]
    assert np.allclose(_centre(moved), (2.5, 0.5, 0.5)) and moved.source is None  # now saved inline
    assert window.editor.undo_action.text() == "Undo Move tetra"
    for typed, shown in (("abc", '"abc"'), ("true", "true"), ("[1]", "[1]")):  # a ValueError once
        _type_into(qtbot, window.editor.panel.fields["position"].boxes[0], typed)
        assert window.editor.panel.problem("position") == (
            f"objects[3].position: expected 3 numbers, got [{shown}, 0.5, 0.5]")
        assert window.model.scene.objects[-1] is moved

    bad = tmp_path / "broken.obj"
    bad.write_text("v 0 0 0\nf 1 2 3\n")
    said = []

    def read_and_close(box):
        said.append(box.text())
        box.button(QMessageBox.StandardButton.Ok).click()

    _answer_modal(qtbot, read_and_close)
    window.editor.add_mesh_file(bad)
    qtbot.waitUntil(lambda: bool(said))
    assert "broken.obj" in said[0] and "objects[4].path" in said[0]  # the fifth object, were it added
    assert len(window.model.scene.objects) == 4


def test_closing_with_unsaved_edits_asks_and_cancel_keeps_the_window(qtbot, window):
    _editor_action(window, "box").trigger()
    asked = _answer_modal(qtbot, _click(QMessageBox.StandardButton.Cancel))
    window.close()
    assert asked and "not saved" in asked[0].text()
    assert window.isVisible()
    assert window.model.scene.objects[-1].name == "box"

    asked = _answer_modal(qtbot, _click(QMessageBox.StandardButton.Cancel))
    window.load_preset("lecture", presets.lecture_scene)  # another scene: asks too
    assert asked and window.model.scene.objects[-1].name == "box"

    asked = _answer_modal(qtbot, _click(QMessageBox.StandardButton.Discard))
    window.close()
    assert asked and not window.isVisible()


QUIT_DISCARDING = r"""
import os
import sys
from PySide6.QtCore import QTimer
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import QApplication, QMessageBox
from app import cli
from app.window.main_window import MainWindow

app = QApplication(sys.argv[:1])


def answer():
    box = QApplication.activeModalWidget()
    if isinstance(box, QMessageBox):
        print("asked:", box.text().splitlines()[0], flush=True)
        box.button(QMessageBox.StandardButton.Discard).click()
    else:
        QTimer.singleShot(20, answer)


def edit_and_quit():
    window = next((w for w in app.topLevelWidgets() if isinstance(w, MainWindow) and w.isVisible()), None)
    if window is None:
        QTimer.singleShot(20, edit_and_quit)
        return
    window.editor.add_light()
    QTimer.singleShot(0, answer)
    quits = [a for a in window.findChildren(QAction) if a.shortcut() == QKeySequence.StandardKey.Quit]
    quit_action = quits[0]
    quit_action.trigger()  # what Ctrl+Q does (a key needs the window active, which Xvfb alone never makes)


QTimer.singleShot(0, edit_and_quit)
QTimer.singleShot(120_000, lambda: os._exit(3))  # never a hung test
sys.exit(cli.main([]))
"""


def test_quitting_with_ctrl_q_and_discarding_the_edits_ends_quietly(tmp_path):
    """The undo stack, deleted after the window, told the window it was clean again: a RuntimeError and
    its traceback on the terminal at every such quit."""
    import os
    import subprocess
    import sys

    from checkout import ROOT

    out = subprocess.run([sys.executable, "-c", QUIT_DISCARDING], cwd=ROOT, capture_output=True, text=True,
                         env={**os.environ, "XDG_CONFIG_HOME": str(tmp_path)}, timeout=300)
    assert out.returncode == 0, out.stderr
    assert "asked: The scene has changes that are not saved" in out.stdout
    assert "Traceback" not in out.stderr and "RuntimeError" not in out.stderr, out.stderr


def test_save_from_the_question_writes_the_file_and_clears_the_star(qtbot, window, tmp_path):
    path = tmp_path / "edited.json"
    assert open_scene_file(qtbot, window, str(_saved_lecture(path)))
    _editor_action(window, "sphere").trigger()
    assert window.isWindowModified()
    asked = _answer_modal(qtbot, _click(QMessageBox.StandardButton.Save))
    window.load_preset("lecture", presets.lecture_scene)
    assert asked
    assert [o.name for o in scene_file.load(path).objects][-1] == "sphere"
    assert [o.name for o in window.model.scene.objects] == ["cube", "cone", "ground"]
    assert not window.isWindowModified()
    assert window.editor.stack.count() == 0  # a new scene starts a fresh history


def test_undone_past_a_save_the_question_names_the_undone_edit_and_an_equal_scene_starts_afresh(
        qtbot, window, tmp_path):
    """Saved with a sphere added, then undone: the question read "(, …)" (nothing left to undo), and
    the lecture scene loaded after Discard, equal to the one shown, kept the history: the title's star,
    Redo of the edit, and the question again at quitting."""
    path = tmp_path / "a.json"
    assert open_scene_file(qtbot, window, str(_saved_lecture(path)))
    _editor_action(window, "sphere").trigger()
    window.editor.save_action.trigger()
    window.editor.undo_action.trigger()  # the scene is the lecture's again, unlike a.json
    assert window.isWindowModified()
    seen = []

    def read_and_discard(box):
        seen.append(box.text())
        box.button(QMessageBox.StandardButton.Discard).click()

    _answer_modal(qtbot, read_and_discard)
    window.load_preset("lecture", presets.lecture_scene)
    qtbot.waitUntil(lambda: bool(seen))
    assert seen[0] == ("The scene has changes that are not saved (undone: Add sphere, …).\n"
                       "Save them to a.json first?")
    assert not window.isWindowModified() and window.editor.stack.count() == 0
    assert not window.editor.redo_action.isEnabled()
    assert window.editor.may_replace_scene()  # nothing to ask about


def test_a_scene_that_cannot_be_saved_says_why_naming_the_file_once(qtbot, window, tmp_path, monkeypatch):
    shown = []
    monkeypatch.setattr(QMessageBox, "critical", lambda _parent, title, text, *_: shown.append((title, text)))
    _editor_action(window, "sphere").trigger()
    path = tmp_path / "gone" / "a.json"  # no such folder
    assert not window.editor.save_to(path)
    ((title, text),) = shown
    assert title == "Cannot save scene" and text.startswith("Could not save a.json:\n\n")
    assert text.count(str(path)) == 1 and "No such file or directory" in text
    assert window.isWindowModified() and window.scene_path != path and not path.exists()


def _saved_lecture(path):
    scene_file.save(presets.lecture_scene(), path)
    return path


def _fresh_window(qtbot):
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    return win


def test_saved_scene_and_observer_come_back_in_a_fresh_window(qtbot, window, tmp_path):
    path = _saved_lecture(tmp_path / "kept.json")
    assert open_scene_file(qtbot, window, str(path))
    _editor_action(window, "pyramid").trigger()
    window.editor.save_action.trigger()  # Ctrl+S: into the scene's file
    assert not window.isWindowModified()
    assert [o.name for o in scene_file.load(path).objects][-1] == "pyramid"
    moved = window.model.camera.orbit(window.model.camera.yaw_deg + 40, 10.0)
    window.model.set_camera(moved)
    session.remember(window)

    fresh = _fresh_window(qtbot)
    assert session.restore(fresh)
    assert [o.name for o in fresh.model.scene.objects] == ["cube", "cone", "ground", "pyramid"]
    assert fresh.model.camera == moved
    assert fresh.scene_path == path and "kept.json" in fresh.windowTitle()
    assert not fresh.isWindowModified()


def test_discarded_edits_are_not_kept_but_the_observer_is(qtbot, window):
    _editor_action(window, "pyramid").trigger()
    moved = window.model.camera.orbit(window.model.camera.yaw_deg - 40, 15.0)
    window.model.set_camera(moved)
    session.remember(window)  # as after "Discard" at closing

    fresh = _fresh_window(qtbot)
    assert session.restore(fresh)
    assert [o.name for o in fresh.model.scene.objects] == ["cube", "cone", "ground"]
    assert fresh.model.camera == moved


def test_settings_that_no_longer_load_are_reported_and_the_lecture_scene_kept(qtbot):
    store = user_settings()
    store.setValue(session.SCENE, '{"objects": [{"type": "sphere", "center": [0, 0, 0], "radius": -1}]}')
    store.sync()
    fresh = _fresh_window(qtbot)
    assert not session.restore(fresh)
    assert fresh.model.scene == presets.lecture_scene()
    said = fresh.statusBar().currentMessage()
    assert "objects[0].radius: must be > 0, got -1" in said
    assert said.startswith("The last session could not be restored, so the lecture scene is shown")
    assert f"(in {store.fileName()})" in said  # where the broken session is kept


def test_a_scene_file_on_the_command_line_wins_over_the_last_session(qtbot, tmp_path):
    store = user_settings()
    store.setValue(session.SCENE, '{"objects": [{"type": "box", "center": [0, 0, 0], "size": 1}]}')
    store.sync()
    given = tmp_path / "given.json"
    scene_file.save(presets.lecture_scene(), given)
    shown = []

    def close_once_shown():
        win = next((w for w in QApplication.topLevelWidgets()
                    if isinstance(w, MainWindow) and w.isVisible() and w.scene_path == given), None)
        if win is None:
            QTimer.singleShot(50, close_once_shown)
            return
        shown.append([o.name for o in win.model.scene.objects])
        win.close()

    QTimer.singleShot(0, close_once_shown)
    assert run(str(given)) == 0
    assert shown == [["cube", "cone", "ground"]]
    fresh = _fresh_window(qtbot)  # and at the next start without a file, that file comes back
    assert session.restore(fresh)
    assert fresh.scene_path == given


def _centre(obj):
    return (obj.vertices.min(axis=0) + obj.vertices.max(axis=0)) / 2


def test_clicking_an_object_in_the_3d_pane_selects_it(qtbot, window):
    view, model = window.scene_view, window.model
    at = view.widget_pos(_centre(model.scene.objects[0]))
    assert view.grabbable_at(at) is None  # the cube's centre is not where the eye or the target is
    qtbot.mouseClick(view.plotter, Qt.MouseButton.LeftButton, pos=at.toPoint())
    assert model.selection == ("object", 0)
    assert window.editor.panel.tree.currentItem().text(0) == "cube"
    assert window.editor.dock.isVisible()
    assert window.editor.picker.handle_center is not None
    # Nothing under the mouse (high above the scene): nothing selected.
    empty = view.widget_pos(np.add(model.camera.target, (0.0, 40.0, 0.0)))
    qtbot.mouseClick(view.plotter, Qt.MouseButton.LeftButton, pos=empty.toPoint())
    assert model.selection is None and window.editor.picker.handle_center is None


def test_clicking_an_object_during_a_lesson_keeps_the_lesson_in_front(qtbot, window):
    view, model = window.scene_view, window.model
    window.lesson_dock.raise_()
    window.lesson_panel.select(0, 0)  # a lesson step is shown: its words are in the left dock
    qtbot.waitUntil(lambda: in_front(window.lesson_dock))
    at = view.widget_pos(_centre(model.scene.objects[0]))
    assert view.grabbable_at(at) is None
    qtbot.mouseClick(view.plotter, Qt.MouseButton.LeftButton, pos=at.toPoint())
    assert model.selection == ("object", 0)
    assert in_front(window.lesson_dock) and not in_front(window.editor.dock)
    assert "Editor tab" in window.statusBar().currentMessage()


def test_dragging_the_handle_moves_the_object_in_one_undo_step(qtbot, window):
    view, model, editor = window.scene_view, window.model, window.editor
    model.set_selection(("object", 0))
    before = _centre(model.scene.objects[0])
    start = view.widget_pos(editor.picker.handle_center)
    qtbot.mousePress(view.plotter, Qt.MouseButton.LeftButton, pos=start.toPoint())
    for k in range(1, 9):
        qtbot.mouseMove(view.plotter, pos=(start + QPointF(5 * k, -2 * k)).toPoint())
    # While dragging, the cube itself is drawn moved with its handle (the scene is not edited yet).
    moved = np.asarray(view.view.actor_of(("object", 0)).user_matrix)[:3, 3]
    assert np.linalg.norm(moved) > 0.1 and editor.stack.count() == 0
    end = start + QPointF(40, -16)
    qtbot.mouseRelease(view.plotter, Qt.MouseButton.LeftButton, pos=end.toPoint())
    after = _centre(model.scene.objects[0])
    assert not np.allclose(after, before)
    assert editor.stack.count() == 1 and editor.undo_action.text() == "Undo Move cube"
    # It moved in the plane facing the overview camera, and landed under the mouse.
    direction = np.asarray(view.plotter.camera.direction)
    assert np.dot(after - before, direction) == pytest.approx(0.0, abs=0.01)
    landed = view.widget_pos(editor.picker.handle_center)
    assert abs(landed.x() - end.x()) <= 1.5 and abs(landed.y() - end.y()) <= 1.5
    assert model.selection == ("object", 0)
    editor.undo_action.trigger()
    assert np.allclose(_centre(model.scene.objects[0]), before)


def test_clicking_a_light_in_the_3d_pane_selects_it(qtbot, window):
    view, model = window.scene_view, window.model
    light = np.asarray(model.scene.lights[0].position, float)
    # Turn the overview towards the light (it may sit above the default framing), as a user would.
    view.plotter.camera_position = [tuple(light + (4.0, 1.0, 4.0)), tuple(light), (0.0, 1.0, 0.0)]
    view.plotter.reset_camera_clipping_range()
    at = view.widget_pos(light)
    assert view.plotter.rect().contains(at.toPoint())
    qtbot.mouseClick(view.plotter, Qt.MouseButton.LeftButton, pos=at.toPoint())
    assert model.selection == ("light", 0)
    assert window.editor.picker.handle_center is not None
    # The handle floats above the light's marker, which is what was clicked.
    assert window.editor.picker.handle_center[1] > light[1]


def test_a_mesh_of_one_triangle_says_one_triangle(qtbot, window):
    # The cube's 12 triangles, then its first alone: "1 triangles" before.
    model, panel = window.model, window.editor.panel
    cube, *others = model.scene.objects
    model.set_selection(("object", 0))
    assert panel.title.text().endswith(", 12 triangles")
    single = replace(cube, triangles=cube.triangles[:1])
    model.set_scene(replace(model.scene, objects=(single, *others)), edit=True)
    model.set_selection(("object", 0))
    assert panel.title.text().endswith(", 1 triangle")
