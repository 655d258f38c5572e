"""File → Export on the Compare tab, as a user works: render a pair, choose an entry, name the file.

The whole comparison saved in the window is checked against an independent
path to the same picture: ``python -m app export --what compare`` run in a
subprocess on the same scene file.
"""

import subprocess
import sys
from dataclasses import replace

import imageio.v3 as iio
import numpy as np
from checkout import ROOT
from matplotlib import colormaps
from PySide6.QtWidgets import QFileDialog
from window_helpers import RENDER_TIMEOUT_MS

from app.export.picture_sheet import MARGIN, TITLE_ROW
from app.window.main_window import MainWindow
from core import presets
from core.compare import OUTPUTS
from core.files import scene_file


def _save_as(monkeypatch, path):
    monkeypatch.setattr(QFileDialog, "getSaveFileName",
                        lambda parent, title, start, filters: (str(path), filters.split(";;")[0]))


def _export(qtbot, window, entry):
    window.exports.refresh()  # what opening the menu does
    action = window.exports.actions[entry]
    assert action.isEnabled(), action.toolTip()
    action.trigger()
    qtbot.waitUntil(lambda: not window.exports.writing(), timeout=RENDER_TIMEOUT_MS)  # encoded off the GUI


def _compare(qtbot, window, a: str, b: str):
    """Show the Compare tab with outputs A and B chosen, and wait for their full comparison."""
    window.show_tab("compare")
    panel = window.tab("compare").widget
    for combo, key in zip(panel.selectors, (a, b), strict=True):
        combo.setCurrentIndex(combo.findData(key))
    qtbot.waitUntil(lambda: window.showing_full("compare") and panel.boxes["a"].title() == f"A: {OUTPUTS[a]}"
                    and panel.boxes["b"].title() == f"B: {OUTPUTS[b]}", timeout=RENDER_TIMEOUT_MS)
    return panel


def test_the_difference_of_an_output_with_itself_is_saved_black_beside_its_scale(qtbot, window, tmp_path,
                                                                                monkeypatch):
    panel = _compare(qtbot, window, "perspective", "perspective")
    window.exports.refresh()
    entries = [key for key in window.exports.actions if key.startswith("Compare/")]
    assert entries == ["Compare/Output A: perspective z-buffer", "Compare/Output B: perspective z-buffer",
                       "Compare/Difference with its colour scale",
                       "Compare/The whole comparison as one picture"]
    for side in ("A", "B"):
        _save_as(monkeypatch, tmp_path / f"{side}.png")
        _export(qtbot, window, f"Compare/Output {side}: perspective z-buffer")
    a, b = iio.imread(tmp_path / "A.png"), iio.imread(tmp_path / "B.png")
    cam = window.model.camera
    assert a.shape == (cam.height, cam.width, 3) and (a == b).all()
    assert len(np.unique(a.reshape(-1, 3), axis=0)) > 20  # the scene, not a blank image

    _save_as(monkeypatch, tmp_path / "difference.png")
    _export(qtbot, window, "Compare/Difference with its colour scale")
    sheet = iio.imread(tmp_path / "difference.png").astype(int)
    top = MARGIN + TITLE_ROW
    region = sheet[top:top + cam.height, MARGIN:MARGIN + cam.width]
    # The colour map's first colour, for a difference of 0: near black.
    zero = np.round(np.asarray(colormaps["magma"](0.0)[:3]) * 255)
    assert (np.abs(region - zero) <= 1).all() and region.max() <= 5
    bar = sheet[top + cam.height + 4:top + cam.height + 14, MARGIN:MARGIN + cam.width]
    assert (np.abs(bar[:, 0] - zero) <= 1).all()  # the scale starts at the colour of no difference
    assert (bar[:, -1] > 150).all()  # and runs to the map's brightest colour
    assert (sheet[top + cam.height + 14:] < 100).any()  # its labels and units, drawn in dark text
    assert panel.views["difference"].rgb.shape[:2] == region.shape[:2]


def test_the_whole_comparison_saved_in_the_window_is_the_command_line_sheet(qtbot, tmp_path, monkeypatch):
    scene = presets.lecture_scene()
    # A small image, and an orthographic view volume other than the default: both paths must honour it.
    camera = scene.camera.replace(width=96, height=72, ortho_height=4.5)
    path = tmp_path / "scene.json"
    scene_file.save(replace(scene, camera=camera), path)
    window = MainWindow(scene_file.load(path))
    qtbot.addWidget(window)
    window.show()
    _compare(qtbot, window, "orthographic", "raytrace")
    _save_as(monkeypatch, tmp_path / "window.png")
    _export(qtbot, window, "Compare/The whole comparison as one picture")

    result = subprocess.run([sys.executable, "-m", "app", "export", str(path), "--what", "compare",
                             "--pair", "orthographic,raytrace", "--out", str(tmp_path / "cli.png")],
                            cwd=ROOT, capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    in_window, on_cli = iio.imread(tmp_path / "window.png"), iio.imread(tmp_path / "cli.png")
    assert in_window.shape == on_cli.shape
    assert in_window.shape[1] >= 3 * 96 + 4 * MARGIN  # A, B and the difference side by side
    assert np.abs(in_window.astype(int) - on_cli.astype(int)).max() <= 1
    difference = in_window[MARGIN + TITLE_ROW:MARGIN + TITLE_ROW + 72, -96 - MARGIN:-MARGIN]
    assert difference.max() > 100  # the projections differ, and the sheet shows where
