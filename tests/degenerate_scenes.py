"""Spheres the scene loader accepts but too small to have any area (issue 35)."""

from core.files import scene_file

TINY = scene_file.from_dict({
    "camera": {"eye": [3, 4, 6], "target": [0, 0, 0], "width": 32, "height": 24},
    "lights": [{"position": [5, 5, 5]}],
    "objects": [{"type": "sphere", "center": [0, 0, 0], "radius": 1e-300},
                {"type": "sphere", "center": [1, 0, 0], "radius": 5e-324}],
})
