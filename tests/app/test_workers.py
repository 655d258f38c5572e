"""Background renders: the newest request wins, a cancelled one stops early."""

import threading
from dataclasses import replace

import numpy as np

from app.workers import Renderer, RenderRequest, render
from core import presets, raycast


def test_background_render_matches_the_direct_ray_cast():
    scene = presets.lecture_scene()
    bands = []
    result = render(RenderRequest(1, scene), progress=lambda pct, img: bands.append(pct))
    direct = raycast.cast(scene)
    assert np.array_equal(result.color, direct.color)
    assert np.array_equal(result.t, direct.t)
    assert bands == sorted(bands) and bands[-1] == 100 and len(bands) > 1
    assert set(result.timings) == {"rays", "intersect", "shade"}


def test_cancelled_render_returns_nothing():
    cancelled = threading.Event()
    seen = []

    def progress(pct, img):
        seen.append(pct)
        cancelled.set()  # the user moved on after the first band

    assert render(RenderRequest(1, presets.lecture_scene()), cancelled, progress) is None
    assert len(seen) == 1


def test_only_the_newest_request_is_delivered(qtbot):
    renderer = Renderer()
    delivered = []
    renderer.finished.connect(delivered.append)
    scene = presets.lecture_scene()
    renderer.request(scene)
    moved = scene.camera.orbit(scene.camera.yaw_deg + 30, 20)
    newest = renderer.request(replace(scene, camera=moved))
    qtbot.waitUntil(lambda: not renderer.busy, timeout=20000)
    assert [r.request_id for r in delivered] == [newest]
