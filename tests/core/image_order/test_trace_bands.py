"""Threads share an image by taking bands of rows from one counter: no band twice, none left out."""

import numba
import numpy as np
from numba import njit, prange

from core.image_order.kernels.intrinsics.bands import take_band


@njit(parallel=True)
def take_at_once(n_workers, takes_each):
    queue = np.zeros(1, np.int64)
    taken = np.empty((n_workers, takes_each), np.int64)
    for w in prange(n_workers):
        for i in range(takes_each):
            taken[w, i] = take_band(queue)
    return taken


def test_threads_taking_bands_at_the_same_time_get_each_band_exactly_once():
    # Two threads hammer the counter; a plain read-add-write would hand out some numbers twice.
    taken = take_at_once(max(2, numba.get_num_threads()), 100_000)
    assert np.array_equal(np.sort(taken.ravel()), np.arange(taken.size))
