"""The three orthographic views frame the objects, and their outlines keep edge-on faces visible."""

from dataclasses import replace

import numpy as np
import pytest

from core import presets, shapes
from core.camera import Camera
from core.object_order import three_views
from core.object_order.outlines import outlined
from core.object_order.pipeline import RasterSettings, render_raster
from core.scene import Material, Scene


def _pixel_box(camera, points):
    """Pixel bounding box of world points, each projected on its own by the projection module."""
    pixels = np.array([camera.project(p).pixel for p in points])
    return pixels.min(axis=0), pixels.max(axis=0)


@pytest.mark.parametrize("name", list(three_views.VIEWS))
def test_each_view_is_framed_on_the_cube_and_cone_not_on_the_wide_ground(name):
    scene = presets.lecture_scene()
    camera = three_views.orthographic_views(scene, 320, 240)[name]
    solids = np.vstack([o.vertices for o in scene.objects if o.name != "ground"])
    low, high = _pixel_box(camera, solids)
    extent = (high - low) / (camera.width, camera.height)
    assert np.all(low >= 0) and np.all(high <= (camera.width, camera.height))  # all of them in view
    assert extent.max() >= 0.8  # they fill the view across (the ground alone is 3.5 times wider)
    assert extent.prod() >= 0.2


def test_a_scene_of_flat_polygons_alone_is_framed_whole():
    flat = [shapes.quad((x, 0.0, 0.0), 1.0, name=f"tile {x}") for x in (0.0, 3.0)]
    scene = Scene(camera=Camera(), objects=tuple(flat))
    low, high = three_views.framing_bounds(scene)
    assert np.allclose(low, [-0.5, 0.0, -0.5]) and np.allclose(high, [3.5, 0.0, 0.5])


def _front(scene):
    camera = three_views.orthographic_views(scene, 160, 120)["front"]
    raster = render_raster(replace(scene, camera=camera), RasterSettings())
    return camera, raster, outlined(raster.color, raster.depth, raster.meshes, camera)


def test_the_ground_seen_edge_on_in_the_front_view_is_drawn_as_its_outline():
    scene = presets.lecture_scene()
    camera, raster, image = _front(scene)
    row = int(camera.project((0.0, 0.0, 0.0)).pixel[1])  # the ground plane y = 0, edge-on
    rows = slice(max(row - 1, 0), row + 2)
    background = np.asarray(scene.background)
    solids = np.vstack([o.vertices for o in scene.objects if o.name != "ground"])
    (x0, _), (x1, _) = _pixel_box(camera, solids)
    beside = np.r_[0:int(x0) - 1, int(x1) + 2:camera.width]  # columns left and right of the solids
    plain = np.all(np.isclose(raster.color[rows], background), axis=2).all(axis=0)
    inked = ~np.all(np.isclose(image[rows], background), axis=2).all(axis=0)
    assert plain[beside].all()  # the z-buffer alone draws nothing of the ground there
    assert inked.mean() > 0.95  # the outline runs across the whole view


def test_edges_hidden_behind_a_nearer_face_are_not_inked():
    red, blue = Material(color=(0.9, 0.1, 0.1)), Material(color=(0.1, 0.2, 0.9))
    scene = Scene(camera=Camera(), objects=(shapes.box((0.0, 0.0, 0.0), 2.0, red, "front box"),
                                            shapes.box((0.0, 0.0, -3.0), 1.0, blue, "hidden box")))
    camera, raster, image = _front(scene)
    (x0, y0), (x1, y1) = _pixel_box(camera, scene.objects[0].vertices)
    inside = (slice(int(y0) + 2, int(y1) - 2), slice(int(x0) + 2, int(x1) - 2))
    assert np.array_equal(image[inside], raster.color[inside])  # the blue box's edges stay hidden
    border = (int((y0 + y1) / 2), slice(int(x0) - 1, int(x0) + 2))
    assert not np.array_equal(image[border], raster.color[border])  # the red box's own edge is inked
