"""Our object-order pipeline against a real rasterizer: VTK, same camera, same meshes.

VTK renders the meshes our pipeline drew (analytic spheres tessellated the
same way), off screen, without multisampling, from the same camera
(:func:`views.scene3d.vtk_convert.apply_camera`).  Its z-buffer is read back and
turned into the distance along the viewing axis with the inverse of the
projection's depth row.
"""

from __future__ import annotations

import numpy as np
import pytest
import pyvista as pv
import vtk
from vtk.util.numpy_support import vtk_to_numpy

from core import presets, shapes
from core.camera import Camera
from core.object_order.pipeline import render_raster
from core.scene import Material, Scene
from views.scene3d import vtk_convert

pytestmark = pytest.mark.gui


def vtk_depth(scene: Scene, meshes) -> np.ndarray:
    """(H, W) distance along the viewing axis of what VTK sees, +inf for background."""
    cam = scene.camera
    plotter = pv.Plotter(off_screen=True, window_size=(cam.width, cam.height))
    try:
        plotter.disable_anti_aliasing()
        for mesh in meshes:
            # Back faces culled as in ours: where the near plane cuts a solid open, both show
            # nothing of its inside instead of its inner walls.
            plotter.add_mesh(vtk_convert.mesh_polydata(mesh), color="white", lighting=False,
                             culling="back")
        vtk_convert.apply_camera(plotter.camera, cam)
        plotter.screenshot(return_img=True)  # renders the frame (render() alone does not, before show)
        assert plotter.camera.clipping_range == pytest.approx((cam.near, cam.far))
        grab = vtk.vtkWindowToImageFilter()
        grab.SetInput(plotter.render_window)
        grab.SetInputBufferTypeToZBuffer()
        grab.ReadFrontBufferOff()
        grab.Update()
        zbuf = vtk_to_numpy(grab.GetOutput().GetPointData().GetScalars()).reshape(cam.height, cam.width)
    finally:
        plotter.close()
    zbuf = zbuf[::-1].astype(float)  # VTK's rows run bottom-up
    n, f = cam.near, cam.far
    if cam.projection == "orthographic":
        distance = n + zbuf * (f - n)
    else:
        z_ndc = 2.0 * zbuf - 1.0
        distance = 2.0 * n * f / ((f + n) - z_ndc * (f - n))
    return np.where(zbuf < 1.0, distance, np.inf)


def _lecture(projection: str) -> Scene:
    scene = presets.lecture_scene()
    cam = scene.camera.replace(projection=projection, width=320, height=240)
    return Scene(camera=cam, objects=scene.objects, lights=scene.lights)


def _through_the_near_plane() -> Scene:
    """A ground plane and a box reaching behind the observer, a sphere beside the view."""
    cam = Camera(eye=(0.0, 0.8, 2.0), target=(0.3, 0.4, -3.0), fov_y_deg=60, near=0.6, far=15.0,
                 width=320, height=240)
    objects = (
        shapes.quad((0.0, 0.0, 0.0), 12.0, Material(), "ground"),
        shapes.box((0.9, 0.5, 1.7), (1.0, 1.0, 2.0), Material(), "box through the near plane"),
        shapes.uv_sphere((-1.8, 0.8, -2.5), 1.0, 24, 48, Material(), "sphere"),
    )
    return Scene(camera=cam, objects=objects)


SCENES = {
    "lecture-perspective": lambda: _lecture("perspective"),
    "lecture-orthographic": lambda: _lecture("orthographic"),
    "near-plane-perspective": _through_the_near_plane,
    "near-plane-orthographic": lambda: (lambda s: Scene(camera=s.camera.replace(
        projection="orthographic", ortho_height=5.0), objects=s.objects))(_through_the_near_plane()),
}


@pytest.mark.parametrize("name", SCENES)
def test_coverage_and_depth_match_vtk(name):
    scene = SCENES[name]()
    ours = render_raster(scene)
    if name.startswith("near-plane"):
        assert ours.stats["polygons_clipped"] > 0
    theirs = vtk_depth(scene, ours.meshes)
    ours_covered, theirs_covered = np.isfinite(ours.depth), np.isfinite(theirs)
    assert ours_covered.mean() > 0.15
    agreement = np.mean(ours_covered == theirs_covered)
    assert agreement >= 0.995, f"coverage agrees on only {agreement:.4f} of pixels"
    both = ours_covered & theirs_covered
    relative = np.abs(ours.depth[both] - theirs[both]) / theirs[both]
    # VTK's depth buffer holds 24-bit or float32 values: agreement to ~1e-6 is all it can give.
    assert np.median(relative) < 1e-5
    assert np.mean(relative < 1e-4) >= 0.999, "depth differs where both see a surface"
