"""The installed Qt binding must not corrupt Python's reference counts (PySide6 6.12.0 did)."""

import os
import subprocess
import sys

CODE = """
import sys
from PySide6.QtWidgets import QApplication, QLabel
app = QApplication([])
label = QLabel()
before = sys.getrefcount(None)
for _ in range(200):
    label.setText("x")
    label.setEnabled(True)
print(sys.getrefcount(None) - before)
"""


def test_qt_calls_that_return_nothing_leave_the_reference_count_of_none_alone():
    # PySide6 6.12.0 decremented None once per such call; on Python 3.11, where None is not
    # immortal, a few thousand calls freed None and aborted the app ("none_dealloc").
    out = subprocess.run([sys.executable, "-c", CODE], capture_output=True, text=True, timeout=120,
                         env={**os.environ, "QT_QPA_PLATFORM": "offscreen"})
    assert out.returncode == 0, out.stderr[-2000:]
    assert abs(int(out.stdout.split()[-1])) < 50, "each Qt call changed None's reference count"
