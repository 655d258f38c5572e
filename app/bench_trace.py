"""``python -m app bench trace``: how fast the compiled tracer is, next to Embree.

Three figures, each the median of several runs after a warm-up run:

1. primary-ray throughput of our BVH on a bumpy ball of about 100,000
   triangles filling most of a 640 x 480 view (closest hit with ``t`` and
   barycentrics per ray; four-wide tree, four boxes and four triangles per
   vector instruction, see :mod:`core.image_order.bvh`);
2. the same rays with Intel Embree through the ``embreex`` package (an
   optional extra: ``pip install -e '.[bench]'``).  ``run()`` of embreex
   traces on the calling thread only, so the rays are split over one Python
   thread per core; Embree works in float32, we in float64;
3. a full Whitted render (all rays counted) of the lecture scene and of the
   mirror-and-glass scene at 640 x 480 with depth 5.

Compiling the kernels (or loading them from numba's cache) is timed
separately and never counted in a figure.
"""

from __future__ import annotations

import argparse
import os
import statistics
import threading
import time


def add_arguments(parser: argparse.ArgumentParser) -> None:
    """Options of ``bench trace``."""
    parser.add_argument("--width", type=int, default=640, help="image width in pixels (default 640)")
    parser.add_argument("--height", type=int, default=480, help="image height in pixels (default 480)")
    parser.add_argument("--triangles", type=int, default=100_000,
                        help="approximate triangle count of the benchmark mesh (default 100000)")
    parser.add_argument("--repeats", type=int, default=7, help="timed runs per figure (default 7)")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1,
                        help="Python threads for Embree (default: one per core)")


def _median_time(func, repeats: int) -> float:
    func()  # warm-up
    times = []
    for _ in range(repeats):
        start = time.perf_counter()
        func()
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def run(args) -> int:
    """Run the benchmark and print the figures; returns the exit status."""
    from dataclasses import replace

    import numba
    import numpy as np

    from core import presets, presets_trace
    from core.image_order.effects_plan import effects_plan
    from core.image_order.flat_scene import TraceSettings, kernel_inputs, trace_scene
    from core.image_order.kernels import layout, render
    from core.image_order.kernels.layout import BOUNDS_TESTS, HIT_PRIM, HIT_SIZE, PRIM_TESTS
    from core.image_order.ray_tracing import ensure_compiled, render_trace
    from core.scene import PointLight, Scene

    size = (args.width, args.height)
    n_rays = args.width * args.height
    print(f"bench trace: {args.width} x {args.height} = {n_rays} rays per frame, "
          f"{numba.get_num_threads()} numba threads, median of {args.repeats} runs after a warm-up")
    compile_s = ensure_compiled()
    print(f"compile (or load from cache) the kernels: {compile_s:.2f} s (not counted below)")

    # 1. Our BVH on a mesh of about 100,000 triangles.
    mesh = presets_trace.bumpy_ball(args.triangles)
    scene = Scene(camera=presets_trace.BIG_MESH_CAMERA.replace(width=args.width, height=args.height),
                  objects=(mesh,), lights=(PointLight((4.0, 8.0, 6.0)),))
    settings = TraceSettings(accel="bvh")
    flat = trace_scene(scene)
    bvh, build_s, _ = flat.geometry.accel("bvh")
    k = kernel_inputs(scene, settings, effects_plan(scene), flat, bvh)
    xs = np.arange(float(args.width))
    ys = np.arange(float(args.height))
    shape = (args.height, args.width)
    hits, depth = np.zeros((*shape, HIT_SIZE)), np.zeros(shape)
    color, children = np.zeros((*shape, 3)), np.zeros((*shape, 2, layout.CHILD_SIZE))
    counters = []

    def ours():
        counters[:] = [render.render_pass(render.PRIMARY_STAGE, k.cam, xs, ys, hits, depth, color,
                                                children, k.materials, k.lights, k.opts, k.geo, k.grid, k.bvh,
                                                k.bvh_depth, numba.get_num_threads())]

    print(f"mesh: {len(mesh.triangles)} triangles; BVH build {build_s:.3f} s, {len(bvh.nodes)} nodes, "
          f"depth {bvh.depth}")
    embree = _embree(mesh, scene, args.threads)
    runners = {"ours": ours} if embree is None else {"ours": ours, "embree": embree[0]}
    runs = _interleaved_runs(runners, args.repeats)
    seconds = {name: statistics.median(times) for name, times in runs.items()}
    ours_rate = n_rays / seconds["ours"] / 1e6
    per_ray = counters[0] / n_rays
    prims = hits[..., HIT_PRIM].reshape(-1)
    print(f"ours   (numba 4-wide BVH, float64): {seconds['ours'] * 1e3:7.1f} ms  {ours_rate:6.2f} Mrays/s  "
          f"({(prims >= 0).mean():.0%} of rays hit; per ray {per_ray[BOUNDS_TESTS]:.1f} box and "
          f"{per_ray[PRIM_TESTS]:.1f} triangle tests)")

    # 2. The same rays with Embree.
    if embree is not None:
        rate = n_rays / seconds["embree"] / 1e6
        agree = np.mean(embree[1]() == prims)
        print(f"Embree (embreex, float32, {args.threads} threads): {seconds['embree'] * 1e3:7.1f} ms  "
              f"{rate:6.2f} Mrays/s  (same triangle as ours for {agree:.2%} of rays)")
        # Each of our runs against the Embree run right after it: a load change on this shared
        # machine slows both alike, so the pairs' ratios scatter less than the times do.
        pairs = sorted(e / o for o, e in zip(runs["ours"], runs["embree"], strict=True))
        print(f"ratio ours / Embree: {statistics.median(pairs):.2f} (goal: >= 0.5; median of {len(pairs)} "
              f"runs side by side, lowest {pairs[0]:.2f}, highest {pairs[-1]:.2f})")

    # 3. Whitted frames, all rays counted.
    for title, build in (("lecture scene", presets.lecture_scene),
                         ("mirror and glass", presets_trace.mirror_and_glass)):
        frame = build()
        frame = replace(frame, camera=frame.camera.replace(width=size[0], height=size[1]))
        whitted = TraceSettings(mode="raytrace", max_depth=5, accel="bvh")
        stats = {}

        def whitted_frame(frame=frame, whitted=whitted, stats=stats):
            stats.update(render_trace(frame, whitted).stats)

        frame_s = _median_time(whitted_frame, args.repeats)
        rays = stats["rays"]
        print(f"Whitted frame, {title}, depth 5: {frame_s * 1e3:7.1f} ms (goal < 250 ms); "
              f"{rays['total']} rays = {rays['primary']} primary + {rays['shadow']} shadow + "
              f"{rays['reflection']} reflection + {rays['refraction']} refraction "
              f"({rays['total'] / frame_s / 1e6:.1f} Mrays/s)")
    return 0


