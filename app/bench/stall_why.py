"""``bench gui --why``: what the GUI thread was doing in its longest stall.

A watcher thread looks every few milliseconds at the time of the bench's last
5 ms tick; once a tick is more than :data:`LOOK_AFTER_S` late, it takes the GUI
thread's Python stack (:func:`sys._current_frames`).  It needs the GIL for that,
so during a long call into C++ that keeps the GIL (VTK drawing) it takes the
stack as soon as that call returns.  On Linux each tick also reads the GUI
thread's scheduler counters, which split a stall into the thread's own work,
waiting for a core (other threads or programs were running) and waiting
otherwise (for the GIL, the X server).
"""

from __future__ import annotations

import os
import sys
import threading
import time
import traceback

LOOK_AFTER_S = 0.05
"""The stack is taken this long into a stall; shorter stalls have none."""

_SCHEDSTAT = "/proc/thread-self/schedstat"


class StallWhy:
    """Record, per tick of the GUI thread, its stack if the next tick is late, and its scheduler times."""

    def __init__(self):
        self.sched: list[tuple[float, float]] = []  # (cpu s, waiting for a core s) at each tick
        self._stacks: dict[int, list[str]] = {}  # tick -> the GUI thread's frames, innermost first
        self._tick, self._at = -1, time.perf_counter()
        self._gui = threading.get_ident()
        self._stop = threading.Event()
        self._watcher = threading.Thread(target=self._watch, name="stall watcher", daemon=True)
        self._watcher.start()

    def tick(self) -> None:
        """Call on the GUI thread at every tick."""
        self._tick, self._at = self._tick + 1, time.perf_counter()
        if os.path.exists(_SCHEDSTAT):
            with open(_SCHEDSTAT) as f:
                cpu_ns, wait_ns, _ = f.read().split()
            self.sched.append((int(cpu_ns) / 1e9, int(wait_ns) / 1e9))

    def stop(self) -> None:
        self._stop.set()
        self._watcher.join()

    def _watch(self) -> None:
        while not self._stop.wait(0.005):
            tick = self._tick
            if tick >= 0 and tick not in self._stacks and time.perf_counter() - self._at > LOOK_AFTER_S:
                frame = sys._current_frames().get(self._gui)
                if frame is not None and tick == self._tick:
                    self._stacks[tick] = [f"{_short(f.filename)}:{f.lineno} {f.name}"
                                          for f in reversed(traceback.extract_stack(frame))]

    def explain(self, i: int, gap_ms: float, outer: str) -> list[str]:
        """Lines telling what the stall between ticks ``i`` and ``i + 1`` was (``gap_ms`` long).

        The stack is shown down to the first frame of the file ``outer`` (the benchmark's own loop).
        """
        lines = []
        if len(self.sched) > i + 1:
            (c0, w0), (c1, w1) = self.sched[i], self.sched[i + 1]
            cpu, core = 1000 * (c1 - c0), 1000 * (w1 - w0)
            lines.append(f"{gap_ms:.0f} ms late: the GUI thread worked {cpu:.0f} ms, waited {core:.0f} ms "
                         f"for a core and {max(0.0, gap_ms - cpu - core):.0f} ms otherwise (GIL, X server)")
        stack = self._stacks.get(i, [])
        stack = stack[:next((k for k, frame in enumerate(stack) if frame.startswith(outer)), len(stack))]
        lines += [f"  {frame}" for frame in stack] or [
            f"  (no stack: the GUI thread was in Qt's event loop, or the stall was under "
            f"{1000 * LOOK_AFTER_S:.0f} ms)"]
        return lines


def _short(path: str) -> str:
    parts = path.replace(os.sep, "/").split("/")
    for root in ("app", "views", "core", "site-packages"):
        if root in parts:
            k = len(parts) - 1 - parts[::-1].index(root)
            return "/".join(parts[k + (root == "site-packages"):])
    return parts[-1]
