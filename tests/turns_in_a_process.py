"""Run a piece of code over and over, a turn of a Qt event loop each, in a process of its own: for
the faults only a crash shows (a Qt object destroyed while another thread uses it)."""

import os
import subprocess
import sys

from checkout import ROOT

SCRIPT = """
import sys, threading
import shiboken6
from PySide6.QtCore import QThreadPool, QTimer
from PySide6.QtWidgets import QApplication, QWidget
{imports}

app = QApplication(sys.argv)
count = [0]

def one_more():
{run}
    count[0] += 1
    if count[0] == {times}:
        app.quit()

timer = QTimer()
timer.timeout.connect(one_more)
timer.start(1)
app.exec()
QThreadPool.globalInstance().waitForDone()  # the jobs still running, and the threads still
for thread in threading.enumerate():  # importing, end before the process does
    if thread.name == "import pyvista":
        thread.join()
print("ran", count[0])
"""


def ran_to_the_end(run: str, folder, imports: str, times: int = 300) -> None:
    """``run`` (the body of a function, indented), after ``imports``, ran ``times`` times, one per turn
    of a Qt event loop, offscreen, in a process of its own started in ``folder``, which ended well."""
    env = {**os.environ, "QT_QPA_PLATFORM": "offscreen", "PYTHONPATH": str(ROOT)}
    script = SCRIPT.format(imports=imports, run=run, times=times)
    out = subprocess.run([sys.executable, "-c", script], env=env, cwd=folder, capture_output=True,
                         text=True, timeout=120)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.split() == ["ran", str(times)]
