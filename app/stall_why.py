"""``bench gui --why``: what the GUI thread was doing in its longest stall.

A watchdog that needs no GIL (:func:`faulthandler.dump_traceback_later`) is
re-armed at every tick of the bench's 5 ms timer; when a tick is more than
:data:`LOOK_AFTER_S` late it writes every thread's Python stack to a file, so a
stall shows its GUI-thread stack even while C++ code (VTK, Qt) holds the GIL.
On Linux each tick also reads the GUI thread's scheduler counters, which split a
stall into the thread's own work, waiting for a core (other threads or programs
were running) and waiting otherwise (for the GIL, the X server).
"""

from __future__ import annotations

import faulthandler
import os
import re
import tempfile
import threading

LOOK_AFTER_S = 0.05
"""The stack is taken this long into a stall; shorter stalls have none."""

_SCHEDSTAT = "/proc/thread-self/schedstat"


class StallWhy:
    """Record, per tick of the GUI thread, its stack if the next tick is late, and its scheduler times."""

    def __init__(self):
        self._dump = tempfile.TemporaryFile("w+")  # noqa: SIM115  (read and closed by stop())
        self._text = ""
        self._tick = 0
        self.sched: list[tuple[float, float]] = []  # (cpu s, waiting for a core s) at each tick

    def tick(self) -> None:
        """Call on the GUI thread at every tick."""
        os.write(self._dump.fileno(), f"\n@tick {self._tick}\n".encode())
        self._tick += 1
        faulthandler.dump_traceback_later(LOOK_AFTER_S, file=self._dump)
        if os.path.exists(_SCHEDSTAT):
            with open(_SCHEDSTAT) as f:
                cpu_ns, wait_ns, _ = f.read().split()
            self.sched.append((int(cpu_ns) / 1e9, int(wait_ns) / 1e9))

    def stop(self) -> None:
        """Stop watching; the stacks are kept for :meth:`explain`."""
        faulthandler.cancel_dump_traceback_later()
        self._dump.seek(0)
        self._text = self._dump.read()
        self._dump.close()

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
        part = re.search(rf"\n@tick {i}\n(.*?)(?:\n@tick |\Z)", self._text, re.S)
        stack = _main_thread_stack(part.group(1)) if part else []
        stack = stack[:next((k for k, frame in enumerate(stack) if frame.startswith(outer)), len(stack))]
        lines += [f"  {frame}" for frame in stack] or [
            f"  (no stack: the GUI thread was in Qt's event loop, or the stall was under "
            f"{1000 * LOOK_AFTER_S:.0f} ms)"]
        return lines


def _main_thread_stack(dump: str) -> list[str]:
    """The GUI (main) thread's frames in a faulthandler dump, innermost first, paths shortened."""
    main = threading.main_thread().ident
    for block in re.split(r"\n(?=(?:Current thread|Thread) 0x)", dump):
        head = re.match(r"(?:Current thread|Thread) 0x([0-9a-f]+)", block)
        if head and int(head.group(1), 16) == main:
            frames = re.findall(r'File "([^"]+)", line (\d+) in (\S+)', block)
            return [f"{_short(path)}:{line} {name}" for path, line, name in frames]
    return []


def _short(path: str) -> str:
    parts = path.replace(os.sep, "/").split("/")
    for root in ("app", "views", "core", "site-packages"):
        if root in parts:
            k = len(parts) - 1 - parts[::-1].index(root)
            return "/".join(parts[k + (root == "site-packages"):])
    return parts[-1]
