"""The installed Qt binding must not corrupt Python's reference counts (PySide6 6.12.0 did)."""

import os
import subprocess
import sys

CODE = """
import sys
from PySide6.QtCore import QObject, Signal
from PySide6.QtWidgets import QApplication, QLabel
class Probe(QObject):
    ping = Signal()
app = QApplication([])
label, probe = QLabel(), Probe()
before = sys.getrefcount(None), sys.getrefcount(True)
for _ in range(200):
    label.setText("x")
    label.setEnabled(True)
    probe.ping.emit()
print(sys.getrefcount(None) - before[0], sys.getrefcount(True) - before[1])
"""


def test_qt_calls_and_signals_leave_the_reference_counts_of_none_and_true_alone():
    # PySide6 6.12.0 decremented None once per such call and True once per emit(); on
    # Python 3.11, where neither is immortal, a few thousand calls freed them and aborted
    # the app ("none_dealloc", "bool_dealloc").
    out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, timeout=120,
                         env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    assert out.returncode == 0, out.stderr[-2000:]
    none_change, true_change = (int(v) for v in out.stdout.split()[-2:])
    assert abs(none_change) < 50, "Qt calls changed the reference count of None"
    assert abs(true_change) < 50, "Signal.emit() changed the reference count of True"
