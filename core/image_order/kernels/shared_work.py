"""What the threads of a parallel kernel share: the counter they take their work from, and their counters.

The tracer's parallel kernels (:func:`~core.image_order.kernels.render.render_pass`,
:func:`~core.image_order.kernels.shadow_rays.trace_shadow_rays`) run one loop
over their threads, each thread taking bands of work from one shared counter
(:func:`~core.image_order.kernels.intrinsics.bands.take_band`) and adding up
what it did in a row of counters of its own.  Both arrays are made here, by a
serial function the kernel calls before its loop: numba makes each
``np.zeros`` written in a kernel compiled with ``parallel=True`` a parallel
loop of its own (``parallel_diagnostics`` lists three loops in such a kernel),
so every call started the threads and waited for all of them three times where
once will do, and a thread that has slept since the last call is woken each
time: on this machine's virtual cores that takes milliseconds.  The lecture
scene's 172,145 shadow rays, traced 0.2 s after the last call (as ``python -m
app bench trace`` times them, two threads), took ours 13.4-13.9 ms where
Embree's kernel, one loop, took 5.8-6.0; with the arrays made here 6.9-7.8
against 7.8 (medians of 21 runs, three processes each).
"""

from __future__ import annotations

import numpy as np

from core.image_order import flat_layout
from core.image_order.kernels.jit import jit_allocating

#: Each thread's counters lie 256 bytes after the previous thread's.  Every ray adds to them, so
#: two threads must never share (or prefetch) one cache line of them: numpy aligns the array to
#: 16 bytes only, and with rows of one 64-byte line (the stride was 8) the two threads' rows
#: straddled a shared line; the adds then took about a sixth of a lecture frame's samples (perf).
COUNTER_STRIDE = 32


@jit_allocating
def shared_work(n_workers):
    """``(queue, counters)``: the threads' shared counter of work taken, (1,) int64 at 0, and
    their counters, ``(n_workers, COUNTER_STRIDE)`` int64 zeros (row ``w`` is thread ``w``'s).

    Both are rows of one array, the queue first, so that it too has cache lines of its own: every
    take of work writes it, and where it shared a line with a thread's counters, each take would
    take that line from the thread adding to them.
    """
    rows = np.zeros((n_workers + 1, COUNTER_STRIDE), np.int64)
    return rows[0, :1], rows[1:]


@jit_allocating
def work_done(counters):
    """All the threads' counters added up: (N_COUNTERS,) int64."""
    return counters.sum(axis=0)[:flat_layout.N_COUNTERS]
