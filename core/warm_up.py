"""Compiled (numba) versions of the hot loops.

Every kernel here is ``@njit(cache=True, nogil=True)``: compiled once and
cached on disk, and it releases the GIL so a worker thread really runs in
parallel with the GUI.  Each kernel has a plain numpy reference in the module
named after its lecture concept, and a test checks that both agree.
"""

import threading
import time


class WarmUp:
    """Compile (or load from numba's disk cache) a group of kernels once per process.

    ``WarmUp(warm_up)()`` runs ``warm_up`` the first time and returns the
    seconds it took; later calls, and a call made from inside ``warm_up``
    itself (a warm-up that renders a tiny scene), return 0.0 at once.  Other
    threads wait until the first run is done.  Renders report this time as
    compile time, apart from the time of their stages.
    """

    def __init__(self, warm_up):
        self._warm_up = warm_up
        self._done = threading.Event()
        self._lock = threading.RLock()
        self._running = False

    def __call__(self) -> float:
        if self._done.is_set():
            return 0.0
        with self._lock:
            if self._done.is_set() or self._running:
                return 0.0
            self._running = True
            try:
                start = time.perf_counter()
                self._warm_up()
                self._done.set()
                return time.perf_counter() - start
            finally:
                self._running = False
