"""The rasterizer's scratch arrays are kept from frame to frame (one set per thread):
a frame must come out exactly as it does in a thread that never drew before,
whatever the thread drew earlier, larger or smaller."""

from __future__ import annotations

import threading

import numpy as np

from core import shapes
from core.camera import Camera
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Mesh, PointLight, Scene


def _scene(rings: int, eye) -> Scene:
    ball = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings, 2 * rings)
    mesh = Mesh(ball.vertices, ball.triangles, Material(color=(0.85, 0.6, 0.3)), "ball")
    camera = Camera(eye=eye, target=(0.0, 0.0, 0.0), fov_y_deg=40, near=0.5, far=10.0, width=160,
                    height=120)
    return Scene(camera=camera, objects=(mesh,), lights=(PointLight((3.0, 5.0, 6.0)),))


def _frame(scene: Scene):
    result = render_raster(scene, RasterSettings(record_steps=True))
    return result.color, result.zbuffer, result.draw.generated, result.draw.passed, result.history.fragments


def _in_a_new_thread(scene: Scene):
    out = []
    thread = threading.Thread(target=lambda: out.append(_frame(scene)))
    thread.start()
    thread.join()
    return out[0]


def _same(a, b) -> bool:
    (*arrays_a, frags_a), (*arrays_b, frags_b) = a, b
    return (all(np.array_equal(x, y) for x, y in zip(arrays_a, arrays_b, strict=True))
            and np.array_equal(frags_a.pixel, frags_b.pixel) and np.array_equal(frags_a.z, frags_b.z)
            and np.array_equal(frags_a.passed, frags_b.passed))


def test_a_frame_after_a_larger_and_after_a_smaller_one_equals_a_fresh_one():
    middle, large = _scene(40, (0.0, 0.6, 3.4)), _scene(90, (0.3, -0.4, 3.0))
    small = _scene(6, (2.0, 1.0, 2.5))
    fresh = {name: _in_a_new_thread(scene) for name, scene in
             (("middle", middle), ("large", large), ("small", small))}
    drawn = {name: len(frame[2]) for name, frame in fresh.items()}  # polygons drawn
    assert drawn["large"] > drawn["middle"] > drawn["small"] > 0
    assert all(len(frame[4]) > 0 for frame in fresh.values())  # fragments
    for name, scene in (("large", large), ("middle", middle), ("small", small), ("middle", middle),
                        ("large", large)):
        assert _same(_frame(scene), fresh[name]), name
