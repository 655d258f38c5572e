"""``python -m app bench trace``: how fast the compiled tracer is, next to Embree.

Figures, each the median of several runs after a warm-up run:

1. primary-ray throughput of our BVH on a bumpy ball of about 10,000,
   100,000 and 1,000,000 triangles (``--triangles``) filling most of a
   640 x 480 view (closest hit with ``t`` and barycentrics per ray; four-wide
   tree, four boxes and four triangles per vector instruction, see
   :mod:`core.image_order.bvh`; rays of 4 x 4 pixels walk the tree together
   where a packet covers less than a typical triangle, see
   :mod:`core.image_order.kernels.bvh_packet`), so that a reader sees how the
   cost grows with the mesh; and on the lecture scene (its cube, cone and
   ground, 110 triangles, from its camera at the same size, with its light),
   where the rays are many and each does little: there what a packet costs to
   set up shows;
2. the same rays with Intel Embree, twice (an optional extra:
   ``pip install -e '.[bench]'`` installs the ``embreex`` wheel, which holds
   Embree's library): through Embree's own packet API, ``rtcIntersect16``
   called from compiled code on the same numba threads as ours, 16 rays of
   4 x 4 pixels per packet (:mod:`app.bench.embree_packets`), the peer the
   goal is set against, its runs and ours back to back; and, for reference,
   through embreex's ``run()``, which traces a whole array of rays in one call
   but on the calling thread only, so the rays are split over one Python thread
   per core, in turns with ours after a pause of 0.2 s that lets those threads
   sleep.  Embree works in float32, we in float64;
3. the shadow rays of those hits: from every hit on the lit side of its
   triangle towards the light, any hit, ours in packets of 16 consecutive
   rays where they share a walk, each finding the blocker it finds alone
   (:mod:`core.image_order.kernels.shadow_rays`), Embree's with
   ``rtcOccluded16`` -- both the very same rays, rounded to float32, and
   the runs back to back, as shading traces them (both run on numba's threads).
   The rays are listed with their pixels row by row, or with
   ``--shadow-order tiles`` in tiles of 4 x 4, as the primary rays' packets
   take them: both tracers' packets then hold neighbouring pixels in both
   directions, and go through fewer nodes of the tree together;
4. a full Whitted render (all rays counted) of the lecture scene and of the
   mirror-and-glass scene at 640 x 480 with depth 5, the two in turns, frame
   after frame with no pause, as at 60 frames a second.

Every ray of 1. to 3. is checked: Embree's packets must find the same
triangle as ours (or be blocked where ours is), but for ties that float32
cannot tell apart (:func:`hit_agreement`); the bench prints the counts and
exits with status 1 when any ray disagrees.  Without embreex it says so in one
line and times ours alone.

Compiling the kernels (or loading them from numba's cache) is timed
separately and never counted in a figure.  Every figure is the median of
interleaved runs after a warm-up run, printed with the lowest and highest.

On a machine shared with other work the wall clock mostly measures the
others' load (one run's figures scatter by 30-300%).  ``--cpu-time`` times
the CPU time of the calling thread instead, with one numba thread (numba's
OpenMP and TBB layers run a one-thread kernel on the calling thread; with its
own work queue the process's CPU time is taken): the time spent waiting for
a core is left out, so two versions of the code can be set side by side (on
such a machine the medians of two runs then agree within 1-3%).  Embree
through embreex, which runs on Python threads of its own, is left out then;
its packet API runs on our one thread, as ours does.  By the wall clock each
Whitted frame also gets its CPU time, all threads, and how many times one of
its threads had to give its core to another process: the frame took its CPU
time per thread if no thread ever waited, and on a busy machine the gap is
that wait.
"""

from __future__ import annotations

