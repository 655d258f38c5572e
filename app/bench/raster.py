"""``python -m app bench raster``: our object-order pipeline against VTK's renderer, frame for frame.

For each size (``--triangles``, default 10,000, 100,000 and 1,000,000) one
mesh (a bumpy sphere) is rendered at 640 x 480 with
:func:`core.object_order.pipeline.render_raster` and with VTK from the same
camera, in the same process.

VTK's frame is what a program using VTK pays for an image and its depth:
one ``Render()`` of the render window, then the raw readback of colour
(``GetRGBACharPixelData``) and depth (``GetZbufferData``) from that window.
(pyvista's ``get_image_depth`` would render the scene a second time.)  With no
display VTK renders off screen through EGL (``VTK_DEFAULT_OPENGL_WINDOW`` is
set to ``vtkEGLRenderWindow`` before VTK loads); the render window class used
is printed.  Multisampling is off, as in ours.

Four kinds of frame are interleaved (ours, VTK, ours recording steps, ours
with the mesh moved so that the near plane and two side planes cut it) so
that a noisy machine slows all of them alike; each figure is the median
after warm-up, with the lowest and highest run.  The clipped case is
compared with the same mesh fully inside.  The numba kernels' compile time
is printed apart: once cold (an empty cache, in a subprocess) and as the
load from the on-disk cache this process did.  Last, the step-history
budget: bytes per fragment and the time to rebuild a random step.

This is a benchmark, not a test; nothing here is asserted.  VTK and numba
are imported only when it runs.
"""

from __future__ import annotations

import os
import subprocess
import sys
import tempfile
import time

from app.usage import UsageError

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

DEFAULT_SIZES = "10000,100000,1000000"


def add_arguments(parser) -> None:
    """Add the benchmark's options to ``parser`` (the ``bench raster`` subcommand)."""
    parser.add_argument("--triangles", default=DEFAULT_SIZES,
                        help=f"comma-separated mesh sizes, about so many triangles each "
                             f"(default {DEFAULT_SIZES})")
    parser.add_argument("--width", type=int, default=640, help="image width in pixels (default 640)")
    parser.add_argument("--height", type=int, default=480, help="image height in pixels (default 480)")
    parser.add_argument("--runs", type=int, default=7, help="timed frames of each kind (default 7)")
    parser.add_argument("--warmup", type=int, default=2, help="untimed frames first (default 2)")
    parser.add_argument("--skip-cold-compile", action="store_true",
                        help="do not measure the kernels' compile time in a fresh cache")
    parser.add_argument("--skip-step-budget", action="store_true",
                        help="do not measure the step history at 1,000,000 triangles and 1920x1080")


def parse_sizes(text: str) -> list[int]:
    """``"10000,100000"`` -> ``[10000, 100000]``; UsageError naming the bad entry."""
    sizes = []
    for part in text.split(","):
        try:
            n = int(part)
        except ValueError:
            raise UsageError(f"--triangles: {part.strip()!r} is not a whole number") from None
        if not 100 <= n <= 20_000_000:
            raise UsageError(f"--triangles: {n} is outside 100 .. 20000000")
        sizes.append(n)
    return sizes


def bench_scene(triangles: int, width: int, height: int, crossing: bool = False):
    """A bumpy sphere of about ``triangles`` triangles and one light.

    Fully inside the frustum, filling most of the image; with ``crossing``
    the observer stands closer and looks past it, so that the near plane and
    the left and bottom planes cut the mesh (the same mesh).
    """
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
    if crossing:
        camera = Camera(eye=(0.0, 0.3, 2.2), target=(0.9, 0.8, 0.0), fov_y_deg=40, near=1.3,
                        far=10.0, width=width, height=height)
    else:
        camera = Camera(eye=(0.0, 0.6, 3.4), target=(0.0, 0.0, 0.0), fov_y_deg=40, near=0.5,
                        far=10.0, width=width, height=height)
    return Scene(camera=camera, objects=(mesh,), lights=(PointLight((3.0, 5.0, 6.0)),))


