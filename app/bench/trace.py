"""``python -m app bench trace``: how fast the compiled tracer is, next to Embree.

Three figures, each the median of several runs after a warm-up run:

1. primary-ray throughput of our BVH on a bumpy ball of about 10,000,
   100,000 and 1,000,000 triangles (``--triangles``) filling most of a
   640 x 480 view (closest hit with ``t`` and barycentrics per ray; four-wide
   tree, four boxes and four triangles per vector instruction, see
   :mod:`core.image_order.bvh`; rays of 4 x 4 pixels walk the tree together
   where a packet covers less than a typical triangle, see
   :mod:`core.image_order.kernels.bvh_packet`), so that a reader sees how the
   cost grows with the mesh;
2. the same rays with Intel Embree through the ``embreex`` package (an
   optional extra: ``pip install -e '.[bench]'``), on its fastest path from
   Python: ``run()`` traces a whole array of rays in one call, but on the
   calling thread only, so the rays are split over one Python thread per
   core, each thread making one call; Embree works in float32, we in float64;
3. a full Whitted render (all rays counted) of the lecture scene and of the
   mirror-and-glass scene at 640 x 480 with depth 5.

Compiling the kernels (or loading them from numba's cache) is timed
separately and never counted in a figure.  Every figure is the median of
interleaved runs after a warm-up run, printed with the lowest and highest.
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
    parser.add_argument("--triangles", type=_sizes, default=(10_000, 100_000, 1_000_000),
                        help="approximate triangle counts of the benchmark meshes, comma separated "
                             "(default 10000,100000,1000000)")
    parser.add_argument("--repeats", type=int, default=7, help="timed runs per figure (default 7)")
    parser.add_argument("--threads", type=int, default=os.cpu_count() or 1,
                        help="Python threads for Embree (default: one per core)")


def _sizes(text: str) -> tuple[int, ...]:
    """``"10000,100000"`` as ``(10000, 100000)``; a clear message for anything else."""
    try:
        sizes = tuple(int(part) for part in text.split(","))
    except ValueError:
        sizes = ()
    if not sizes or min(sizes) < 1:
        raise argparse.ArgumentTypeError(f"expected positive whole numbers separated by commas, got {text!r}")
    return sizes


def _spread(times: list) -> str:
    """``"median ms (lowest-highest)"`` of run times in seconds."""
    return (f"{statistics.median(times) * 1e3:7.1f} ms ({min(times) * 1e3:.1f}-"
            f"{max(times) * 1e3:.1f})")


def run(args) -> int:
    """Run the benchmark and print the figures; returns the exit status."""
    from dataclasses import replace

    import numba

    from core import presets, presets_trace
    from core.image_order.flat_scene import TraceSettings
    from core.image_order.ray_tracing import ensure_compiled, render_trace

    size = (args.width, args.height)
    print(f"bench trace: {args.width} x {args.height} = {args.width * args.height} rays per frame, "
          f"{numba.get_num_threads()} numba threads, median of {args.repeats} runs after a warm-up "
          "(lowest-highest in brackets)")
    compile_s = ensure_compiled()
    print(f"compile (or load from cache) the kernels: {compile_s:.2f} s (not counted below)")

    # 1. and 2. Our BVH and Embree on meshes of growing size.
    rows = [_primary_rays(triangles, args) for triangles in args.triangles]
    if len(rows) > 1:
        print("primary rays against mesh size (median ms; ratio ours / Embree as above):")
        for n, ours_ms, embree_ms, ratio in rows:
            other = "" if embree_ms is None else f"  Embree {embree_ms:7.1f}  ratio {ratio:.2f}"
            print(f"  {n:>9,} triangles: ours {ours_ms:7.1f}{other}")

    # 3. Whitted frames, all rays counted, the two scenes in turns.
    frames, stats = {}, {}
    for title, build in (("lecture scene", presets.lecture_scene),
                         ("mirror and glass", presets_trace.mirror_and_glass)):
        frame = build()
        frame = replace(frame, camera=frame.camera.replace(width=size[0], height=size[1]))
        whitted = TraceSettings(mode="raytrace", max_depth=5, accel="bvh")
        stats[title] = []

        def whitted_frame(frame=frame, whitted=whitted, out=stats[title]):
            out.append(render_trace(frame, whitted).stats)

        frames[title] = whitted_frame
    runs = _interleaved_runs(frames, args.repeats)
    for title, goal in (("lecture scene", 50), ("mirror and glass", 80)):
        frame_s = statistics.median(runs[title])
        rays = stats[title][-1]["rays"]
        stages = ", ".join(f"{stage} {statistics.median(s['times'][stage] for s in stats[title]) * 1e3:.1f}"
                           for stage in _STAGES)
        print(f"Whitted frame, {title}, depth 5: {_spread(runs[title])} (goal <= {goal} ms); "
              f"{rays['total']} rays = {rays['primary']} primary + {rays['shadow']} shadow + "
              f"{rays['reflection']} reflection + {rays['refraction']} refraction "
              f"({rays['total'] / frame_s / 1e6:.1f} Mrays/s); median ms per stage: {stages}")
    return 0


_STAGES = ("primary", "shading", "secondary")


def _primary_rays(triangles: int, args) -> tuple:
    """Time the primary rays on a mesh of about ``triangles`` triangles, ours and Embree's, in turns.

    Prints the figures; returns ``(triangle count, our median ms, Embree's median ms, the median
    ratio of side-by-side runs)``, the last two ``None`` without embreex.
    """
    import numba
    import numpy as np

    from core import presets_trace
    from core.image_order.effects_plan import effects_plan
    from core.image_order.flat_layout import (
        BOUNDS_TESTS,
        CHILD_SIZE,
        HIT_PRIM,
        HIT_SIZE,
        OPT_PACKETS,
        PRIM_TESTS,
    )
    from core.image_order.flat_scene import TraceSettings, kernel_inputs, trace_scene
    from core.image_order.kernels import render
    from core.scene import PointLight, Scene

    n_rays = args.width * args.height
    mesh = presets_trace.bumpy_ball(triangles)
    scene = Scene(camera=presets_trace.BIG_MESH_CAMERA.replace(width=args.width, height=args.height),
                  objects=(mesh,), lights=(PointLight((4.0, 8.0, 6.0)),))
    flat = trace_scene(scene)
    bvh, build_s, _ = flat.geometry.accel("bvh")
    k = kernel_inputs(scene, TraceSettings(accel="bvh"), effects_plan(scene), flat, bvh)
    xs = np.arange(float(args.width))
    ys = np.arange(float(args.height))
    shape = (args.height, args.width)
    hits, depth, objects = np.zeros((*shape, HIT_SIZE)), np.zeros(shape), np.zeros(shape, np.int64)
    color, children = np.zeros((*shape, 3)), np.zeros((*shape, 2, CHILD_SIZE))
    spawned = np.zeros(shape, np.uint8)
    counters = []

    def ours():
        counters[:] = [render.render_pass(render.PRIMARY_STAGE, k.cam, xs, ys, hits, depth, objects,
                                          color, children, spawned, k.materials, k.lights, k.opts, k.geo,
                                          k.grid, k.bvh, k.bvh_depth, numba.get_num_threads(),
                                          render.no_heat())]

    # The same rays into an empty scene: what our figure spends before and after the scene itself.
    empty = Scene(camera=scene.camera, objects=(), lights=scene.lights)
    flat_empty = trace_scene(empty)
    e = kernel_inputs(empty, TraceSettings(accel="bvh"), effects_plan(empty), flat_empty,
                      flat_empty.geometry.accel("bvh")[0])
    hits_empty, depth_empty = np.zeros_like(hits), np.zeros_like(depth)  # ours' hits stay for the comparison

    def nothing_to_hit():
        render.render_pass(render.PRIMARY_STAGE, e.cam, xs, ys, hits_empty, depth_empty, objects, color,
                           children, spawned, e.materials, e.lights, e.opts, e.geo, e.grid, e.bvh,
                           e.bvh_depth, numba.get_num_threads(), render.no_heat())

    print(f"mesh: {len(mesh.triangles):,} triangles; BVH build {build_s:.3f} s, {len(bvh.nodes)} nodes, "
          f"depth {bvh.depth}")
    embree = _embree(mesh, scene, args.threads)
    runners = {"ours": ours, "nothing to hit": nothing_to_hit}
    if embree is not None:
        runners["embree"] = embree[0]
    runs = _interleaved_runs(runners, args.repeats)
    seconds = {name: statistics.median(times) for name, times in runs.items()}
    per_ray = counters[0] / n_rays
    prims = hits[..., HIT_PRIM].reshape(-1)
    walk = "packets of 4 x 4 rays" if k.opts[OPT_PACKETS] else "one ray at a time"
    print(f"  ours   (numba 4-wide BVH, float64, {walk}): {_spread(runs['ours'])}  "
          f"{n_rays / seconds['ours'] / 1e6:6.2f} Mrays/s  ({(prims >= 0).mean():.0%} of rays hit; per ray "
          f"{per_ray[BOUNDS_TESTS]:.1f} box and {per_ray[PRIM_TESTS]:.1f} triangle tests)")
    print(f"         the same rays, nothing to hit: {_spread(runs['nothing to hit'])}  (making the rays and "
          "writing their hits and depths; Embree's rays are made before its clock starts)")
    if embree is None:
        return len(mesh.triangles), seconds["ours"] * 1e3, None, None
    agree = np.mean(embree[1]() == prims)
    print(f"  Embree (embreex, float32, {args.threads} threads): {_spread(runs['embree'])}  "
          f"{n_rays / seconds['embree'] / 1e6:6.2f} Mrays/s  (same triangle as ours for {agree:.2%} of rays)")
    # Each of our runs against the Embree run right after it: a load change on this shared
    # machine slows both alike, so the pairs' ratios scatter less than the times do.
    pairs = sorted(e / o for o, e in zip(runs["ours"], runs["embree"], strict=True))
    print(f"  ratio ours / Embree: {statistics.median(pairs):.2f} (goal: >= 1.0; median of {len(pairs)} "
          f"runs side by side, lowest {pairs[0]:.2f}, highest {pairs[-1]:.2f})")
    return len(mesh.triangles), seconds["ours"] * 1e3, seconds["embree"] * 1e3, statistics.median(pairs)


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
