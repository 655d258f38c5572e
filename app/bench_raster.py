"""``python -m app bench raster``: our object-order pipeline against VTK's renderer, frame for frame.

Renders one mesh of about 100,000 triangles (a bumpy sphere) at 640 x 480
with :func:`core.object_order.pipeline.render_raster` and with VTK (pyvista off
screen, multisampling off, colour and depth read back from the render
window), from the same camera, in the same process.  The runs are
interleaved (ours, VTK, ours recording, ours, ...) so that a noisy machine
slows all three alike, and medians are printed.  The numba kernels' compile
time is printed separately: once cold (a fresh cache in a subprocess) and as
the load from the on-disk cache this process did.

This is a benchmark, not a test; nothing here is asserted.  Qt, VTK and
numba are imported only when it runs.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

COLD_COMPILE = """
import time
t = time.perf_counter()
from core.object_order import pipeline
from core import presets
result = pipeline.render_raster(presets.zbuffer_piercing(),
                                pipeline.RasterSettings(record_steps=True))
result.history.buffers(1)
print(time.perf_counter() - t)
"""


def add_arguments(parser) -> None:
    """Add the benchmark's options to ``parser`` (the ``bench raster`` subcommand)."""
    parser.add_argument("--triangles", type=int, default=100_000,
                        help="about how many triangles the mesh has (default 100000)")
    parser.add_argument("--width", type=int, default=640, help="image width in pixels (default 640)")
    parser.add_argument("--height", type=int, default=480, help="image height in pixels (default 480)")
    parser.add_argument("--runs", type=int, default=9, help="timed frames of each kind (default 9)")
    parser.add_argument("--warmup", type=int, default=2, help="untimed frames first (default 2)")
    parser.add_argument("--skip-cold-compile", action="store_true",
                        help="do not measure the kernels' compile time in a fresh cache")


def bench_scene(triangles: int, width: int, height: int):
    """A bumpy sphere of about ``triangles`` triangles filling most of the image, one light."""
    import numpy as np

    from core import shapes
    from core.camera import Camera
    from core.scene import Material, Mesh, PointLight, Scene

    # 2 segments (rings - 1) triangles, with segments = 2 (rings - 1): 4 (rings - 1)^2.
    rings = max(3, round((triangles / 4) ** 0.5) + 1)
    sphere = shapes.uv_sphere((0.0, 0.0, 0.0), 1.0, rings, 2 * (rings - 1))
    v = sphere.vertices
    lon, lat = np.arctan2(v[:, 2], v[:, 0]), np.arcsin(np.clip(v[:, 1], -1, 1))
    bumpy = v * (1.0 + 0.08 * np.sin(7 * lon) * np.cos(6 * lat))[:, None]
    mesh = Mesh(bumpy, sphere.triangles, Material(color=(0.85, 0.6, 0.3)), "bumpy sphere")
    camera = Camera(eye=(0.0, 0.6, 3.4), target=(0.0, 0.0, 0.0), fov_y_deg=40, near=0.5, far=10.0,
                    width=width, height=height)
    return Scene(camera=camera, objects=(mesh,), lights=(PointLight((3.0, 5.0, 6.0)),))


