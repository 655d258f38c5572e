"""Ray casting: one ray from the eye through each pixel, and how deep its hit lies.

The lecture's image order starts here: "for each pixel we generate the ray
with the beginning in eye of the observer.  The ray goes through the pixel
and then go towards scene until it hit the first object."  In parallel
(orthographic) projection the rays are parallel instead, each starting on the
near plane in front of its pixel.

The formula of that *primary ray* is :func:`core.camera.pixel_ray`, shared
with :meth:`core.camera.Camera.primary_rays`.  The tracer's kernels read the
camera from one flat array (:func:`camera_array`, columns named in
:mod:`core.image_order.flat_layout`); :func:`primary_ray` unpacks it and
compiles the formula in, so the kernels, the ray tree of one pixel
(:mod:`core.image_order.ray_tree`) and the camera trace the very same rays.

What the first hit along each primary ray gives the pixel - colour, shadow
rays, and in ray tracing the reflected and refracted rays - is the work of
:mod:`core.image_order.ray_tracing`.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera, image_plane_point, ray_through
from core.compiling.jitable import jitable
from core.image_order import flat_layout


def camera_array(cam: Camera) -> np.ndarray:
    """The observer as the kernels read it, (CAM_SIZE,) float64 (see :mod:`.flat_layout`)."""
    c = np.zeros(flat_layout.CAM_SIZE)
    c[flat_layout.CAM_EYE:flat_layout.CAM_EYE + 3] = cam.eye
    c[flat_layout.CAM_ROTATION:flat_layout.CAM_ROTATION + 9] = cam.world_from_view[:3, :3].ravel()
    c[flat_layout.CAM_FORWARD:flat_layout.CAM_FORWARD + 3] = cam.forward
    c[flat_layout.CAM_HALF_WIDTH], c[flat_layout.CAM_HALF_HEIGHT] = cam.half_extent(1.0)
    c[flat_layout.CAM_WIDTH], c[flat_layout.CAM_HEIGHT] = cam.width, cam.height
    c[flat_layout.CAM_ORTHOGRAPHIC] = cam.projection == "orthographic"
    c[flat_layout.CAM_NEAR], c[flat_layout.CAM_FAR] = cam.near, cam.far
    return c


@jitable(forceinline=True)
def primary_ray(cam, x, y):
    """The ray through the centre of pixel ``(x, y)``: ``(origin, direction, t_min, t_max)``.

    ``cam`` is :func:`camera_array`; the rest is :func:`core.camera.pixel_ray`
    (``t_min, t_max``: from the near to the far plane).
    """
    px, py = pixel_on_image_plane(cam, x, y)
    return primary_ray_through(cam, px, py)


@jitable(forceinline=True)
def pixel_on_image_plane(cam, x, y):
    """:func:`primary_ray`'s first step, :func:`core.camera.image_plane_point`: ``(px, py)``,
    ``px`` from the column alone and ``py`` from the row, so a render works them out once for
    each column and each row rather than for each pixel."""
    return image_plane_point(x, y, cam[flat_layout.CAM_WIDTH], cam[flat_layout.CAM_HEIGHT],
                             cam[flat_layout.CAM_HALF_WIDTH], cam[flat_layout.CAM_HALF_HEIGHT])


@jitable(forceinline=True)
def primary_ray_through(cam, px, py):
    """:func:`primary_ray` from the pixel's point on the image plane (:func:`pixel_on_image_plane`)."""
    e, r, f = flat_layout.CAM_EYE, flat_layout.CAM_ROTATION, flat_layout.CAM_FORWARD
    return ray_through(px, py, (cam[e], cam[e + 1], cam[e + 2]),
                       (cam[r], cam[r + 1], cam[r + 2], cam[r + 3], cam[r + 4], cam[r + 5], cam[r + 6],
                        cam[r + 7], cam[r + 8]),
                       (cam[f], cam[f + 1], cam[f + 2]), cam[flat_layout.CAM_NEAR], cam[flat_layout.CAM_FAR],
                       cam[flat_layout.CAM_ORTHOGRAPHIC] > 0.0)


@jitable(forceinline=True)
def view_depth(cam, o, d, t):
    """Distance along the viewing axis of the point ``o + t d`` (camera space, positive ahead)."""
    start, step = view_depth_of_ray(cam, o, d)
    return start + t * step


@jitable(forceinline=True)
def view_depth_of_ray(cam, o, d):
    """``(start, step)``: the :func:`view_depth` of the point ``o + t d`` is ``start + t * step``.

    A ray's primary hit is only known after the walk; the two numbers are worked out with the ray
    (for a packet, four rays at a time), and its hit's depth then costs one product and one sum.
    """
    f = flat_layout.CAM_FORWARD
    e = flat_layout.CAM_EYE
    return ((o[0] - cam[e]) * cam[f] + (o[1] - cam[e + 1]) * cam[f + 1] + (o[2] - cam[e + 2]) * cam[f + 2],
            d[0] * cam[f] + d[1] * cam[f + 1] + d[2] * cam[f + 2])
