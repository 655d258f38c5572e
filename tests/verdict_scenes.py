"""Scenes whose pixels' verdicts are known without running the pipelines (tests of core.pixel_verdict).

Each scene comes with a pixel and what decides it there, worked out by hand in the
comments.  Images are 40 x 30 pixels (even), looking straight down the world's -y
axis unless said otherwise, with ``up = (0, 0, -1)``: image right is world +x and
image down is world +z.  The image's centre lies between pixels, so the pixel
(22, 14) used below sits 2.5 pixels right of and 0.5 pixels above the centre: off
every quad's and box face's diagonal (those run at 45 degrees on the screen) and
off every edge.
"""

from __future__ import annotations

import math

from core.camera import Camera
from core.scene import Material, PointLight, Scene, Sphere
from core.shapes import box, quad

#: The pixel the looking-down scenes ask about (see the module's notes).
PIXEL = (22, 14)


def _down(eye_height: float = 10.0, near: float = 1.0, far: float = 30.0) -> Camera:
    return Camera(eye=(0.0, eye_height, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), fov_y_deg=40.0,
                  near=near, far=far, width=40, height=30)


def back_face_only() -> Scene:
    """A ground quad seen from below: its normal is +y, the eye at y = -10 looks up at its back.

    Only the quad's back face covers the centre of the image, so back-face culling drops
    it: the verdict is ``culled`` and the pixel keeps the background.
    """
    cam = Camera(eye=(0.0, -10.0, 0.0), target=(0.0, 0.0, 0.0), up=(0.0, 0.0, -1.0), width=40, height=30)
    return Scene(camera=cam, objects=(quad((0, 0, 0), 4.0, name="ground"),))


def two_quads(near_first: bool = True) -> Scene:
    """Two ground-like quads under the eye (y = 10): ``near`` at y = 2 (distance 8), ``far`` at y = 0 (10).

    Both cover the pixel; the z-buffer keeps ``near``.  Drawn first, ``near`` makes
    ``far`` fail the z-test; drawn second, it overwrites ``far``'s fragment.
    """
    near = quad((0, 2, 0), 3.0, Material(color=(0.9, 0.2, 0.2)), name="near")
    far = quad((0, 0, 0), 6.0, Material(color=(0.2, 0.2, 0.9)), name="far")
    return Scene(camera=_down(), objects=(near, far) if near_first else (far, near))


def before_near_plane() -> Scene:
    """A quad 0.5 below the eye, nearer than the near plane (1): clipping removes it at every pixel.

    The verdict is ``clipped`` at the ``near`` plane, at distance 0.5.
    """
    return Scene(camera=_down(near=1.0), objects=(quad((0, 9.5, 0), 4.0, name="pane"),))


def beyond_far_plane() -> Scene:
    """A quad ``distant`` of side 6 at y = -30, 40 below the eye, beyond the far plane (30).

    Its bounding sphere has radius at least the half-diagonal 3 sqrt(2) = 4.24 (and
    any bounding sphere of it fits inside a radius 6, twice that), and its centre lies
    40 - 30 = 10 beyond the far plane: the whole sphere is outside, so frustum
    culling drops the object before clipping.  The verdict is ``frustum-culled`` at
    the ``far`` plane, at distance 40.  (A pixel spans 2 x 40 tan 20° / 30 = 0.97 units at
    distance 40: the pixel's ray meets the quad's plane 2.5 x 0.97 = 2.43 units to the
    side and 0.49 along, inside its half-side 3.)  With frustum culling off, clipping
    cuts it away at the same plane instead: ``clipped``, ``far``.
    """
    return Scene(camera=_down(far=30.0), objects=(quad((0, -30, 0), 6.0, name="distant"),))


def pane_over_box() -> Scene:
    """A transparent quad ``pane`` (opacity 0.4) at y = 2 over an opaque ``box`` of side 2 at the origin.

    Drawn opaque first, then transparent: the box's top face (y = 1, distance 9) is
    kept, its bottom face (y = -1, distance 11) is a back face from above and is culled,
    and the pane's fragment (distance 8) is blended over the top face.  (A pixel spans
    2 d tan 20° / 30 = 0.22 units at distance d = 9: the pixel's ray meets the box
    0.55 units off its axis, well inside its faces.)
    """
    pane = quad((0, 2, 0), 4.0, Material(color=(0.2, 0.4, 1.0), opacity=0.4), name="pane")
    return Scene(camera=_down(), objects=(pane, box((0, 0, 0), 2.0, name="box")))


