"""Bands of image rows, handed out to the render's threads one at a time.

Neighbouring pixels send nearly the same rays into the scene, so they visit
nearly the same BVH nodes and triangles.  When one thread traces a band of
neighbouring rows one after the other, the second row finds that data still
in the core's own cache.  When the rows are dealt out in turn (row 0 to one
thread, row 1 to the next, ...), every thread sweeps the whole image and
keeps reloading the whole tree: on the 100,000-triangle benchmark that costs
about a fifth of the primary rays' time.

Which thread takes which band is decided while the render runs: a thread
that is done with its band takes the next untaken one from a shared counter
(:func:`take_band`).  A thread that meets a busy part of the image is not
left with the rest of that part while the other threads idle, which a fixed
split of the image would do for a scene whose objects sit in one half.
"""

from __future__ import annotations

from numba import types
from numba.extending import intrinsic

#: Rows per band: enough for the rows to share cached nodes, few enough for an even share per thread.
BAND_ROWS = 8


@intrinsic
def take_band(typingctx, queue):
    """Take the next band: ``queue[0]`` before it was raised by one, atomically.

    ``queue`` is a (1,) int64 array shared by all threads, zero at the start.
    A plain ``queue[0] += 1`` could hand the same band to two threads; the
    atomic add cannot.
    """
    signature = types.int64(queue)

    def codegen(context, builder, sig, args):
        data = context.make_array(sig.args[0])(context, builder, args[0]).data
        one = context.get_constant(types.int64, 1)
        return builder.atomic_rmw("add", data, one, "monotonic")

    return signature, codegen
