"""A stop request ends a compiled render that would run for hours (issue 35).

The renders below trace or fill for minutes to hours if nothing stops them (90,000 triangles
without acceleration at 800 x 600; 40,000 triangles, each covering half the image, one behind
the other at 2048 x 2048: 80 billion fragments).  A request set from another thread, as
Cancel in the window does, makes them raise :class:`core.stopping.StoppedError`; the join's
timeout only guards against a hang.
"""

from __future__ import annotations

import threading

import numpy as np
import pytest

from core import stopping
from core.camera import Camera
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Mesh, PointLight, Scene
from core.shapes import uv_sphere


def _hours_of_tracing():
    cam = Camera(eye=(0, 0, 6), target=(0, 0, 0), width=800, height=600)
    sphere = uv_sphere((0, 0, 0), 1.5, rings=150, segments=300)
    return Scene(camera=cam, objects=(sphere,), lights=(PointLight((5, 5, 5)),))


def _minutes_of_filling(n=20_000):
    corners = np.array([[-50, -50], [50, -50], [50, 50], [-50, 50]], float)
    vertices = np.concatenate([np.column_stack([corners, np.full(4, -k * 1e-3)]) for k in range(n)])
    quads = np.arange(n)[:, None] * 4
    triangles = np.concatenate([quads + [0, 1, 2], quads + [0, 2, 3]])
    cam = Camera(eye=(0, 0, 5), target=(0, 0, 0), width=2048, height=2048)
    mesh = Mesh(vertices, triangles, Material())
    return Scene(camera=cam, objects=(mesh,), lights=(PointLight((5, 5, 5)),))


def _stopped_after(render, seconds: float):
    """Run ``render()`` on a thread whose stop request is set after ``seconds``; what it raised."""
    request, outcome = stopping.StopRequest(), {}

    def job():
        with stopping.stopped_by(request):
            try:
                outcome["result"] = render()
            except stopping.StoppedError as exc:
                outcome["stopped"] = exc

    worker = threading.Thread(target=job)
    worker.start()
    threading.Timer(seconds, request.set).start()
    worker.join(timeout=120)
    assert not worker.is_alive(), "still rendering 2 minutes after the stop request"
    return outcome


@pytest.mark.parametrize("seconds", [0.0, 1.5])
def test_a_stop_request_ends_a_render_of_hours_without_acceleration(seconds):
    outcome = _stopped_after(lambda: render_trace(_hours_of_tracing(), TraceSettings(accel="none")), seconds)
    assert "stopped" in outcome and "result" not in outcome


def test_a_stop_request_ends_a_raster_fill_of_minutes():
    outcome = _stopped_after(lambda: render_raster(_minutes_of_filling()), 1.5)
    assert "stopped" in outcome and "result" not in outcome


def test_a_stopped_draw_that_records_its_steps_gathers_no_fragment():
    # Recording the steps gathers every drawn fragment afterwards: a draw stopped before its first
    # piece must gather none (the pieces it never drew have no counts; reading them wrote out of
    # bounds, and a superseded lesson step's render crashed the window).
    request = stopping.StopRequest()
    request.set()
    with stopping.stopped_by(request), pytest.raises(stopping.StoppedError):
        render_raster(_minutes_of_filling(50), RasterSettings(record_steps=True))


def test_a_request_of_another_thread_does_not_stop_this_one():
    other = stopping.StopRequest()
    other.set()
    small = Scene(camera=Camera(width=8, height=6), objects=(uv_sphere((0, 0, 0), 1.0, rings=4, segments=6),),
                  lights=(PointLight((5, 5, 5)),))
    with stopping.stopped_by(stopping.StopRequest()):
        assert render_trace(small, TraceSettings(accel="none")).color.shape == (6, 8, 3)
        assert render_raster(small).color.shape == (6, 8, 3)


def test_kernels_of_two_threads_watch_and_stop_watching_the_same_request():
    # Two renders at once (a tab's and an export's) both watch Ctrl+C's request; the one that ends
    # first must leave the other's flag watched. (Removing an entry by == compared the flag arrays.)
    first, second = np.zeros(8), np.zeros(8)
    request = stopping.StopRequest()
    with request._watched(first, 0):
        with request._watched(second, 3):
            pass
        request.set()
    assert first[0] == 1 and second[3] == 0  # the first still watched; the ended second left alone