import argparse
import os
import resource
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
    parser.add_argument("--shadow-order", choices=("rows", "tiles"), default="rows",
                        help="the order of the shadow rays, the same for both tracers, whose packets take "
                             "16 consecutive rays: their pixels row by row (default), or in tiles of 4 x 4 "
                             "as the primary rays' packets take them")
    parser.add_argument("--cpu-time", action="store_true",
                        help="time the CPU time of one numba thread instead of the wall clock, so that "
                             "waiting for a core on a shared machine is not counted (embreex is left out)")


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
    """Run the benchmark and print the figures; returns the exit status (1: Embree and ours found
    different hits)."""
    from app.usage import UsageError

    for name, value, low in (("--repeats", args.repeats, 1), ("--threads", args.threads, 1),
                             ("--width", args.width, 16), ("--height", args.height, 16)):
        if value < low:
            raise UsageError(f"{name} must be at least {low}, got {value}")
    from dataclasses import replace

    import numba

    from core import presets, presets_trace
    from core.image_order.flat_scene import TraceSettings
    from core.image_order.ray_tracing import ensure_compiled, render_trace
    from core.in_words import counted

    size = (args.width, args.height)
    if args.cpu_time:
        numba.set_num_threads(1)
    compile_s = ensure_compiled()  # runs the kernels once, so numba's threading layer is known below
    args.clock = _clock(args.cpu_time, numba.threading_layer())
    clock = {time.perf_counter: "wall clock,", time.thread_time: "CPU time of the calling thread,",
             time.process_time: "CPU time of the process,"}[args.clock]
    print(f"bench trace: {args.width} x {args.height} = {args.width * args.height} rays per frame, "
          f"{clock} {counted(numba.get_num_threads(), 'numba thread')}, median of "
          f"{counted(args.repeats, 'run')} after a warm-up (lowest-highest in brackets)")
    print(f"compile (or load from cache) the kernels: {compile_s:.2f} s (not counted below)")

    # 1. and 2. Our BVH and Embree's on meshes of growing size.
    from app.bench.embree_packets import find_library

    library = find_library()
    if library is None:
        print("Embree: not measured, the embreex package (whose wheel holds Embree's library) is missing; "
              "install it with `.venv/bin/pip install -e '.[bench]'`")
    size_camera = presets_trace.BIG_MESH_CAMERA.replace(width=args.width, height=args.height)
    rows = []
    for asked in args.triangles:
        mesh = presets_trace.bumpy_ball(asked)
        rows.append(_scene_rays(f"{len(mesh.triangles):>9,} triangles", mesh, size_camera, _MESH_LIGHT, args,
                                library, _GOALS.get(asked, ())))
    lecture = presets.lecture_scene()
    lecture_mesh = _one_mesh(lecture)
    rows.append(_scene_rays(f"lecture scene ({len(lecture_mesh.triangles)} triangles)", lecture_mesh,
                            lecture.camera.replace(width=args.width, height=args.height),
                            lecture.lights[0].position, args, library, _GOALS["lecture scene"]))
    print("against mesh size, and the lecture scene (median ms; ratio: the peer's time over ours, paired "
          "runs, as above):")
    for row in rows:
        for kind in ("primary", "shadow"):
            figures = row[kind]
            goal = ", goal >= 1.0" if kind in row["goals"] else ""  # set against Embree's packets only
            peers = "".join(f"  {_PEER_NAMES[peer]} {figures[peer]:7.1f} "
                            f"(ratio {figures[f'ratio {peer}']:.2f}{goal if peer == 'packets' else ''})"
                            for peer in ("embreex", "packets") if peer in figures)
            print(f"  {row['label']}, {kind:>7} rays: ours {figures['ours']:7.1f}{peers}")
    disagree = sum(row["disagree"] for row in rows)

    # 3. Whitted frames, all rays counted, the two scenes in turns.
    frames, stats = {}, {}
    for title, build in (("lecture scene", presets.lecture_scene),
                         ("mirror and glass", presets_trace.mirror_and_glass)):
        frame = build()
        frame = replace(frame, camera=frame.camera.replace(width=size[0], height=size[1]))
        whitted = TraceSettings(mode="raytrace", max_depth=5, accel="bvh")
        stats[title] = []

        def whitted_frame(frame=frame, whitted=whitted, out=stats[title]):
            cpu, preempted = time.process_time(), _preempted()
            frame_stats = render_trace(frame, whitted).stats
            out.append({**frame_stats, "cpu": time.process_time() - cpu,
                        "preempted": _preempted() - preempted})

        frames[title] = whitted_frame
    # Back to back, as frames at 60 a second come.  After the meshes' pause of 0.2 s each frame began
    # with numba's threads asleep (``python -m app`` lets waiting threads sleep at once): the lecture
    # and mirror and glass took 22-26 and 37-47 ms, their threads losing their cores 12-24 times a
    # frame, against 13.5-14.1 and 22.0-22.7 ms and 0-1 times back to back (interleaved runs).
    runs = _interleaved_runs(frames, args.repeats, args.clock, pause=0.0)
    for title, goal in (("lecture scene", 16), ("mirror and glass", 25)):  # issue 36's goals
        frame_s = statistics.median(runs[title])
        rays = stats[title][-1]["rays"]
        stages = ", ".join(f"{stage} {statistics.median(s['times'][stage] for s in stats[title]) * 1e3:.1f}"
                           for stage in _STAGES)
        print(f"Whitted frame, {title}, depth 5: {_spread(runs[title])} (goal <= {goal} ms); "
              f"{rays['total']} rays = {rays['primary']} primary + {rays['shadow']} shadow + "
              f"{rays['reflection']} reflection + {rays['refraction']} refraction "
              f"({rays['total'] / frame_s / 1e6:.1f} Mrays/s); median ms per stage (wall clock): {stages}")
        cpu_ms = statistics.median(s["cpu"] for s in stats[title]) * 1e3
        preempted = statistics.median(s["preempted"] for s in stats[title])
        print(f"  its CPU time {cpu_ms:.1f} ms over {numba.get_num_threads()} threads "
              f"({cpu_ms / numba.get_num_threads():.1f} each), {preempted:.0f} times a thread had to leave "
              "its core to another process (medians per frame): a frame longer than its CPU time per "
              "thread waited, on a busy machine for a core")
    if disagree:
        print(f"bench trace: Embree and ours found different hits for {disagree:,} rays (see above)")
        return 1
    return 0


