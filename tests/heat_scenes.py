"""Scenes whose heat maps are known without running the renderers (tests of what each pixel cost).

Each scene comes with what its heat map holds, worked out by hand in the docstrings.
"""

from __future__ import annotations

import numpy as np

from core.camera import Camera
from core.scene import Material, Mesh, Scene

W, H = 40, 30
#: The pixel column the flat edge runs down the middle of (see :func:`flat_edge`).
EDGE_COLUMN = 24
#: Samples per axis in a refined pixel (the window's, ``core.accuracy.sweep.ADAPTIVE_N``).
N = 4


def flat_edge() -> Scene:
    """An edge between two flat colours: white (exactly 1, no lights) on the left, black background right.

    An orthographic camera, one scene unit per pixel, looking down -z: pixel
    coordinates (x right, y down) are world ``(x - W/2, H/2 - y)``.  The white
    rectangle ``left`` ends at world x = 4.5, pixel x = 24.5: the middle of pixel
    column 24, and it reaches far past the top, bottom and left of the image.

    Adaptive supersampling traces the pixels' corners, at whole pixel coordinates:
    those with x <= 24 are white (1, 1, 1), those with x >= 25 black.  Only the
    pixels of column 24 have corners of both colours (x = 24 and x = 25), so with
    any threshold below 1 they, and they alone, are refined: 1 + N^2 = 17 samples
    each, 1 everywhere else.  Rays traced: the (W + 1)(H + 1) = 41 x 31 = 1271
    corners, plus N^2 = 16 for each of the H = 30 refined pixels, 480: 1751.
    """
    cam = Camera(eye=(0.0, 0.0, 10.0), target=(0.0, 0.0, 0.0), projection="orthographic",
                 ortho_height=float(H), near=1.0, far=20.0, width=W, height=H)
    edge, far = EDGE_COLUMN + 0.5 - W / 2, 1000.0
    white = Material(color=(1.0, 1.0, 1.0), ambient=1.0, diffuse=0.0, specular=0.0)
    # counter-clockwise as the camera (on +z) sees it
    rect = Mesh(vertices=[(-far, -far, 0.0), (edge, -far, 0.0), (edge, far, 0.0), (-far, far, 0.0)],
                triangles=[[0, 1, 2], [0, 2, 3]], material=white, name="left")
    return Scene(camera=cam, objects=(rect,), lights=(), background=(0.0, 0.0, 0.0))


def flat_edge_samples() -> np.ndarray:
    """(H, W) int64, the samples per pixel :func:`flat_edge`'s docstring works out."""
    samples = np.ones((H, W), dtype=np.int64)
    samples[:, EDGE_COLUMN] = 1 + N * N
    return samples


#: Rays adaptive supersampling traces in :func:`flat_edge` (its docstring).
FLAT_EDGE_TRACED = (W + 1) * (H + 1) + N * N * H
