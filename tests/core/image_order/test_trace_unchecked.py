"""The traversal's unchecked array access reads and writes the element numpy's ``flat`` names."""

import numpy as np
import pytest
from numba import njit
from numba.core.errors import TypingError

from core.image_order.kernels.intrinsics.unchecked import load_at, store_at


@njit
def _read_all(array):
    out = np.empty(array.size, array.dtype)
    for k in range(array.size):
        out[k] = load_at(array, k)
    return out


@njit
def _write(array, index, value):
    store_at(array, index, value)


def test_reads_every_element_in_flat_order_of_a_two_dimensional_array():
    nodes = np.arange(24, dtype=np.int32).reshape(4, 6) * 7 - 50  # negative values too
    assert np.array_equal(_read_all(nodes), nodes.ravel())


def test_writes_the_flat_element_and_converts_to_the_array_type():
    stack = np.zeros((3, 4))
    _write(stack, 9, 2)  # an int into a float array
    expected = np.zeros((3, 4))
    expected.flat[9] = 2.0
    assert np.array_equal(stack, expected)
    counts = np.zeros(5, np.int64)
    _write(counts, 4, 7)
    assert counts.tolist() == [0, 0, 0, 0, 7]


def test_refuses_an_array_whose_flat_order_is_not_its_memory_order():
    with pytest.raises(TypingError, match="C-contiguous"):
        _read_all(np.zeros((4, 6))[:, ::2])
