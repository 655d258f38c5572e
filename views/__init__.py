"""Qt and pyvista views of the scene.

Importing this package works around a reference-counting bug of PySide6
6.12.0: every ``Signal.emit()`` made from Python drops one reference to
``True`` (and other paths drop ``None``), so after some ten thousand
signals the interpreter aborts with "Fatal Python error: bool_dealloc".
These three objects are never freed in a healthy process (Python 3.12 makes
them immortal), so here their reference counts are raised far beyond what
any run can drop.  Remove this once PySide6 is pinned to a fixed release.
"""

import ctypes

import PySide6

if PySide6.__version__ == "6.12.0":
    for _singleton in (True, False, None):
        ctypes.c_ssize_t.from_address(id(_singleton)).value += 1 << 40