_STAGES = ("primary", "shading", "secondary")


#: The light of the bench's meshes.
_MESH_LIGHT = (4.0, 8.0, 6.0)


def _one_mesh(scene):
    """``scene``'s objects as one mesh, as the rasterizer joins them (its spheres tessellated: the
    lecture scene has none), for the peer, which takes one triangle geometry."""
    from core.object_order.pipeline import joined_triangles, object_mesh
    from core.scene import Mesh

    return Mesh(*joined_triangles(tuple(object_mesh(obj) for obj in scene.objects)))


def _scene_rays(label: str, mesh, camera, light, args, library, goals: tuple = ()) -> dict:
    """Time the primary and the shadow rays of ``camera`` and ``light`` on ``mesh``, ours and the
    peers', in turns, and check that the peers find the same hits.

    ``library``: Embree's library (:func:`app.bench.embree_packets.find_library`), ``None`` to
    time ours alone.  ``goals``: the ray kinds (``"primary"``, ``"shadow"``) whose ratio to
    Embree's packets has a goal here (:data:`_GOALS`).  Prints the figures; returns a summary row:
    ``label`` and the triangle count, per ray kind (``"primary"``, ``"shadow"``) the median ms of
    each tracer and the median ratios of side-by-side runs, and ``"disagree"``, the rays where a
    peer found another hit.
    """
    import numba
    import numpy as np

    from core.image_order.effects_plan import effects_plan
    from core.image_order.flat_layout import (
        BOUNDS_TESTS,
        CHILD_SIZE,
        GEO_N_SPHERES,
        HIT_PRIM,
        HIT_SIZE,
        HIT_T,
        OPT_PACKETS,
        PRIM_TESTS,
    )
    from core.image_order.flat_scene import TraceSettings, kernel_inputs, trace_scene
    from core.image_order.kernels import render
    from core.image_order.kernels.shadow_rays import trace_shadow_rays
    from core.scene import PointLight, Scene

    n_rays = args.width * args.height
    scene = Scene(camera=camera, objects=(mesh,), lights=(PointLight(light),))
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
    # Its rays are made as ours are, in packets where ours go in packets (an empty tree alone would
    # send them one by one, another loop).
    e.opts[OPT_PACKETS] = k.opts[OPT_PACKETS]
    hits_empty, depth_empty = np.zeros_like(hits), np.zeros_like(depth)  # ours' hits stay for the comparison

    def nothing_to_hit():
        render.render_pass(render.PRIMARY_STAGE, e.cam, xs, ys, hits_empty, depth_empty, objects, color,
                           children, spawned, e.materials, e.lights, e.opts, e.geo, e.grid, e.bvh,
                           e.bvh_depth, numba.get_num_threads(), render.no_heat())

    print(f"{label.strip()}: BVH build {build_s:.3f} s, {len(bvh.nodes)} nodes, "
          f"depth {bvh.depth}")
    o, d, t_min, t_max = _primary_rays(scene.camera)
    runners = {"ours": ours, "nothing to hit": nothing_to_hit}
    beside_embreex = {}
    packets = None
    if library is not None:
        from app.bench.embree_packets import EmbreePackets

        if not args.cpu_time:  # its Python threads' time is not this thread's
            beside_embreex["embreex"], embreex_prims = _embreex(mesh, scene, args.threads)
        packets = EmbreePackets(library, mesh.corners, numba.get_num_threads())
        order = _tile_order(args.height, args.width)
        runners["packets"], peer = packets.tracer(o[order], d[order], t_min[order], t_max[order], False)
        print(f"  Embree's own BVH build (rtcCommitScene) {packets.build_seconds:.3f} s; first call of the "
              f"kernel that calls rtcIntersect16 / rtcOccluded16 (compiles it, once per run) "
              f"{packets.compile_seconds:.2f} s (not counted below)")
    # Back to back, as the shadow rays below: ours and Embree's packets both run on numba's threads.
    # After a pause of 0.2 s before each run the second thread often woke late, and on the lecture
    # scene (5 ms a run) ours took 5.2-12.9 ms and Embree's 5.5-13.1 in one bench run (ratio 0.87,
    # lowest 0.67, highest 2.50), against 4.9-9.3 and 5.3-8.5 back to back (ratio 1.07).
    runs = _interleaved_runs(runners, args.repeats, args.clock, pause=0.0)
    if beside_embreex:
        # embreex's Python threads spin a while after each call, so it takes turns with ours after a
        # pause that lets them sleep; its figure and ratio come from those turns.
        beside_embreex["ours"] = ours
        beside = _interleaved_runs(beside_embreex, args.repeats, args.clock)
        runs["embreex"] = beside["embreex"]
    seconds = {name: statistics.median(times) for name, times in runs.items()}
    per_ray = counters[0] / n_rays
    prims, ts = hits[..., HIT_PRIM].reshape(-1).astype(np.int64), hits[..., HIT_T].reshape(-1)
    walk = "packets of 4 x 4 rays" if k.opts[OPT_PACKETS] else "one ray at a time"
    print(f"  primary rays, ours (numba 4-wide BVH, float64, {walk}): {_spread(runs['ours'])}  "
          f"{n_rays / seconds['ours'] / 1e6:6.2f} Mrays/s  ({(prims >= 0).mean():.0%} of rays hit; per ray "
          f"{per_ray[BOUNDS_TESTS]:.1f} box and {per_ray[PRIM_TESTS]:.1f} triangle tests)")
    print(f"         the same rays, nothing to hit: {_spread(runs['nothing to hit'])}  (making the rays and "
          "writing their hits and depths; the peers' rays are made before their clocks start)")
    row = {"label": label, "disagree": 0, "goals": goals,
           "primary": {"ours": seconds["ours"] * 1e3}, "shadow": {}}
    if packets is not None:
        if "embreex" in runs:
            same = np.mean(embreex_prims() == prims)
            print(f"  primary rays, Embree (embreex, float32, {args.threads} Python threads): "
                  f"{_spread(runs['embreex'])}  {n_rays / seconds['embreex'] / 1e6:6.2f} Mrays/s  "
                  f"(same triangle as ours for {same:.2%} of rays; in turns with ours after a pause of "
                  f"0.2 s each, ours {statistics.median(beside['ours']) * 1e3:.1f} ms)")
        print(f"  primary rays, Embree (rtcIntersect16 packets, float32, {numba.get_num_threads()} numba "
              f"threads): {_spread(runs['packets'])}  {n_rays / seconds['packets'] / 1e6:6.2f} Mrays/s")
        peer_prims, peer_t = np.empty_like(peer[0]), np.empty_like(peer[1])
        peer_prims[order], peer_t[order] = peer[0], peer[1]
        row["disagree"] += _report_agreement("primary", mesh.corners, o, d, prims, ts, peer_prims, peer_t)
        if beside_embreex:
            row["primary"].update(_ratios(beside, seconds, "embreex", False))
        row["primary"].update(_ratios(runs, seconds, "packets", "primary" in goals))

    # Shadow rays: from every lit hit of ours towards the light, the same rays for both tracers.
    pixels = _tile_order(args.height, args.width) if args.shadow_order == "tiles" else None
    so, sd, s_min, s_max = _shadow_rays(mesh, scene.lights[0].position, o, d, prims, ts, pixels)
    n_shadow = len(so)
    blockers, blocker_t = np.full(n_shadow, -1, np.int64), np.full(n_shadow, np.inf)  # none, until blocked
    shadow_counters = []

    def ours_shadow():
        shadow_counters[:] = [trace_shadow_rays(so, sd, s_min, s_max, k.bvh, k.geo[GEO_N_SPHERES],
                                                k.bvh_depth, numba.get_num_threads(), blockers, blocker_t)]

    start = time.perf_counter()
    ours_shadow()
    print(f"  shadow rays, our kernel's first call (compiles it, or loads it from the cache, once): "
          f"{time.perf_counter() - start:.2f} s (not counted below)")
    runners = {"ours": ours_shadow}
    if packets is not None:
        runners["packets"], occluded = packets.tracer(so, sd, s_min, s_max, True)
    # Back to back, as shading traces them within a frame: both tracers run on numba's threads, and
    # no other library's threads spin meanwhile.  After the pause of 0.2 s the primary rays take,
    # the second thread often woke on the first one's core and the two took turns on it for the
    # whole run: on the 100,000-triangle ball ours took 12-16.5 ms, Embree 10.4-15 (their CPU
    # time 22 and 17.6 ms), against 10.9-11.1 and 8.7-9.0 back to back.
    runs = _interleaved_runs(runners, args.repeats, args.clock, pause=0.0)
    seconds = {name: statistics.median(times) for name, times in runs.items()}
    per_ray = shadow_counters[0] / max(n_shadow, 1)
    listed = "row by row" if pixels is None else "in tiles of 4 x 4"
    print(f"  shadow rays ({n_shadow:,}: every lit hit towards the light, pixels {listed}), ours (any hit, "
          f"packets of 16 rays): {_spread(runs['ours'])}  {n_shadow / seconds['ours'] / 1e6:6.2f} Mrays/s  "
          f"({(blockers >= 0).mean():.0%} blocked; per ray {per_ray[BOUNDS_TESTS]:.1f} box and "
          f"{per_ray[PRIM_TESTS]:.1f} triangle tests)")
    row["shadow"]["ours"] = seconds["ours"] * 1e3
    if packets is not None:
        print(f"  shadow rays, Embree (rtcOccluded16 packets, float32): {_spread(runs['packets'])}  "
              f"{n_shadow / seconds['packets'] / 1e6:6.2f} Mrays/s")
        row["disagree"] += _report_shadow_agreement(packets, mesh.corners, so, sd, s_min, s_max, blockers,
                                                    blocker_t, occluded[0])
        row["shadow"].update(_ratios(runs, seconds, "packets", "shadow" in goals))
        packets.close()
    return row


