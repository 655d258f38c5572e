"""A parallel kernel starts its threads once a call: its one loop over the threads is its only parallel loop.

numba makes every ``np.zeros`` written in a kernel compiled with ``parallel=True`` a parallel
loop of its own, which starts the threads and waits for all of them like the kernel's own
``prange`` loop (``core.image_order.kernels.shared_work``): a kernel that made its arrays itself
started its threads three times a call.
"""

import ast

import numpy as np
from checkout import ROOT
from numba import njit, prange

from core.image_order.kernels.shared_work import COUNTER_STRIDE, shared_work, work_done


@njit(parallel=True)
def _making_its_arrays(n_workers):
    queue = np.zeros(1, np.int64)
    counters = np.zeros((n_workers, COUNTER_STRIDE), np.int64)
    for w in prange(n_workers):
        counters[w, 0] += 1 + queue[0]
    return counters.sum(axis=0)[:3]


@njit(parallel=True)
def _given_its_arrays(n_workers):
    queue, counters = shared_work(n_workers)
    for w in prange(n_workers):
        counters[w, 0] += 1 + queue[0]
    return work_done(counters)


def _parallel_loops(kernel) -> int:
    compiled = next(iter(kernel.overloads.values()))
    return len(compiled.metadata["parfor_diagnostics"].initial_parfors)


def test_arrays_made_in_a_parallel_kernel_are_parallel_loops_of_their_own_and_shared_work_makes_none():
    assert _making_its_arrays(2)[0] == 2
    assert _given_its_arrays(2)[0] == 2  # both threads counted their one turn
    assert _parallel_loops(_making_its_arrays) == 3
    assert _parallel_loops(_given_its_arrays) == 1


def _is_parallel(decorator: ast.expr) -> bool:
    if isinstance(decorator, ast.Name):
        return decorator.id == "jit_parallel"
    return isinstance(decorator, ast.Call) and any(
        k.arg == "parallel" and isinstance(k.value, ast.Constant) and k.value.value is True
        for k in decorator.keywords)


def _is_prange_loop(node: ast.AST) -> bool:
    return (isinstance(node, ast.For) and isinstance(node.iter, ast.Call)
            and isinstance(node.iter.func, ast.Name) and node.iter.func.id == "prange")


def _numpy_calls(statements) -> list[str]:
    return [ast.unparse(node) for statement in statements for node in ast.walk(statement)
            if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute)
            and isinstance(node.func.value, ast.Name) and node.func.value.id == "np"]


def test_every_parallel_kernel_of_core_has_one_prange_loop_and_makes_no_numpy_array_outside_it():
    kernels = {}
    for path in sorted((ROOT / "core").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text())):
            if isinstance(node, ast.FunctionDef) and any(map(_is_parallel, node.decorator_list)):
                kernels[f"{path.relative_to(ROOT)}:{node.name}"] = node
    # the tracer's render and shadow rays, the rasterizer's boxes and bands, culling, flat shading
    assert len(kernels) >= 6, sorted(kernels)
    for name, kernel in kernels.items():
        loops = [node for node in ast.walk(kernel) if _is_prange_loop(node)]
        assert len(loops) == 1, f"{name}: {len(loops)} prange loops"
        outside = [statement for statement in kernel.body if not _is_prange_loop(statement)]
        assert _numpy_calls(outside) == [], f"{name} makes arrays outside its prange loop"
