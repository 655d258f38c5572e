"""The first window on a machine compiles every renderer's kernels in the background, on every core.

The kernels compile once per machine and version of the code (:mod:`core.compiling.kernel_cache`).
The window's first render would compile only what it needs, on one core, and
every other tab would compile its own kernels when first shown.  So once the
window is on screen, a thread looks whether every kernel group is compiled
(that imports numba: not on the GUI thread), and if not it starts
``python -m app compile --give-way`` in a process of its own at a lower priority
(:mod:`core.give_way`: the process lowers its own; a hook run between ``fork`` and ``exec``,
as ``subprocess``'s ``preexec_fn``, is not safe in a process with threads), which
compiles each group in a process of its own.  A render that needs kernels being
compiled there waits for them (:class:`core.compiling.warm_up.WarmUp` holds a lock file
while it compiles) and then loads them, saying so in its progress bar; the
window stays responsive.  Closing the window stops the compile; what was
finished stays compiled.
"""

from __future__ import annotations

import contextlib
import os
import signal
import subprocess
import sys
import threading

from app.commands.compile_kernels import child_env
from core.compiling.warm_up import GROUPS, warm_up_of


class BackgroundCompile:
    """Start with :meth:`start`; :meth:`stop` ends the compile if it still runs."""

    #: What runs: ``python`` and these arguments.
    COMMAND = ("-m", "app", "compile", "--quiet", "--give-way")

    def __init__(self):
        self._process: subprocess.Popen | None = None
        self._stopped = threading.Event()
        self.checked = threading.Event()
        """Set once the thread has looked (and started the compile if it was needed)."""

    def start(self) -> None:
        """Look in a thread whether anything is to compile, and start compiling it if so."""
        threading.Thread(target=self._start_if_needed, name="background compile", daemon=True).start()

    def _start_if_needed(self) -> None:
        try:
            if not self._stopped.is_set() and not all(warm_up_of(group).ready() for group in GROUPS):
                self._start()
        finally:
            self.checked.set()

    def _start(self) -> None:
        self._process = subprocess.Popen(
            [sys.executable, *self.COMMAND], env=child_env(), stdin=subprocess.DEVNULL,
            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, start_new_session=True)

    @property
    def running(self) -> bool:
        return self._process is not None and self._process.poll() is None

    def stop(self) -> None:
        """End the compile and every process it started (the window is closing)."""
        self._stopped.set()
        if self.running:
            with contextlib.suppress(ProcessLookupError):  # ended by itself just now
                os.killpg(self._process.pid, signal.SIGTERM)
