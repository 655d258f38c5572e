"""The window's memory budget: a render over it never starts, says what to reduce; the window stays usable.

The 16384 x 16384 scene runs the real window in a subprocess, so that its peak
memory can be read and a regression cannot exhaust the machine (an
address-space limit turns it into a failure).  Peaks are read as ``VmHWM``, the
high-water mark of the subprocess's own memory: ``ru_maxrss`` would start at
the forking pytest process's size.  The other tests
use a small budget on a moderately large image, in the test's own window.
"""

import json
import subprocess
import sys
from dataclasses import replace

import pytest
from checkout import ROOT
from PySide6.QtWidgets import QMessageBox
from window_helpers import RENDER_TIMEOUT_MS, open_scene_file

from app import render_budget
from core import budget, presets
from core.files import scene_file
from core.scene import PointLight
from views.panels.pane_cover import covered_with

PEAK = """
def peak_bytes():  # the high-water mark of this process's resident memory
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) * 1024 for line in status if line.startswith("VmHWM:"))
"""

DRIVER = PEAK + """
import json, os, resource, sys
resource.setrlimit(resource.RLIMIT_AS, (6 * 2**30, 6 * 2**30))  # a regression fails, the machine lives
from PySide6.QtCore import QTimer
from PySide6.QtWidgets import QApplication, QMessageBox
from app.window import main_window

app = QApplication([])
seen = {}

def windows(kind):
    return [w for w in QApplication.topLevelWidgets() if isinstance(w, kind) and w.isVisible()]

def look():
    boxes, [win] = windows(QMessageBox), windows(main_window.MainWindow)
    if "box" not in seen and boxes:
        seen.update(box=boxes[0].text(), progress=win.progress.format(), caption=win.status_caption.text(),
                    peak=peak_bytes())
        boxes[0].accept()
        win.camera_panel.resolution.setCurrentIndex(0)  # 160 x 120: the window renders it
    elif "box" in seen and win.showing_full("image order"):
        seen["rendered"] = list(win.tab("image order").widget.image.rgb.shape)
        win.close()

def give_up():  # the refusal comes at once, before any render; without it, no waiting for one
    if "box" not in seen:
        print(json.dumps(seen), flush=True)
        os._exit(1)

timer = QTimer()
timer.timeout.connect(look)
timer.start(50)
QTimer.singleShot(60_000, give_up)
status = main_window.run(sys.argv[1])
print(json.dumps({"status": status, **seen}))
"""


