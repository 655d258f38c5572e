"""A recorded step keeps the 3D pane's viewpoint, the highlight and the heat map through the file."""

from types import MappingProxyType

import numpy as np

from core.files.lesson_file import load_lesson
from core.image_order.flat_scene import TraceSettings
from core.lessons.authoring import add_step, step_record
from core.object_order.pipeline import RasterSettings
from core.presets import culling_pyramid


def test_the_viewpoint_highlight_and_heat_map_are_written_and_read_back(tmp_path):
    scene = culling_pyramid()
    view = {"position": np.array([7.0, 5.5, -6.0]), "focal_point": (0.0, 0.8, 0.0), "up": (0, 1, 0)}
    highlight = MappingProxyType({"face": MappingProxyType({"object": "pyramid", "triangle": np.int64(2)}),
                                  "pixel": (80, 60), "ray": "shadow"})
    step = step_record(title="t", text="w", scene=scene, panes=["object order"], image_order=TraceSettings(),
                       object_order=RasterSettings(), view=view, highlight=highlight,
                       heat_map="box and sphere tests")
    lesson = add_step(tmp_path / "l.json", step)
    again = load_lesson(tmp_path / "l.json").steps[0]
    for read in (lesson.steps[0], again):
        assert dict(read.view) == {"position": (7.0, 5.5, -6.0), "focal_point": (0.0, 0.8, 0.0),
                                   "up": (0.0, 1.0, 0.0)}
        assert dict(read.highlight["face"]) == {"object": "pyramid", "triangle": 2}
        assert read.highlight["pixel"] == (80, 60) and read.highlight["ray"] == "shadow"
        assert read.heat_map == "box and sphere tests"
    plain = step_record(title="t", text="w", scene=scene, panes=["object order"], image_order=TraceSettings(),
                        object_order=RasterSettings())
    assert not {"view", "highlight", "heat_map"} & set(plain)  # nothing to say: the defaults