def _ratios(runs: dict, seconds: dict, peer: str, goal: bool) -> dict:
    """The peer's median ms and the ratio ours / peer (the peer's time over ours: above 1.0 we are
    faster), printed, with the goal where one is set (``goal``, :data:`_GOALS`).

    Each of our runs is set against the peer's run in the same turn: a load change on this shared
    machine slows both alike, so the pairs' ratios scatter less than the times do.  One run's median
    above the goal does not meet it: the goal is met where the medians of several runs are.
    """
    pairs = sorted(p / o for o, p in zip(runs["ours"], runs[peer], strict=True))
    set_here = "goal: >= 1.0; " if goal else ""
    print(f"    ratio ours / {_PEER_NAMES[peer]}: {statistics.median(pairs):.2f} ({set_here}median of "
          f"{len(pairs)} runs side by side, lowest {pairs[0]:.2f}, highest {pairs[-1]:.2f})")
    return {peer: seconds[peer] * 1e3, f"ratio {peer}": statistics.median(pairs)}


#: Where issue 36 sets a goal of ours at least as fast as Embree's packets (``rtcIntersect16``,
#: ``rtcOccluded16``): the primary rays at 100,000 and 1,000,000 triangles, the shadow rays at
#: 100,000 and the lecture scene's.  The other figures show how the cost grows, with no goal.
_GOALS = {100_000: ("primary", "shadow"), 1_000_000: ("primary",), "lecture scene": ("shadow",)}


