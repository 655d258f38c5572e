"""Start-up: the window opens and works before VTK loads; the 3D pane comes in afterwards as asked."""

import os
import subprocess
import sys
import threading

import numpy as np
import pytest
from checkout import ROOT, TYPESETTING
from PySide6.QtCore import Qt
from PySide6.QtWidgets import QApplication, QLabel
from window_helpers import RENDER_TIMEOUT_MS

from app.bench.startup import watched_start
from app.window.main_window import MainWindow
from core import presets
from core.lessons.lesson_file import shipped_lessons
from views import gui_thread
from views.scene3d import deferred_scene_view
from views.scene3d.deferred_scene_view import PLACEHOLDER

LATER = ("vtkmodules", "pyvista", "pyvistaqt", "matplotlib", "mpmath", "numba")
"""What the 3D pane, the Cost plot, typesetting a new formula, the hard cases and the renders'
compiled kernels need, and the window's first frame does not."""


def test_importing_the_window_loads_nothing_its_first_frame_does_not_need():
    code = ("import sys, app.window.main_window; "
            f"print(','.join(m for m in {LATER!r} if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == ""


FIRST_FRAME = TYPESETTING + """
import sys
from app import cli
from PySide6.QtCore import QEvent, QObject, QTimer
from PySide6.QtWidgets import QApplication
from views.scene3d.deferred_scene_view import DeferredSceneView


def build_soon(self, *_):  # the 3D pane stays out: what is checked is the window's own first frame
    pass


DeferredSceneView.build_soon = build_soon
seen = []

def all_typeset():  # the first start ends once its formulas are typeset and kept
    views = [view for view in app.allWidgets() if type(view).__name__ == "MathView"]
    if views and not any(view.pending for view in views):
        seen[0] = typesetting()
        app.quit()


class FirstFormula(QObject):
    def eventFilter(self, obj, event):
        if event.type() == QEvent.Type.Paint and type(obj).__name__ == "MathView" and not seen:
            seen.append(typesetting())
            if sys.argv[1:] == ["second"]:
                app.quit()
            else:
                QTimer(app, interval=50, timeout=all_typeset).start()
        return False

app = QApplication(sys.argv[:1])
watch = FirstFormula()
app.installEventFilter(watch)
status = cli.main([])  # opened and ended as python -m app opens and ends them
print(seen[0])
sys.exit(status)
"""


@pytest.mark.gui
def test_the_second_start_paints_its_lesson_formulas_without_typesetting_them(tmp_path):
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path),  # an empty formula cache at first
           "XDG_CONFIG_HOME": str(tmp_path)}  # no last session: the lecture scene
    loaded = []
    for start in ("first", "second"):
        out = subprocess.run([sys.executable, "-c", FIRST_FRAME, start], cwd=ROOT, capture_output=True,
                             text=True, env=env, timeout=300)
        assert out.returncode == 0, out.stderr
        loaded.append(out.stdout.split()[-1])
    assert loaded == ["True", "False"]  # typeset once, then read from the cache


@pytest.mark.gui
def test_the_window_is_painted_before_numba_loads_and_its_first_image_follows():
    """numba takes about half a second to import: the window must not wait for it, the render does.
    Watched as ``python -m app bench startup`` watches a start (no last session: the lecture scene)."""
    start = watched_start(RENDER_TIMEOUT_MS / 1000, ROOT)
    assert not start["shown"].numba_loaded  # painted without numba
    assert start["image"].numba_loaded  # the image needed it


@pytest.fixture
def opening(qtbot, monkeypatch):
    """The window just shown; its 3D pane is built when its first image is shown, not on a timer."""
    monkeypatch.setattr(deferred_scene_view, "BUILD_AFTER_MS", 3_600_000)
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    win.show()
    qtbot.waitExposed(win)
    return win


