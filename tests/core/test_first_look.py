"""The first look (numpy, before the kernels compile) shows what the tracer shows, lit as worked by hand."""

import numpy as np

from core import presets, shapes
from core.camera import Camera
from core.first_look import first_look
from core.image_order.ray_tracing import TraceSettings, render_trace
from core.scene import Material, PointLight, Scene


def test_it_covers_the_pixels_the_tracer_sees_objects_in():
    scene = presets.lecture_scene()
    look = first_look(scene, step=1)
    traced = render_trace(scene, TraceSettings(mode="raycast"))
    background = np.all(np.isclose(look, scene.background), axis=-1)
    agree = background == (traced.object_index < 0)
    # Only pixels whose centre lies on an outline may differ (the cone's facets are coarser here).
    assert agree.mean() > 0.99
    assert (~background).sum() > 0.2 * background.size  # the scene is there, not an empty field


def test_a_face_lit_head_on_has_its_colour_times_ambient_plus_diffuse():
    # A quad facing +z, the eye and the light straight in front of it: N . L = 1 at its centre,
    # so the colour is color * (k_a + k_d * intensity)
    #                 = (0.5, 0.25, 1.0) * (0.1 + 0.6 * 0.5) = (0.2, 0.1, 0.4).
    material = Material(color=(0.5, 0.25, 1.0), ambient=0.1, diffuse=0.6)
    wall = shapes.quad((0.0, 0.0, 0.0), (4.0, 4.0), material=material)
    wall = type(wall)(wall.vertices @ np.array([[1, 0, 0], [0, 0, 1], [0, 1, 0]]), wall.triangles,
                      material=material, name="wall")  # the ground-plane quad stood up to face +z
    scene = Scene(objects=(wall,), lights=(PointLight((0.0, 0.0, 50.0), intensity=0.5),),
                  camera=Camera(eye=(0.0, 0.0, 10.0), target=(0.0, 0.0, 0.0), width=21, height=21),
                  background=(0.0, 0.0, 0.0))
    look = first_look(scene, step=1)
    assert np.allclose(look[10, 10], (0.2, 0.1, 0.4), atol=1e-3)
    assert np.allclose(look[0, 0], 0.0)  # the corner pixel looks past the wall at the background
