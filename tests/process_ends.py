"""Waiting for a process to end, from outside it: its entry in ``/proc``."""

from __future__ import annotations

import time


def ended(pid: int, timeout_s: float = 60.0) -> bool:
    """Whether process ``pid`` ends within ``timeout_s`` (a zombie waiting for its new parent has ended)."""
    deadline = time.monotonic() + timeout_s
    while time.monotonic() < deadline:
        try:
            with open(f"/proc/{pid}/stat") as stat:
                if stat.read().rsplit(")", 1)[1].split()[0] == "Z":
                    return True
        except FileNotFoundError:
            return True
        time.sleep(0.05)  # a process, not the GUI: nothing to wait on but its entry in /proc
    return False
