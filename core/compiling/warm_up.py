"""Compiled (numba) versions of the hot loops, and their warm-ups.

Every kernel is ``@njit(cache=True, nogil=True)``: compiled once per machine and
version of the code, kept in the user's cache folder (:mod:`core.compiling.kernel_cache`),
and it releases the GIL so a worker thread really runs in parallel with the GUI.
Each kernel has a plain numpy reference in the module named after its lecture
concept, and a test checks that both agree.

A *warm-up* renders a tiny scene so that a group of kernels is compiled (or
loaded from the cache) before a real render needs it; :data:`GROUPS` lists every
group, for ``python -m app compile`` and its benchmark.
"""

from __future__ import annotations

import contextlib
import fcntl
import importlib
import threading
import time
from pathlib import Path

#: Every kernel group: its name -> ``module:WarmUp`` that compiles all of it; the largest first, so
#: that ``python -m app compile`` starts it first.
GROUPS = {
    "trace": "core.image_order.ray_tracing:compile_renders",
    "ray-tree": "core.image_order.ray_tracing:compile_ray_tree_and_shadow_rays",
    "raster": "core.object_order.pipeline:ensure_compiled",
}


def warm_up_of(group: str) -> WarmUp:
    """The :class:`WarmUp` of a group of :data:`GROUPS`."""
    module, name = GROUPS[group].split(":")
    return getattr(importlib.import_module(module), name)


class WarmUp:
    """Compile (or load from the kernel cache) a group of kernels once per process.

    ``WarmUp(warm_up, kernels, tag, name)()`` runs ``warm_up`` the first time and returns
    the seconds it took; later calls, and a call made from inside ``warm_up``
    itself (a warm-up that renders a tiny scene), return 0.0 at once.  Other
    threads wait until the first run is done, and so do other processes: while one
    compiles these kernels (``python -m app compile`` in the background, say) it holds
    a lock file beside them, and the others wait for it and then load what it
    compiled instead of compiling the same kernels again.  Renders report this time
    as compile time, apart from the time of their stages.

    Parameters
    ----------
    warm_up : renders a tiny scene with the group's kernels.
    kernels : the kernel package (imported to find the group's cache folder).
    tag : the kernel group's cache tag (:func:`core.compiling.kernel_cache.share_cache`).
    name : this warm-up's name, unique within ``tag``.
    """

    def __init__(self, warm_up, kernels: str, tag: str, name: str):
        self._warm_up = warm_up
        self._kernels, self._tag, self.name = kernels, tag, name
        self._done = threading.Event()
        self._lock = threading.RLock()
        self._running = False

    def marker(self) -> Path:
        """The file whose presence says these kernels are compiled on this machine (imports numba)."""
        importlib.import_module(self._kernels)
        from core.compiling.kernel_cache import compiled_marker

        return compiled_marker(self._tag, self.name)

    def ready(self) -> bool:
        """Whether calling this costs no compile: run in this process already, or compiled on this
        machine before (then it loads the kernels from the cache, a second or two)."""
        return self._done.is_set() or self.marker().exists()

    def __call__(self) -> float:
        if self._done.is_set():
            return 0.0
        with self._lock:
            if self._done.is_set() or self._running:
                return 0.0
            self._running = True
            try:
                start = time.perf_counter()
                with self._machine_lock():
                    self._warm_up()
                    self._done.set()
                    with contextlib.suppress(OSError):  # unwritable: the kernels live in a temporary folder
                        self.marker().touch()
                return time.perf_counter() - start
            finally:
                self._running = False

    @contextlib.contextmanager
    def _machine_lock(self):
        """Hold this warm-up's lock file for as long as it runs: one process at a time compiles it."""
        marker = self.marker()
        try:
            lock = open(marker.with_suffix(".lock"), "a")  # noqa: SIM115 -- held across the yield
        except OSError:  # an unwritable cache: nothing to share, nobody to wait for
            yield
            return
        with lock:
            fcntl.flock(lock, fcntl.LOCK_EX)
            yield