_PEER_NAMES = {"embreex": "embreex", "packets": "Embree packets"}


def _tile_order(height: int, width: int):
    """Pixel indices (row-major) in tiles of 4 x 4 pixels, the tiles row by row: the order in
    which the peer's packets of 16 take the primary rays, as our packets of 4 x 4 pixels do."""
    import numpy as np

    j, i = np.meshgrid(np.arange(height), np.arange(width), indexing="ij")
    tile = (j // 4) * ((width + 3) // 4) + i // 4
    return np.lexsort((((j % 4) * 4 + i % 4).ravel(), tile.ravel()))


def _primary_rays(camera):
    """The camera's primary rays, (N, 3) origins and directions and (N,) ``t_min, t_max`` (the near
    and the far plane), pixels row by row: the rays our kernels trace (perspective camera)."""
    import numpy as np

    origins, directions = camera.primary_rays()
    origins, directions = origins.reshape(-1, 3), directions.reshape(-1, 3)
    along = directions @ np.asarray(camera.forward, float)
    return origins, directions, camera.near / along, camera.far / along


def _shadow_rays(mesh, light, origins, directions, prims, ts, pixels=None):
    """Rays from every hit of ``prims, ts`` on the lit side of its triangle towards ``light``.

    ``origins, directions``: the primary rays, ``(N, 3)``, one a pixel; only hits on a triangle's
    front (seen from the camera) are kept, listed in the order of their pixels in ``pixels``
    (pixel indices, as :func:`_tile_order` gives them), row by row without.
    Each shadow ray starts at its hit point moved off the triangle towards the light by
    ``_FLOAT32_SLACK`` rounding steps of float32 (Embree works in float32, so our float64 offset
    would let it find the triangle the ray starts on), and ends at the light (``t_max``, the unit
    direction's length to it).  Returns ``(origins, directions, t_min, t_max)``, float32: both
    tracers read these very arrays, Embree's numbers as they are, ours each widened to float64
    (exactly), so that both trace exactly the same rays from the same bytes.
    """
    import numpy as np

    light = np.asarray(light, float)
    hit = prims >= 0
    p = origins[hit] + ts[hit, None] * directions[hit]
    normals = mesh.normals[prims[hit]]
    to_light = light - p
    lit = np.einsum("ij,ij->i", normals, to_light) > 0.0
    facing_camera = np.einsum("ij,ij->i", normals, directions[hit]) < 0.0
    kept = np.flatnonzero(lit & facing_camera)  # among the hits
    if pixels is not None:
        rank = np.empty_like(pixels)
        rank[pixels] = np.arange(len(pixels))
        kept = kept[np.argsort(rank[np.flatnonzero(hit)[kept]])]
    magnitude = np.abs(mesh.corners).max()
    start = p[kept] + _FLOAT32_SLACK * 2.0**-24 * magnitude * normals[kept]
    to_light = light - start
    distance = np.linalg.norm(to_light, axis=1)
    rounded = [np.ascontiguousarray(a, np.float32) for a in (start, to_light / distance[:, None], distance)]
    return rounded[0], rounded[1], np.zeros(len(distance), np.float32), rounded[2]


#: How many rounding steps of float32 (of the scene's largest coordinate) two tracers' hits may
#: differ by and still be the same: rounding the rays and the corners to float32 moves each by up
#: to one step, and Embree's float32 crossing test adds a few more; the rest is margin.
_FLOAT32_SLACK = 64


def hit_agreement(corners, origins, directions, prims_a, t_a, prims_b, t_b) -> tuple[int, int, int]:
    """How two tracers' hits of the same rays compare: ``(same, ties, differ)`` ray counts.

    ``same``: the same triangle (or both missed).  ``ties``: another triangle, or a hit against a
    miss, where the two cannot be told apart in float32: both hit at the same ``t``, or one of the
    hit points lies within ``_FLOAT32_SLACK`` float32 rounding steps (of the largest coordinate of
    ``corners``) of an edge of its triangle, where the two tracers' roundings may take the ray to
    either side.  ``differ``: the rest, a real disagreement.

    Parameters
    ----------
    corners : (M, 3, 3) float, the triangles' corners.
    origins, directions : (N, 3) float, the rays.
    prims_a, prims_b : (N,) int, the triangle each tracer found (-1: none).
    t_a, t_b : (N,) float, where along the ray (ignored where none was found).
    """
    import numpy as np

    prims_a, prims_b = np.asarray(prims_a).astype(np.int64), np.asarray(prims_b).astype(np.int64)
    same = prims_a == prims_b
    slack = _FLOAT32_SLACK * 2.0**-24 * np.abs(corners).max()
    other = ~same
    o, d = origins[other], directions[other]
    pa, pb, ta, tb = prims_a[other], prims_b[other], np.asarray(t_a)[other], np.asarray(t_b)[other]
    both = (pa >= 0) & (pb >= 0)
    tie = both & (np.abs(np.where(both, ta - tb, 0.0)) <= slack)
    for prims, t in ((pa, ta), (pb, tb)):
        found = prims >= 0
        near_edge = np.zeros(len(prims), bool)
        points = o[found] + t[found, None] * d[found]
        near_edge[found] = _edge_distance(corners[prims[found]], points) <= slack
        tie |= near_edge
    return int(same.sum()), int(tie.sum()), int((~tie).sum())


def _edge_distance(triangles, points):
    """(N,) distance of each point to the nearest of the three lines through its triangle's edges."""
    import numpy as np

    distances = []
    for a, b in ((0, 1), (1, 2), (2, 0)):
        edge = triangles[:, b] - triangles[:, a]
        arm = points - triangles[:, a]
        distances.append(np.linalg.norm(np.cross(arm, edge), axis=1) / np.linalg.norm(edge, axis=1))
    return np.min(distances, axis=0)


def _report_agreement(kind, corners, origins, directions, prims, ts, peer_prims, peer_ts,
                      same_means="the same triangle") -> int:
    """Print how the peer's hits compare with ours (:func:`hit_agreement`); return the disagreements."""
    same, ties, differ = hit_agreement(corners, origins, directions, prims, ts, peer_prims, peer_ts)
    print(f"    {kind} rays, Embree packets against ours: {same:,} {same_means}, {ties:,} ties within "
          f"float32 rounding, {differ:,} disagree" + (" -- DISAGREEMENT" if differ else ""))
    return differ


def _report_shadow_agreement(packets, corners, origins, directions, t_min, t_max, blockers, blocker_t,
                             occluded) -> int:
    """Compare blocked against blocked: any hit may name any blocker, so where only one tracer finds
    one, Embree's closest hit on those rays (``rtcIntersect16``) is set against our blocker."""
    import numpy as np

    ours_blocked, peer_blocked = blockers >= 0, occluded >= 0
    other = np.flatnonzero(ours_blocked != peer_blocked)
    prims_a, prims_b = np.where(ours_blocked, 0, -1), np.where(peer_blocked, 0, -1)
    ta, tb = blocker_t.copy(), np.full(len(blockers), np.inf)
    if len(other):
        trace, (peer_prims, peer_t, _, _) = packets.tracer(origins[other], directions[other], t_min[other],
                                                           t_max[other], False)
        trace()
        prims_a[other], prims_b[other] = blockers[other], peer_prims
        tb[other] = peer_t
    return _report_agreement("shadow", corners, origins, directions, prims_a, ta, prims_b, tb,
                             "the same answer (blocked or not)")


def _preempted() -> int:
    """How many times so far a thread of this process had to leave its core to another process
    before it was done (involuntary context switches, all threads)."""
    return resource.getrusage(resource.RUSAGE_SELF).ru_nivcsw


def _clock(cpu_time: bool, threading_layer: str):
    """The clock of the figures: the wall clock, or with ``cpu_time`` the calling thread's CPU time
    where numba runs a one-thread kernel on the calling thread, else the process's."""
    if not cpu_time:
        return time.perf_counter
    return time.thread_time if threading_layer in ("omp", "tbb") else time.process_time


def _interleaved_runs(runners: dict, repeats: int, clock=time.perf_counter, pause: float = 0.2) -> dict:
    """Seconds of each run of each runner by ``clock``, the runs taken in turns so that load changes
    hit all alike.

    A pause of ``pause`` seconds before each run lets the other library's idle
    worker threads (which spin for a while before they sleep) get out of the way.
    """
    for run_once in runners.values():
        run_once()  # warm-up
    times = {name: [] for name in runners}
    for _ in range(repeats):
        for name, run_once in runners.items():
            time.sleep(pause)
            start = clock()
            run_once()
            times[name].append(clock() - start)
    return times


def _embreex(mesh, scene, n_threads: int):
    """``(trace, primitive_ids)``: a function tracing the primary rays with embreex on
    ``n_threads`` Python threads, and one returning the triangle each ray hit (-1: none)."""
    import numpy as np
    from embreex import mesh_construction, rtcore_scene

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