def ball_shadow() -> Scene:
    """A ``ball`` over a ``floor``, lit by ``sun`` straight above it and by ``fill`` off to the side.

    The ball: r 0.5 at (0, 1.5, 0); the floor: y = 0; sun at (0, 5, 0), fill at (0, 5, 10).

    The camera at (0, 3, 6) looks at the origin, through the centre of its odd-sized
    (41 x 31) image: pixel (20, 15).  Its ray to the origin passes the ball's centre at
    distance sqrt(1.8) = 1.34 > 0.5, so it hits the floor at the origin, t = |(0, 3, 6)|
    = sqrt(45).  The shadow ray to ``sun`` goes straight up through the ball: blocked;
    the one to ``fill`` passes the ball's centre at distance sqrt(1.8) again: lit.
    """
    cam = Camera(eye=(0.0, 3.0, 6.0), target=(0.0, 0.0, 0.0), width=41, height=31)
    floor = quad((0, 0, 0), 10.0, name="floor")
    ball = Sphere((0.0, 1.5, 0.0), 0.5, name="ball")
    lights = (PointLight((0.0, 5.0, 0.0), name="sun"), PointLight((0.0, 5.0, 10.0), name="fill"))
    return Scene(camera=cam, objects=(floor, ball), lights=lights)


def mirror_ball() -> Scene:
    """A ``mirror`` ball (reflectivity 0.8, r 1 at the origin), the eye at (0, 0, 5), a ``wall`` behind it.

    The centre pixel (20, 15) of the 41 x 31 image looks straight down -z: it hits the
    mirror at (0, 0, 1), t = 4, where the normal is +z, so the reflected ray goes
    straight back along +z and hits the wall (a box at z = 8, behind the eye, which
    primary rays cannot see).
    """
    cam = Camera(eye=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), width=41, height=31)
    mirror = Sphere((0.0, 0.0, 0.0), 1.0, Material(reflectivity=0.8), name="mirror")
    wall = box((0, 0, 8), (6.0, 6.0, 0.2), name="wall")
    return Scene(camera=cam, objects=(mirror, wall), lights=(PointLight((0.0, 4.0, 4.0), name="lamp"),))


def glass_ball() -> Scene:
    """A ``glass`` ball (transparency 0.9, ior 1.5, r 1 at the origin) before a ``backdrop`` at z = -4.

    The centre pixel's ray meets the ball head on at (0, 0, 1), t = 4: Fresnel at normal
    incidence from air into glass gives R = ((1.5 - 1) / (1.5 + 1))^2 = 0.04 and
    T = 0.96.  The refracted ray goes straight on and meets the glass again from inside
    at (0, 0, -1).
    """
    cam = Camera(eye=(0.0, 0.0, 5.0), target=(0.0, 0.0, 0.0), width=41, height=31)
    glass = Sphere((0.0, 0.0, 0.0), 1.0, Material(transparency=0.9, ior=1.5), name="glass")
    backdrop = box((0, 0, -4), (8.0, 8.0, 0.2), name="backdrop")
    return Scene(camera=cam, objects=(glass, backdrop), lights=(PointLight((0.0, 4.0, 4.0), name="lamp"),))


def glass_block() -> Scene:
    """A ray inside a ``glass`` block (ior 1.5) meets its side beyond the critical angle.

    The block: a box of side 2 at the origin (top y = 1, sides x = +-1, bottom y = -1).
    The centre pixel (20, 15) of the 41 x 31 image looks through the target P = (0.5, 1, 0)
    on the top face along d = (sin 60, -cos 60, 0) = (0.866, -0.5, 0), from the eye
    P - 4 d, so t = 4 and the angle of incidence is 60 degrees.  Fresnel there, cos 60 = 0.5 and
    cos(theta2) = 0.8165: r_s = (0.5 - 1.5 x 0.8165) / (0.5 + 1.5 x 0.8165) = -0.4202, r_p = (0.8165 -
    1.5 x 0.5) / (0.8165 + 1.5 x 0.5) = 0.0425, R = (r_s^2 + r_p^2) / 2 = 0.0892.  Snell: sin(theta2) =
    sin 60 / 1.5 = 0.577, theta2 = 35.3 degrees; the refracted ray (0.577, -0.816, 0) crosses
    the 0.5 to the side x = 1 after 0.866, at y = 1 - 0.707 = 0.293, inside the side face.
    There its angle of incidence is 90 - 35.3 = 54.7 degrees, beyond the critical angle
    asin(1 / 1.5) = 41.8 degrees: total internal reflection inside the glass (the second
    surface the pixel's rays meet).  The ray reflected back (-0.577, -0.816, 0) reaches the
    bottom y = -1 at x = 1 - 1.293 x 0.707 = 0.086, at 35.3 degrees: it leaves the glass, and
    its part reflected there (-0.577, 0.816, 0) climbs 1.086 x sqrt(2) = 1.536 on its way to the
    side x = -1, meeting it at y = 0.536, again at 54.7 degrees: a second total internal reflection.
    """
    eye = (0.5 - 4.0 * math.sqrt(3.0) / 2.0, 1.0 + 4.0 * 0.5, 0.0)  # P - 4 d
    cam = Camera(eye=eye, target=(0.5, 1.0, 0.0), width=41, height=31)
    glass = box((0, 0, 0), 2.0, Material(transparency=0.9, ior=1.5), name="glass")
    return Scene(camera=cam, objects=(glass,), lights=(PointLight((0.0, 6.0, 0.0), name="lamp"),))
