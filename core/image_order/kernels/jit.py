"""How the tracer's kernels are compiled: one place for numba's options.

``jit`` compiles a helper (called from other kernels, or from Python for a
single ray); ``jit_parallel`` compiles an entry kernel whose ``prange`` loops
run on all cores.  Both

- cache the machine code on disk (``cache=True``), so only the first run on a
  machine pays the compile time;
- release the GIL (``nogil=True``), so a worker thread renders while the GUI
  thread keeps running;
- follow IEEE 754 for division by zero (``error_model="numpy"``): ``1 / 0``
  is ``inf`` rather than an exception, which the slab test relies on.

``jit`` and ``jit_inline`` helpers also borrow their arrays (numba's
``_nrt=False``): numba otherwise counts the references of every array a
function binds, an atomic add on a counter that all threads share, and in the
render's loops those counts took about a third of the time (perf, lecture
scene: samples in ``NRT_incref``/``NRT_decref``).
The arrays belong to the caller for the whole render, so the helpers need no
count; a borrowing helper must then neither make an array nor return one
(``tests/core/image_order/test_trace_kernels.py`` checks every compiled signature).  The
few helpers that make arrays are compiled with ``jit_allocating``.

``fastmath`` stays off: the watertight triangle test needs ``a*b - c*d`` to be
evaluated exactly as written (no fused multiply-add, no reassociation).

The cache
---------
On import this module caches the tracer's kernels in the user's cache folder, in a
folder named after the contents of every file they are made of (:data:`SOURCES`;
:mod:`core.compiling.kernel_cache`): every checkout and install of the same code shares them,
and a changed formula (say in :mod:`core.image_order.optics`) is never served from an
old kernel.  It also registers the formulas marked :func:`~core.compiling.jitable.jitable` with
numba (:func:`core.compiling.jitable.register_all`).
"""

from __future__ import annotations

from pathlib import Path

from core.compiling.jitable import register_all
from core.compiling.kernel_cache import share_cache
from core.compiling.one_signature import njit

# ``forceinline`` is set on every kernel: a kernel compiled for an inlined caller would inherit it
_OPTIONS = {"cache": True, "nogil": True, "error_model": "numpy", "forceinline": False}
_BORROWING = {**_OPTIONS, "_nrt": False}
_KERNELS = Path(__file__).resolve().parent
_IMAGE_ORDER = _KERNELS.parent
_CORE = _IMAGE_ORDER.parent
#: Every file whose code ends up inside the tracer's compiled kernels: the kernels
#: themselves (this folder and its sub-folders), the flat arrays' layout, the lecture
#: modules whose ``register_jitable`` formulas they compile in, and the shared modules those import
#: (the primary ray's formula lives with the camera).  ``tests/core/image_order/test_trace_kernels.py``
#: checks that every ``core`` module a listed file imports is listed too.
SOURCES = sorted(_KERNELS.rglob("*.py")) + [
    _IMAGE_ORDER / name for name in ("flat_layout.py", "optics.py", "shading.py", "ray_offset.py",
                                     "intersect_sphere.py", "intersect_triangle.py", "ray_casting.py")] + [
    _CORE / name for name in ("camera.py", "projection.py", "compiling/jitable.py",
                              "compiling/one_signature.py", "shown_numbers.py")]


share_cache(_KERNELS, SOURCES, "trace")
register_all()  # the lecture modules' formulas, before any kernel is compiled or loaded


#: Every kernel compiled to borrow its arrays, for the test that none returns one.
BORROWING: list = []


def _borrowing(func, **options):
    dispatcher = njit(**{**_BORROWING, **options})(func)
    BORROWING.append(dispatcher)
    return dispatcher


def jit(func):
    """Compile ``func`` with the tracer's options (serial), borrowing its arrays."""
    return _borrowing(func)


def jit_allocating(func):
    """Compile ``func`` with the tracer's options (serial), counting references: for the few
    kernels that make arrays."""
    return njit(**_OPTIONS)(func)


def jit_inline(func):
    """Compile ``func`` with the tracer's options, inlined into every caller (for the
    innermost tests, where the cost of a call would exceed the work).

    LLVM inlines it (``forceinline``), after numba compiled it once: numba's own inlining
    (``inline="always"``) typed and compiled its body again at every call, and the kernels
    inline each other several levels deep (on the tracer, about 2.8 times the compile time).
    """
    return _borrowing(func, forceinline=True)


def jit_parallel(func):
    """Compile ``func`` with the tracer's options, ``prange`` loops in parallel."""
    return njit(parallel=True, **_OPTIONS)(func)