def _interleaved_runs(runners: dict, repeats: int) -> dict:
    """Seconds of each run of each runner, the runs taken in turns so that load changes hit all alike.

    A pause before each run lets the other library's idle worker threads (which
    spin for a while before they sleep) get out of the way.
    """
    for run_once in runners.values():
        run_once()  # warm-up
    times = {name: [] for name in runners}
    for _ in range(repeats):
        for name, run_once in runners.items():
            time.sleep(0.2)
            start = time.perf_counter()
            run_once()
            times[name].append(time.perf_counter() - start)
    return times


def _embree(mesh, scene, n_threads: int):
    """``(trace, primitive_ids)``: a function tracing the primary rays with Embree on
    ``n_threads`` threads, and one returning the triangle each ray hit (-1: none);
    ``None`` when embreex is missing."""
    import numpy as np

    try:
        from embreex import mesh_construction, rtcore_scene
    except ImportError:
        print("Embree: not measured, the embreex package is missing; install it with "
              "`.venv/bin/pip install embreex` (or `pip install -e '.[bench]'`)")
        return None
    origins, directions = scene.camera.primary_rays()
    origins = origins.reshape(-1, 3).astype(np.float32)
    directions = directions.reshape(-1, 3).astype(np.float32)
    embree_scene = rtcore_scene.EmbreeScene()
    mesh_construction.TriangleMesh(embree_scene, mesh.corners.astype(np.float32))
    parts = np.array_split(np.arange(len(origins)), n_threads)
    chunks = [(origins[p], directions[p]) for p in parts]
    out = [None] * n_threads

    def work(i):
        out[i] = embree_scene.run(*chunks[i], output=1)

    def trace():
        threads = [threading.Thread(target=work, args=(i,)) for i in range(n_threads)]
        for t in threads:
            t.start()
        for t in threads:
            t.join()

    return trace, lambda: np.concatenate([o["primID"] for o in out])
