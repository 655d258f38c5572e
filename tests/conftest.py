"""Shared test set-up, free of Qt and pyvista: ``pytest tests/core`` runs where neither is installed.

The compiled kernels are the user's (``~/.cache/render-explorer/kernels``, compiled
up front by ``python -m app compile`` in ``.ci/test.sh``): every test, and every
process a test starts, finds them there even when it points ``XDG_CACHE_HOME``
at an empty folder, so no test compiles kernels inside its own time limit.
The fixtures of the window and view tests are in :mod:`qt_fixtures`.
"""

import os

from core.compiling.kernel_cache import cache_root

os.environ["NUMBA_CACHE_DIR"] = str(cache_root())


def pytest_configure(config):
    config.addinivalue_line("markers", "gui: needs an X server (Qt xcb plugin, OpenGL for VTK)")
