"""A kernel called with constants compiles once, for the plain types, and still gives the same numbers."""

from numba import types

from core.compiling.one_signature import njit


@njit
def _scaled(x, doubled, times):
    return x * times * (2.0 if doubled else 1.0)


@njit
def _callers(x):
    total = _scaled(x, True, 3) + _scaled(x, False, 3)  # constants: Literal[bool], Literal[int]
    for n in range(2):  # a counter that starts as the constant 0
        total += _scaled(x, False, n)
    return total


@njit
def _pick(pair, at):
    return pair[at]


@njit
def _mixed(x):
    pair = (x, 7)  # a tuple of mixed types: only a constant index types
    return _pick(pair, 0) + _pick(pair, 1)


def test_calls_with_constant_arguments_share_one_compiled_signature_of_plain_types():
    # by hand: 1.5*3*2 + 1.5*3*1 + 1.5*0 + 1.5*1 = 9 + 4.5 + 0 + 1.5
    assert _callers(1.5) == 15.0
    assert _scaled.signatures == [(types.float64, types.boolean, types.int64)]


def test_a_callee_that_needs_its_constant_is_compiled_for_it():
    assert _mixed(2.5) == 9.5  # 2.5 + 7
    assert {str(sig[1]) for sig in _pick.signatures} == {"Literal[int](0)", "Literal[int](1)"}
