"""A formula marked ``jitable`` is plain Python without numba and compiles into kernels once registered."""

import subprocess
import sys

from checkout import ROOT

FRESH_PROCESS = """
import math, sys
from core.compiling.jitable import jitable, register_all

@jitable
def hypot2(a, b):
    return a * a + b * b

@jitable(inline="always")
def half(x):
    return 0.5 * x

plain = (hypot2(3.0, 4.0), half(5.0), "numba" in sys.modules)
register_all()

@jitable
def root(x):  # marked after register_all: registered at once
    return math.sqrt(x)

from numba import njit

@njit
def kernel(a, b):
    return half(root(hypot2(a, b)))

print(plain, kernel(3.0, 4.0), kernel(5.0, 12.0))
"""


def test_marked_formulas_run_as_python_without_numba_and_compile_into_a_kernel_after_register_all():
    out = subprocess.run([sys.executable, "-c", FRESH_PROCESS], cwd=ROOT, capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr
    # 3² + 4² = 25 and 5 / 2; the kernel: sqrt(25) / 2 and sqrt(5² + 12²) / 2 = 13 / 2.
    assert out.stdout.split("\n")[0] == "(25.0, 2.5, False) 2.5 6.5"
