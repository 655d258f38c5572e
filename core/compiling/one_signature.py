"""One compiled signature per kernel: a call with constant arguments uses the plain one.

numba compiles a kernel called from another kernel once per distinct list of argument
types, and a constant has a type of its own: ``f(x, True)`` and ``f(x, False)`` compile ``f``
twice (``Literal[bool](True)``, ``Literal[bool](False)``), and so does ``f(n)`` in a loop whose
counter starts at 0 (numba types the call once with ``Literal[int](0)`` before it learns that
``n`` is an ``int64``, and compiles both).  On the tracer's kernels that was a third of the
compiled copies (``python -m app bench compile``, issue 30).

:func:`njit` compiles a kernel as numba's ``njit`` does, but types such a call with the
plain types (``bool``, ``int64``) first, so every caller shares one compiled copy.  A
caller's constant still reaches the callee's code where it is inlined
(:mod:`core.image_order.kernels.jit`): LLVM folds it there.  A callee that cannot be typed
without its constant (an index into a tuple of mixed types) is compiled for it, as before.
"""

from __future__ import annotations

from numba import types
from numba.core import errors
from numba.core.registry import CPUDispatcher


class OneSignatureDispatcher(CPUDispatcher):
    """numba's CPU dispatcher, typing calls from other kernels without their constants first."""

    def get_call_template(self, args, kws):
        plain_args = tuple(types.unliteral(a) for a in args)
        plain_kws = {name: types.unliteral(a) for name, a in kws.items()}
        if plain_args != tuple(args) or plain_kws != kws:
            try:
                return super().get_call_template(plain_args, plain_kws)
            except errors.TypingError:
                pass  # it needs the constant itself: compiled for it below
        return super().get_call_template(args, kws)


def njit(func=None, *, cache: bool = False, **options):
    """``numba.njit(**options)`` with :class:`OneSignatureDispatcher`; use as ``@njit`` or
    ``@njit(cache=True, ...)``."""

    def compile_lazily(f):
        dispatcher = OneSignatureDispatcher(py_func=f, locals={}, targetoptions={"nopython": True, **options})
        if cache:
            dispatcher.enable_caching()
        return dispatcher

    return compile_lazily if func is None else compile_lazily(func)