def _cold_compile_seconds() -> float:
    """First render with an empty numba cache, in a subprocess: the kernels' compile time."""
    root = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    with tempfile.TemporaryDirectory() as cache:
        env = dict(os.environ, NUMBA_CACHE_DIR=cache)
        out = subprocess.run([sys.executable, "-c", COLD_COMPILE], cwd=root, env=env, check=True,
                             capture_output=True, text=True)
    return float(out.stdout.strip().splitlines()[-1])


class VtkFrame:
    """VTK rendering one mesh into its own render window, read back raw.

    Parameters
    ----------
    scene : a scene of one mesh; its camera and image size are used.
    """

    def __init__(self, scene):
        import pyvista as pv
        import vtk

        from views.scene3d import vtk_convert

        cam = scene.camera
        self.width, self.height = cam.width, cam.height
        mesh = scene.objects[0]
        self.window = vtk.vtkRenderWindow()
        self.window.SetOffScreenRendering(1)
        self.window.SetMultiSamples(0)
        self.window.SetSize(cam.width, cam.height)
        self.renderer = vtk.vtkRenderer()
        self.renderer.SetBackground(*scene.background)
        self.window.AddRenderer(self.renderer)
        mapper = vtk.vtkPolyDataMapper()
        mapper.SetInputData(vtk_convert.mesh_polydata(mesh))
        actor = vtk.vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(*mesh.material.color)
        self.renderer.AddActor(actor)
        light = scene.lights[0]
        vtk_light = vtk.vtkLight()
        vtk_light.SetPosition(*light.position)
        vtk_light.SetPositional(True)
        self.renderer.AddLight(vtk_light)
        camera = pv.Camera()
        vtk_convert.apply_camera(camera, cam)
        self.renderer.SetActiveCamera(camera)
        self.rgba = vtk.vtkUnsignedCharArray()
        self.depth = vtk.vtkFloatArray()

    @property
    def window_class(self) -> str:
        """The render window class VTK chose (``vtkEGLRenderWindow``, ``vtkXOpenGLRenderWindow``...)."""
        return self.window.GetClassName()

    def __call__(self):
        """One frame: render once, then read colour and depth straight from the window."""
        w, h = self.width, self.height
        self.window.Render()
        self.window.GetRGBACharPixelData(0, 0, w - 1, h - 1, 0, self.rgba)
        self.window.GetZbufferData(0, 0, w - 1, h - 1, self.depth)
        return self.rgba, self.depth

    def close(self) -> None:
        self.window.Finalize()


def _figure(times: list[float]) -> str:
    """Median with the lowest and highest run, in ms."""
    import numpy as np

    ms = np.array(times) * 1e3
    return f"{np.median(ms):8.1f} ms [{ms.min():.1f} .. {ms.max():.1f}]"