def _cold_compile_seconds() -> float:
    """First render with an empty numba cache, in a subprocess: the kernels' compile time."""
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = subprocess.run([sys.executable, "-c", COLD_COMPILE], cwd=root, env=env, check=True,
                             capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


def _vtk_frame(plotter):
    """One VTK frame: render, then read colour and depth back from the window."""
    plotter.render()
    color = plotter.image
    depth = plotter.get_image_depth(fill_value=None, reset_camera_clipping_range=False)
    return color, depth


def run(args) -> int:
    """Run the benchmark and print its figures; returns the exit status."""
    import numpy as np
    import pyvista as pv

    from core.object_order.kernels import raster as kernels
    from core.object_order.pipeline import RasterSettings, render_raster
    from views import vtk_convert

    scene = bench_scene(args.triangles, args.width, args.height)
    mesh = scene.objects[0]
    print(f"bench raster: {mesh.name}, {len(mesh.triangles):,} triangles, {args.width}x{args.height}, "
          f"median of {args.runs} frames after {args.warmup} warm-up")

    if not args.skip_cold_compile:
        print(f"numba kernels, cold compile (empty cache, subprocess): {_cold_compile_seconds():.2f} s")
    t = time.perf_counter()
    render_raster(bench_scene(200, 32, 24), RasterSettings(record_steps=True)).history.buffers(1)
    first = time.perf_counter() - t
    cached = sum(kernels.draw_triangles.stats.cache_hits.values()) > 0
    print(f"numba kernels, first call in this process ({'loaded from cache' if cached else 'compiled'}): "
          f"{first:.2f} s")

    plotter = pv.Plotter(off_screen=True, window_size=(args.width, args.height))
    plotter.disable_anti_aliasing()  # pyvista turns 8x MSAA on by default
    plotter.add_mesh(vtk_convert.mesh_polydata(mesh), color=mesh.material.color)
    vtk_convert.apply_camera(plotter.camera, scene.camera)
    plotter.show(auto_close=False)

    plain, recording = RasterSettings(), RasterSettings(record_steps=True)
    frames = {"ours": lambda: render_raster(scene, plain), "vtk": lambda: _vtk_frame(plotter),
              "recording": lambda: render_raster(scene, recording)}
    times: dict[str, list[float]] = {name: [] for name in frames}
    for i in range(args.warmup + args.runs):
        for name, frame in frames.items():
            t = time.perf_counter()
            frame()
            if i >= args.warmup:
                times[name].append(time.perf_counter() - t)
    plotter.close()

    med = {name: float(np.median(ts)) for name, ts in times.items()}
    result = render_raster(scene, recording)
    fragments, nbytes = len(result.history.fragments), result.history.nbytes
    print(f"ours, plain frame:                      {med['ours'] * 1e3:8.1f} ms")
    print(f"VTK frame (render + colour + depth):    {med['vtk'] * 1e3:8.1f} ms")
    print(f"ratio ours / VTK:                       {med['ours'] / med['vtk']:8.2f}")
    print(f"ours, recording steps:                  {med['recording'] * 1e3:8.1f} ms  "
          f"(ratio to VTK {med['recording'] / med['vtk']:.2f}; {fragments:,} fragments, "
          f"{nbytes / 1e6:.1f} MB)")
    print(f"goal plain <= VTK: {'met' if med['ours'] <= med['vtk'] else 'missed'}; "
          f"recording <= 2 x VTK: {'met' if med['recording'] <= 2 * med['vtk'] else 'missed'}")
    _step_budget(args, render_raster, RasterSettings, np)
    return 0


def _step_budget(args, render_raster, RasterSettings, np) -> None:
    """The step-history budget: 10,000 triangles, memory per fragment and time to rebuild a step."""
    scene = bench_scene(10_000, args.width, args.height)
    no_culling = RasterSettings(back_face_culling=False, record_steps=True)
    history = render_raster(scene, no_culling).history
    rng = np.random.default_rng(0)
    steps = rng.integers(0, history.n_steps + 1, size=max(args.runs, 5))
    rebuild = []
    for k in steps:
        t = time.perf_counter()
        history.buffers(int(k))
        rebuild.append(time.perf_counter() - t)
    fragments = len(history.fragments)
    print(f"step history, {len(scene.objects[0].triangles):,} triangles, culling off: "
          f"{fragments:,} fragments in {history.nbytes / 1e6:.1f} MB "
          f"({history.nbytes / max(fragments, 1):.1f} bytes per fragment); rebuilding a random step: "
          f"median {np.median(rebuild) * 1e3:.1f} ms, worst {max(rebuild) * 1e3:.1f} ms (goal < 50 ms)")