def test_keys_move_the_observer_and_a_tab_shows_its_image_before_the_3d_pane_exists(qtbot, opening):
    win = opening
    pane_built_at_image = []
    win.image_shown.connect(lambda *_: pane_built_at_image.append(win.scene_view.view is not None))
    assert win.scene_view.view is None
    assert win.scene_view.findChild(QLabel).text() == PLACEHOLDER
    win.activateWindow()
    qtbot.waitUntil(win.isActiveWindow)
    before = win.model.camera
    qtbot.keyClick(win, Qt.Key.Key_W)  # walk forward a tenth of the eye-to-target distance
    view = np.subtract(before.target, before.eye)
    assert np.allclose(np.subtract(win.model.camera.eye, before.eye), 0.1 * view)
    assert win.scene_view.view is None
    qtbot.waitUntil(lambda: win.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    image = win.tab("image order").widget.image
    assert image.rgb.shape[:2] == (win.model.camera.height, win.model.camera.width)
    assert pane_built_at_image[0] is False  # the first image came before VTK
    qtbot.waitUntil(lambda: win.scene_view.view is not None)
    assert np.allclose(win.scene_view.frustum.points, win.model.camera.frustum_corners())


def _unit(v):
    return np.asarray(v, float) / np.linalg.norm(v)


def test_what_a_lesson_asks_of_the_3d_pane_before_it_exists_shows_once_it_is_built(qtbot, opening):
    win = opening
    lesson = next(i for i, lesson in enumerate(shipped_lessons()) if lesson.id == "observer")
    step = shipped_lessons()[lesson].steps[0]
    win.lesson_panel.select(lesson, 0)
    assert win.scene_view.view is None
    asked = win.scene_view.overlay_names()
    assert "lesson" in asked
    qtbot.waitUntil(lambda: win.scene_view.view is not None, timeout=RENDER_TIMEOUT_MS)
    view = win.scene_view.view
    assert set(asked) <= set(view.overlay_names())
    lit, names = view.overlay_parts("lesson")  # the highlighted object, and the names the text speaks of
    assert "object 3" in list(names.point_data["labels"])
    obj = next(o for o in step.scene.objects if o.name == step.highlight["object"])
    low, high = np.array(lit.bounds).reshape(3, 2).T
    assert np.allclose(low, obj.vertices.min(axis=0)) and np.allclose(high, obj.vertices.max(axis=0))
    # The step's view, stepped back so that its frustum and the planes' labels fit (it shows the frustum).
    position, focal_point, up = (np.asarray(v, float) for v in view.plotter.camera_position)
    asked_direction = np.subtract(step.view["focal_point"], step.view["position"])
    assert np.allclose(_unit(focal_point - position), _unit(asked_direction))
    assert np.dot(_unit(up), _unit(step.view["up"])) > 0.99


def test_the_3d_pane_comes_in_on_its_own_when_no_image_is_shown(qtbot, monkeypatch):
    monkeypatch.setattr(deferred_scene_view, "BUILD_AFTER_MS", 100)
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    win.show_tab("hard cases")  # a tab that renders nothing: no first image to wait for
    shown = []
    win.image_shown.connect(lambda *_: shown.append(1))
    win.show()
    qtbot.waitUntil(lambda: win.scene_view.view is not None, timeout=RENDER_TIMEOUT_MS)
    assert shown == []
    assert np.allclose(win.scene_view.frustum.points, win.model.camera.frustum_corners())


def test_the_3d_pane_is_built_in_two_turns_around_a_render_window_the_import_thread_made(qtbot, monkeypatch):
    # Built in one go, it held the window 110-120 ms (VTK's widget and OpenGL 70, the actors the
    # rest); in two turns the first still held it 83-97 ms, and in three (the render window first)
    # that first turn 61-100 ms: VTK tries a window of the X server to make the first render window,
    # loading OpenGL.  The import thread makes it now.
    import vtkmodules.vtkRenderingCore

    from views.scene3d.image_plotter import ImagePlotter

    made_on = {}  # each render window made, by the thread that made it
    real = vtkmodules.vtkRenderingCore.vtkRenderWindow

    def noted_window():
        window = real()
        made_on[window] = threading.current_thread()
        return window

    monkeypatch.setattr(vtkmodules.vtkRenderingCore, "vtkRenderWindow", noted_window)
    monkeypatch.setattr(deferred_scene_view, "BUILD_AFTER_MS", 100)
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    pane = win.scene_view
    seen = []  # connected after the pane's own slot: what the turn that hears from the thread left
    told = gui_thread.messenger().told
    told.connect(note := lambda target, _call: target() is pane and seen.append((pane.view,
                                                                                  pane.findChild(ImagePlotter))))
    win.show()
    qtbot.waitUntil(lambda: pane.view is not None, timeout=RENDER_TIMEOUT_MS)
    told.disconnect(note)
    [(view, plotter)] = seen
    assert view is None and isinstance(plotter, ImagePlotter)  # VTK's widget, the view a turn later
    assert pane.view.plotter is plotter
    assert made_on[plotter.ren_win] is not threading.main_thread()  # in the window the import thread made


def test_a_window_closed_while_its_3d_pane_loads_builds_no_pane_after(qtbot, monkeypatch):
    # It went on to build the pane: VTK's render window and its OpenGL context, which nothing then
    # closed, for Python's garbage collector to destroy on whichever thread ran it.
    from views.scene3d.image_plotter import ImagePlotter

    made = []
    init = ImagePlotter.__init__
    monkeypatch.setattr(ImagePlotter, "__init__", lambda plotter, *a: made.append(1) or init(plotter, *a))
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    pane = win.scene_view
    loaded = []
    told = gui_thread.messenger().told
    told.connect(note := lambda target, _call: target() is pane and loaded.append(1))
    win.show()
    pane.build_soon()  # pyvista is imported on a thread ...
    win.close()  # ... and the window closes meanwhile
    qtbot.waitUntil(lambda: loaded == [1], timeout=RENDER_TIMEOUT_MS)
    told.disconnect(note)
    QApplication.processEvents()  # the turn VTK's widget would have been made in, and the next
    QApplication.processEvents()
    assert made == [] and pane.view is None and pane.findChild(ImagePlotter) is None


def test_a_window_closed_between_vtks_widget_and_the_view_closes_vtks_widget(qtbot, monkeypatch):
    from views.scene3d.image_plotter import ImagePlotter

    monkeypatch.setattr(deferred_scene_view, "BUILD_AFTER_MS", 100)
    monkeypatch.setattr(deferred_scene_view.DeferredSceneView, "build", lambda pane: None)  # the third turn
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    win.show()
    pane = win.scene_view
    qtbot.waitUntil(lambda: pane.findChild(ImagePlotter) is not None, timeout=RENDER_TIMEOUT_MS)
    plotter = pane.findChild(ImagePlotter)
    assert plotter.ren_win.GetGenericContext() is not None  # VTK's widget has its OpenGL context
    win.close()
    assert plotter.ren_win is None and plotter.iren is None  # closed (pyvista's close): the window finalized
    assert pane.view is None


def test_the_first_render_starts_once_the_window_is_painted(qtbot):
    win = MainWindow(presets.lecture_scene())
    qtbot.addWidget(win)
    assert not win.renders.busy(win.current)  # loading the kernels would hold up the first frame
    assert win.progress.format() == "Image order: not rendered yet"
    win.show()
    qtbot.waitUntil(lambda: win.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    image = win.tab("image order").widget.image
    assert image.rgb.shape[:2] == (win.model.camera.height, win.model.camera.width)


BUILD_IMPORTS = """
import sys
from PySide6.QtWidgets import QApplication
from views import gui_thread
from views.scene3d import deferred_scene_view

deferred_scene_view.BUILD_AFTER_MS = 3_600_000
app = QApplication(sys.argv[:1])
from app.window.main_window import MainWindow
from core import presets
window = MainWindow(presets.lecture_scene())
deferred_scene_view._import_pyvista(lambda: None)  # what the import thread runs (for no pane)
before = set(sys.modules)
window.scene_view.build()  # on the GUI thread
assert window.scene_view.view is not None
print(",".join(sorted(set(sys.modules) - before)) or "-")
"""


@pytest.mark.gui
def test_building_the_3d_pane_on_the_gui_thread_imports_nothing():
    """Every module the 3D pane loads comes in on the import thread: an import on the GUI thread
    (VTK's widgets and views took 90 ms, the pane's own modules 100 ms) froze the window."""
    out = subprocess.run([sys.executable, "-c", BUILD_IMPORTS], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    assert out.stdout.split()[-1] == "-"


TYPESETTING_LOADED = """
import sys
from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication
from views import gui_thread
from views.scene3d import deferred_scene_view
from views.text import math_view

deferred_scene_view.DeferredSceneView.build_soon = lambda self, *_: None  # no 3D pane: pyvista stays out
app = QApplication(sys.argv[:1])
from app.window.main_window import MainWindow
from core import presets
window = MainWindow(presets.lecture_scene())
window.image_shown.connect(lambda *_: app.quit())
QTimer.singleShot(TIMEOUT_MS, app.quit)
window.show()
app.exec()
started = math_view.loader is not None  # by the first image
math_view.load_typesetting_soon().join(60)
before = set(sys.modules)
math_view.render_mathtext("$t = 0.123456$", 14.0, "#000000", 96.0)  # a formula no cache holds
print(started, "pyvista" in sys.modules, ",".join(sorted(set(sys.modules) - before)) or "-")
"""


@pytest.mark.gui
def test_the_first_image_starts_loading_typesetting_so_a_new_formula_imports_nothing(tmp_path):
    """A picked pixel's worked math is new formulas: the first one loaded mathtext and its fonts on the
    GUI thread (about 0.2 s). The first image starts loading them on a thread of their own."""
    env = {**os.environ, "XDG_CACHE_HOME": str(tmp_path), "XDG_CONFIG_HOME": str(tmp_path)}
    code = TYPESETTING_LOADED.replace("TIMEOUT_MS", str(RENDER_TIMEOUT_MS))
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, env=env,
                         timeout=RENDER_TIMEOUT_MS / 1000 + 60)
    assert out.returncode == 0, out.stderr
    started, pyvista, imported = out.stdout.split()[-3:]
    assert started == "True"
    assert pyvista == "False"  # typesetting came in by itself, not with the 3D pane's imports
    assert imported == "-"
