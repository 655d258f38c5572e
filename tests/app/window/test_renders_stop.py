"""Cancel in the window stops a compiled render that would run for hours (issue 35).

The job traces 90,000 triangles without acceleration at 800 x 600 (hours).  Once it is inside
the render, Cancel (:meth:`app.renders.Renderer.cancel`) raises the kernel's stop flag and the
pool thread is free again: no result and no failure are delivered.
"""

import threading

from app.renders import Renderer
from core.camera import Camera
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.scene import PointLight, Scene
from core.shapes import uv_sphere


def test_cancel_stops_a_render_of_hours_inside_its_kernel(qtbot):
    scene = Scene(camera=Camera(eye=(0, 0, 6), target=(0, 0, 0), width=800, height=600),
                  objects=(uv_sphere((0, 0, 0), 1.5, rings=150, segments=300),),
                  lights=(PointLight((5, 5, 5)),))
    started, ended = threading.Event(), threading.Event()

    def job(cancelled, progress):
        started.set()
        try:
            return render_trace(scene, TraceSettings(accel="none"))
        finally:
            ended.set()

    renderer = Renderer()
    with qtbot.assertNotEmitted(renderer.finished, wait=200), qtbot.assertNotEmitted(renderer.failed):
        renderer.submit(job)
        qtbot.waitUntil(started.is_set, timeout=10_000)
        renderer.cancel()
        qtbot.waitUntil(ended.is_set, timeout=60_000)  # a guard against a hang: the render takes hours
    assert not renderer.busy
