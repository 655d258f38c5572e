"""Formulas the kernels compile in, marked without importing numba.

Each formula of the lecture is written once, as a plain Python function that
the readable code, the worked solutions and the compiled kernels all call
(numba's ``register_jitable``).  But importing numba takes about half a
second, and the lecture modules (the camera, the scene, the formulas the
panels explain) are all on the window's import path: the window would wait
for a compiler it does not need until its first render.

So the modules mark their formulas with :func:`jitable`, which returns the
function unchanged and only notes it.  :func:`register_all` hands every noted
function to ``numba.extending.register_jitable``; each kernel package calls it
on import, before any kernel is compiled or loaded from numba's disk cache.
Functions marked after that are registered at once.
"""

from __future__ import annotations

import threading
from collections.abc import Callable

_lock = threading.Lock()
_pending: list[tuple[Callable, dict]] = []
_registered = False


def _register(func: Callable, options: dict) -> None:
    from numba.extending import register_jitable

    if options:
        register_jitable(**options)(func)
    else:
        register_jitable(func)


def jitable(func: Callable | None = None, **options):
    """Mark ``func`` as a formula numba may compile into a kernel; returns ``func`` itself.

    Use as ``@jitable`` or ``@jitable(forceinline=True)``; the options are those of
    ``numba.extending.register_jitable``.
    """

    def mark(f: Callable) -> Callable:
        with _lock:
            if _registered:
                _register(f, options)
            else:
                _pending.append((f, options))
        return f

    return mark if func is None else mark(func)


def register_all() -> None:
    """Register every formula marked so far with numba (imports numba); later marks register at once."""
    global _registered
    with _lock:
        for func, options in _pending:
            _register(func, options)
        _pending.clear()
        _registered = True
