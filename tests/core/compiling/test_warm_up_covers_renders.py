"""The kernels' warm-up loads every compiled version a render needs.

numba compiles a kernel once per kind of argument (a read-only array is a kind
of its own). A version the warm-up did not load is compiled, or read from the
disk cache, the first time a render needs it: seconds inside one of the
render's stages, reported as that stage's time, after the window said the
kernels were ready. So, in a fresh process: warm up both halves, then render
every example and every lesson step with the step's own settings (z-buffer
steps, traced bands and the coarse preview too), every z-buffer format and
stage switch, and every acceleration method, offset and mode; no kernel may
gain a version meanwhile.
"""

from __future__ import annotations

import json
import subprocess
import sys

from checkout import ROOT

_RENDER_EVERYTHING = """
import json
import sys
from dataclasses import replace

from numba.core.registry import CPUDispatcher

from core import presets, presets_trace
from core.image_order import ray_tracing
from core.image_order.flat_scene import TraceSettings
from core.image_order.flat_layout import ACCEL_CODES
from core.lessons.lesson_file import shipped_lessons
from core.object_order import pipeline
from core.object_order.depth_formats import DEPTH_FORMATS
from core.object_order.pipeline import RasterSettings, render_raster


def versions():
    found = {}
    for name, module in list(sys.modules.items()):
        if name.startswith("core"):
            for thing in list(vars(module).values()):
                if isinstance(thing, CPUDispatcher):
                    key = f"{thing.py_func.__module__}.{thing.py_func.__name__}"
                    found[key] = sorted(map(str, thing.signatures))
    return found


def small(scene):
    return replace(scene, camera=scene.camera.replace(width=40, height=30))


ray_tracing.ensure_compiled()
pipeline.ensure_compiled()
warm = versions()
scenes = [small(build()) for _, build in (*presets.PRESETS.values(), *presets_trace.PRESETS_TRACE.values())]
for scene in scenes:
    render_raster(scene, RasterSettings(record_steps=True))
for lesson in shipped_lessons():
    for step in lesson.steps:
        scene = small(step.scene)
        history = render_raster(scene, replace(step.object_order, record_steps=True)).history
        history.buffers(history.n_steps)
        ray_tracing.render_trace(scene, step.image_order, rows=(0, 15))
        ray_tracing.render_trace(scene, step.image_order, step=4)
for depth_format in DEPTH_FORMATS:
    render_raster(scenes[0], RasterSettings(depth_format=depth_format, record_steps=True))
for stage in ("back_face_culling", "frustum_culling", "clipping", "sort_transparent", "z_test"):
    render_raster(small(presets.frustum_cases()), RasterSettings(**{stage: False}))
for accel in ACCEL_CODES:
    for offset in ("scaled", "fixed"):
        for mode in ("raycast", "raytrace"):
            settings = TraceSettings(mode=mode, accel=accel, offset=offset)
            ray_tracing.render_trace(small(presets_trace.mirror_and_glass()), settings)
after = versions()
print(json.dumps({"kernels": len(warm),
                  "new": {k: [s for s in v if s not in warm.get(k, [])] for k, v in after.items()
                          if v != warm.get(k)}}))
"""


def test_no_render_compiles_or_loads_a_kernel_after_the_warm_up():
    done = subprocess.run([sys.executable, "-c", _RENDER_EVERYTHING], cwd=ROOT, capture_output=True,
                          text=True, timeout=1200)
    assert done.returncode == 0, done.stderr[-2000:]
    found = json.loads(done.stdout.splitlines()[-1])
    assert found["kernels"] >= 20  # both halves' kernels were found and warmed
    assert found["new"] == {}
