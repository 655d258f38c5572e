"""Qt and pyvista views of the scene.

Importing this package guards against a reference-counting bug of PySide6
6.12.0: there every ``Signal.emit()`` made from Python drops one reference
to ``True`` (and other paths drop ``None``), so after some ten thousand
signals the interpreter aborts with "Fatal Python error: bool_dealloc".
A few emits of a throwaway signal show whether the installed PySide6 has
the bug; if it has, the reference counts of ``True``, ``False`` and ``None``
(never freed in a healthy process; Python 3.12 makes them immortal) are
raised far beyond what any run can drop.  With a fixed PySide6 nothing is
changed.
"""

import ctypes
import sys

from PySide6.QtCore import QObject, Signal


class _Probe(QObject):
    ping = Signal()


def _emit_drops_references() -> bool:
    probe = _Probe()
    before = sys.getrefcount(True)
    for _ in range(8):
        probe.ping.emit()
    return sys.getrefcount(True) < before


if _emit_drops_references():
    for _singleton in (True, False, None):
        ctypes.c_ssize_t.from_address(id(_singleton)).value += 1 << 40
