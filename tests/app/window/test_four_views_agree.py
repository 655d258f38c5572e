"""The four views the command line writes are the ones the window's Four views tab shows."""

import subprocess
import sys
from dataclasses import replace

import imageio.v3 as iio
import numpy as np
from checkout import ROOT
from PySide6.QtWidgets import QFileDialog
from window_helpers import RENDER_TIMEOUT_MS

from app.export.picture_sheet import MARGIN, TITLE_ROW
from core.files import scene_file
from core.object_order.four_views import four_cameras
from core.object_order.pipeline import render_raster
from core.srgb import to_srgb8


def test_cli_four_views_equal_the_windows_sheet_outlines_and_all(qtbot, window, tmp_path, monkeypatch):
    scene = window.model.scene
    window.show_tab("four views")
    qtbot.waitUntil(lambda: window.showing_full("four views"), timeout=RENDER_TIMEOUT_MS)
    shown = tmp_path / "window.png"
    monkeypatch.setattr(QFileDialog, "getSaveFileName", lambda *a: (str(shown), "PNG image (*.png)"))
    window.exports.refresh()
    window.exports.actions["Four views/All 4 panes as one picture"].trigger()
    qtbot.waitUntil(lambda: not window.exports.writing(), timeout=RENDER_TIMEOUT_MS)  # written off the GUI
    scene_path, written = tmp_path / "scene.json", tmp_path / "cli.png"
    scene_file.save(scene, scene_path)
    result = subprocess.run([sys.executable, "-m", "app", "export", str(scene_path), "--what", "four-views",
                             "--out", str(written)], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert result.returncode == 0, result.stderr
    in_window, from_cli = iio.imread(shown), iio.imread(written)
    # The same panels under the same titles; the command line adds a caption line below.
    assert from_cli.shape[1] == in_window.shape[1] and from_cli.shape[0] > in_window.shape[0]
    assert np.array_equal(from_cli[:in_window.shape[0]], in_window)
    # ... and the front view has its edges inked: a plain z-buffer render of it differs.
    cam = scene.camera
    front = from_cli[MARGIN + TITLE_ROW:MARGIN + TITLE_ROW + cam.height, MARGIN:MARGIN + cam.width]
    plain = to_srgb8(render_raster(replace(scene, camera=four_cameras(scene)["front"])).color)
    inked = np.abs(front.astype(int) - plain.astype(int)).max(axis=2) > 40
    assert inked.sum() > cam.width  # at least the ground's rim, seen edge-on, across the view
