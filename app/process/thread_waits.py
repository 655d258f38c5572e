"""Threads that wait for the others sleep, and give their core back.

numba runs the renderers' parallel loops (``prange``) on OpenMP's threads
(GNU ``libgomp``).  By default a thread that is done with its share of a loop
spins, up to 300,000 rounds (``GOMP_SPINCOUNT``), waiting for the others, and
the pool spins the same way after each loop.  A Whitted frame has three such
loops, one per stage (:mod:`core.image_order.kernels.render`); at the end of
each, the thread done first spins on a core.  Where the cores are shared with
other programs (or the other render thread waits for a core), that core is
taken from the very thread it waits for.  :func:`let_waiting_threads_sleep`
sets ``OMP_WAIT_POLICY=PASSIVE``: a thread that waits sleeps at once, and is
woken when there is work (some microseconds, against a frame's milliseconds).

Measured on a 2-core machine shared with other work, separate processes
interleaved twelve times: a Whitted frame at 640 x 480, depth 5, takes 7-9%
less CPU time of the process (lecture scene 90.5 -> 84.6 ms, mirror and glass
146.5 -> 136.0 ms, medians; about the same in the machine's quiet minutes) and
no more wall-clock time; the rasterizer's frames are unchanged.

The setting must be made before the OpenMP library is loaded (numba loads it
at the first parallel loop), so it is made once, in the program's entry
(:mod:`app.__main__`).  A policy the user has set is kept.
"""

from __future__ import annotations

import os


def let_waiting_threads_sleep() -> None:
    """Make OpenMP's waiting threads sleep (see the module), unless ``OMP_WAIT_POLICY`` is set."""
    os.environ.setdefault("OMP_WAIT_POLICY", "PASSIVE")