@pytest.mark.gui
def test_opening_a_16384_square_scene_shows_why_allocates_none_of_it_and_renders_a_smaller_one(tmp_path):
    path = tmp_path / "big.json"
    path.write_text(json.dumps({"camera": {"eye": [0, 1, 6], "target": [0, 0, 0],
                                           "width": 16384, "height": 16384},
                                "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1}]}))
    out = subprocess.run([sys.executable, "-c", DRIVER, str(path)], cwd=ROOT, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    seen = json.loads(out.stdout.splitlines()[-1])
    for fragment in ("big.json", "16384 × 16384", "GB", "the budget is", "smaller Image size"):
        assert fragment in seen["box"]
    assert seen["progress"] == "Image order: not rendered, over the memory budget"
    assert "smaller Image size" in seen["caption"]
    # The window alone peaks at about 0.6 GB; one 8-bit copy of this image is 0.8 GB, its float
    # colour buffer 6.4 GB, so nothing of the image was allocated.
    assert seen["peak"] < 1.3e9
    assert seen["rendered"] == [120, 160, 3] and seen["status"] == 0


def _saved(tmp_path, scene, name):
    path = tmp_path / name
    scene_file.save(scene, path)
    return path


def test_a_scene_over_the_budget_is_refused_in_every_tab_and_a_smaller_image_renders(qtbot, window, tmp_path):
    window.model.memory_limit = 200_000_000
    large = presets.lecture_scene()
    large = replace(large, camera=large.camera.replace(width=2000, height=1500))
    shown = []
    window.image_shown.connect(lambda title, preview: shown.append(title))
    assert open_scene_file(qtbot, window, _saved(tmp_path, large, "large.json"))

    [box] = [b for b in window.findChildren(QMessageBox) if b.isVisible()]
    for fragment in ("large.json", "Image order: the 2000 × 1500 image", "the budget is 200 MB",
                     "smaller Image size"):
        assert fragment in box.text()
    assert all(title in box.informativeText() for title in ("Object order", "Four views", "Compare"))
    box.accept()
    assert window.model.scene.camera.width == 2000  # the scene is open, to be made smaller
    assert window.camera_panel.resolution.currentIndex() == -1
    assert window.camera_panel.resolution.placeholderText() == "2000 × 1500"
    for name in ("Image order", "Object order", "Four views", "Compare"):
        window.show_tab(name)
        assert window.progress.format() == f"{name}: not rendered, over the memory budget"
        assert "smaller Image size" in window.status_caption.text()
        assert not window.renders.busy(window.tab(name))
        assert "the budget is 200 MB" in covered_with(window.tab(name).widget)  # no stale image as current
    assert shown == []

    window.show_tab("image order")
    window.camera_panel.resolution.setCurrentIndex(1)  # 320 x 240
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    assert window.tab("image order").widget.image.rgb.shape == (240, 320, 3)
    assert window.progress.format() == "Image order: done"
    assert covered_with(window.tab("image order").widget) is None


def test_previews_while_the_observer_moves_are_budgeted_too(window):
    window.model.memory_limit = 20_000_000
    scene = window.model.scene
    window.model.set_scene(replace(scene, camera=scene.camera.replace(width=960, height=720)))
    camera = window.model.camera
    window.model.set_camera(camera.orbit(camera.yaw_deg + 5, camera.pitch_deg))  # a preview is due
    assert window.progress.format() == "Image order: not rendered, over the memory budget"
    assert window.status_caption.text().startswith("Image order preview: the 960 × 720 image")
    assert "smaller Image size" in window.statusBar().currentMessage()
    assert not window.renders.busy(window.tab("image order"))


def test_a_full_render_estimated_to_be_long_is_announced_before_it_starts(qtbot, window):
    # 960 x 720 rays, each with 5 shadow rays and, the cube a mirror, up to 5 bounces: about 7 s by the
    # estimate.
    scene = window.model.scene
    lights = tuple(PointLight((5.0 * k - 10, 6.0, 8.0)) for k in range(5))
    cube, *others = scene.objects
    mirror = replace(cube, material=replace(cube.material, reflectivity=0.6))
    slow = replace(scene, objects=(mirror, *others), lights=lights,
                   camera=scene.camera.replace(width=960, height=720))
    assert budget.estimate(slow, "raytrace").seconds > budget.SLOW_SECONDS
    window.model.set_scene(slow)
    for text in (window.statusBar().currentMessage(), window.status_caption.text()):
        assert text.startswith("Image order: estimated about") and "Esc cancels" in text
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)


def test_the_estimate_counts_bounces_only_where_a_surface_mirrors_or_refracts():
    """With no mirror and no glass a traced frame has only primary and shadow rays: counting five
    bounces for every pixel put a 200-frame orbit of the lecture scene at "about 6 min" where it took
    14 s."""
    scene = presets.lecture_scene()
    pixels, lights = scene.camera.width * scene.camera.height, len(scene.lights)
    plain = budget.estimate(scene, "raytrace", max_depth=5)
    assert plain.seconds == pytest.approx(pixels * (1 + lights) * budget.SECONDS_PER_RAY)
    assert plain.seconds == pytest.approx(budget.estimate(scene, "raycast").seconds)
    cube, *others = scene.objects
    see_through = replace(cube, material=replace(cube.material, transparency=0.5))
    glass = replace(scene, objects=(see_through, *others))
    assert budget.estimate(glass, "raytrace", max_depth=5).seconds == pytest.approx(6 * plain.seconds)


class _Tab:
    title = "Example"

    def __init__(self, cost):
        self.cost = lambda scene, preview: cost


@pytest.mark.parametrize(("part", "advice"), [("image buffers", "smaller Image size"),
                                              ("shown images", "smaller Image size"),
                                              ("triangles", "fewer objects or triangles")])
def test_a_refusal_names_what_takes_the_most_memory(part, advice):
    parts = {"image buffers": 1, "triangles": 1, "shown images": 1, part: 3 * 10**9}
    tab = _Tab(budget.Estimate(sum(parts.values()), parts, 1.0))
    refusal, warning = render_budget.check(tab, presets.lecture_scene(), False, 10**9)
    assert refusal.startswith("Example: the 320 × 240 image of 3 objects needs about 3 GB")
    assert "the budget is 1 GB (the window's --memory-limit)" in refusal and advice in refusal
    assert warning is None


def test_tabs_without_a_cost_are_never_refused():
    class Panel:
        title = "Hard cases"

    assert render_budget.check(Panel(), presets.lecture_scene(), False, 1) == (None, None)


MEASURE = PEAK + """
import json, sys, threading
from dataclasses import replace
from PySide6.QtWidgets import QApplication
app = QApplication([])
from app.window import tabs
from app.window.state import SceneModel
from core import presets

title = sys.argv[1]
scene = presets.lecture_scene()
scene = replace(scene, camera=scene.camera.replace(width=1024, height=768))
tab = next(cls for cls in tabs.TABS if cls.title == title)(SceneModel(scene))
small = replace(scene, camera=scene.camera.replace(width=32, height=24))
tab.show(tab.job(small, False)(threading.Event(), lambda *_: None))  # kernels and panels ready
before = peak_bytes()
tab.show(tab.job(scene, False)(threading.Event(), lambda *_: None))
app.processEvents()
after = peak_bytes()
print(json.dumps({"measured": after - before, "estimated": tab.cost(scene, False).bytes}))
"""


@pytest.mark.gui
@pytest.mark.parametrize("title", ["Image order", "Object order", "Four views", "Compare"])
def test_a_tabs_estimate_covers_the_memory_its_render_takes(title):
    out = subprocess.run([sys.executable, "-c", MEASURE, title], cwd=ROOT, capture_output=True,
                         text=True, timeout=600)
    assert out.returncode == 0, out.stderr[-3000:]
    figures = json.loads(out.stdout.splitlines()[-1])
    # Estimates are good to a factor of about two, and err on the large side.
    assert figures["measured"] <= figures["estimated"] <= 3 * figures["measured"]


def test_a_bad_memory_limit_for_the_window_is_refused_before_it_opens(tmp_path):
    out = subprocess.run([sys.executable, "-m", "app", "--memory-limit", "lots", str(tmp_path / "s.json")],
                         cwd=ROOT, capture_output=True, text=True, timeout=120)
    assert out.returncode == 2 and "Traceback" not in out.stderr
    assert "--memory-limit: expected a size such as 8G" in out.stderr