def run(args) -> int:
    """Run the benchmark and print its figures; returns the exit status."""
    sizes = parse_sizes(args.triangles)
    for name, value, low in (("--runs", args.runs, 1), ("--warmup", args.warmup, 0),
                             ("--width", args.width, 16), ("--height", args.height, 16)):
        if value < low:
            raise UsageError(f"{name} must be at least {low}, got {value}")
    if not os.environ.get("DISPLAY"):  # before VTK loads: render off screen through EGL
        os.environ.setdefault("VTK_DEFAULT_OPENGL_WINDOW", "vtkEGLRenderWindow")
    import numba
    import numpy as np

    from core.object_order.kernels import raster as kernels
    from core.object_order.pipeline import RasterSettings, render_raster

    print(f"bench raster: bumpy sphere at {args.width}x{args.height}, {numba.get_num_threads()} numba "
          f"threads; median of {args.runs} interleaved frames after {args.warmup} warm-up "
          f"[lowest .. highest]")
    if not args.skip_cold_compile:
        print(f"numba kernels, cold compile (empty cache, subprocess): {_cold_compile_seconds():.2f} s")
    t = time.perf_counter()
    render_raster(bench_scene(200, 32, 24), RasterSettings(record_steps=True)).history.buffers(1)
    first = time.perf_counter() - t
    cached = sum(kernels.draw_triangles.stats.cache_hits.values()) > 0
    print(f"numba kernels, first call in this process ({'loaded from cache' if cached else 'compiled'}): "
          f"{first:.2f} s")

    plain, recording = RasterSettings(), RasterSettings(record_steps=True)
    rows = []
    for n in sizes:
        scene = bench_scene(n, args.width, args.height)
        crossing = bench_scene(n, args.width, args.height, crossing=True)
        vtk_frame = VtkFrame(scene)
        frames = {"ours": lambda s=scene: render_raster(s, plain), "vtk": vtk_frame,
                  "recording": lambda s=scene: render_raster(s, recording),
                  "clipped": lambda s=crossing: render_raster(s, plain)}
        times: dict[str, list[float]] = {name: [] for name in frames}
        for i in range(args.warmup + args.runs):
            for name, frame in frames.items():
                t = time.perf_counter()
                frame()
                if i >= args.warmup:
                    times[name].append(time.perf_counter() - t)
        window_class = vtk_frame.window_class
        vtk_frame.close()
        cut = render_raster(crossing, plain).stats
        recorded = render_raster(scene, recording)
        rec, history = recorded.stats, recorded.history
        med = {name: float(np.median(ts)) for name, ts in times.items()}
        triangles = len(scene.objects[0].triangles)
        print(f"\n{triangles:,} triangles ({rec['fragments_generated']:,} fragments):")
        print(f"  ours, plain frame:                    {_figure(times['ours'])}")
        print(f"  VTK frame ({window_class}): {_figure(times['vtk'])}")
        per_fragment = max(len(history.fragments), 1)
        print(f"  ours, recording steps:                {_figure(times['recording'])}  "
              f"({history.fragments.nbytes / per_fragment:.1f} bytes per fragment; "
              f"{history.nbytes / per_fragment:.1f} with the polygons' colours and origins)")
        print(f"  ours, near + 2 side planes cut it:    {_figure(times['clipped'])}  "
              f"({cut['polygons_clipped']:,} polygons clipped, {cut['fragments_generated']:,} fragments)")
        rows.append((triangles, med))

    print("\ntime against size (medians, ms; ratios ours / VTK, clipped / inside):")
    print(f"  {'triangles':>10} {'ours':>8} {'VTK':>8} {'ratio':>6} {'record':>8} {'ratio':>6} "
          f"{'clipped':>8} {'ratio':>6}")
    for triangles, med in rows:
        o, v, r, c = (med[k] * 1e3 for k in ("ours", "vtk", "recording", "clipped"))
        print(f"  {triangles:>10,} {o:8.1f} {v:8.1f} {o / v:6.2f} {r:8.1f} {r / v:6.2f} {c:8.1f} "
              f"{c / o:6.2f}")
    print("goals: plain <= 1.0 x VTK, recording <= 1.5 x VTK, clipped <= 1.5 x inside: "
          + "; ".join(f"{t:,}: " + "/".join("met" if ok else "missed" for ok in (
              m["ours"] <= m["vtk"], m["recording"] <= 1.5 * m["vtk"], m["clipped"] <= 1.5 * m["ours"]))
              for t, m in rows))
    if not args.skip_step_budget:
        _step_budget(args, render_raster, RasterSettings, np)
    return 0


def _step_budget(args, render_raster, RasterSettings, np) -> None:
    """The step-history budget at 1,000,000 triangles and 1920 x 1080: memory and rebuild time."""
    scene = bench_scene(1_000_000, 1920, 1080)
    history = render_raster(scene, RasterSettings(record_steps=True)).history
    history.buffers(history.n_steps)  # warm-up
    rng = np.random.default_rng(0)
    steps = list(rng.integers(0, history.n_steps + 1, size=max(args.runs, 5))) + [history.n_steps]
    rebuild = []
    for k in steps:
        t = time.perf_counter()
        history.buffers(int(k))
        rebuild.append(time.perf_counter() - t)
    fragments = max(len(history.fragments), 1)
    print(f"\nstep history, {len(scene.objects[0].triangles):,} triangles at 1920x1080: "
          f"{len(history.fragments):,} fragments in {history.fragments.nbytes / 1e6:.1f} MB "
          f"({history.fragments.nbytes / fragments:.1f} bytes per fragment, goal <= 16; with the "
          f"{history.n_steps:,} polygons' colours and origins {history.nbytes / fragments:.1f}); "
          f"rebuilding a step (random ones and the last): {_figure(rebuild).strip()} (goal <= 50 ms)")
