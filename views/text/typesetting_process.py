"""Formulas are typeset in a process of their own.

mathtext is pure Python.  Typeset on a thread of the window's process, it held the interpreter's lock
in turns with the GUI thread: after a change of text size, the thread typesetting the formulas at the
new size ran 230 ms of a 330 ms stall of the window, whose own work was 120 ms (``bench gui``, each
thread's CPU time read from ``/proc``).  In a process of its own it runs on the other core, and the
window waits for nothing.

One child process (``python -m views.text.typesetting_process``) reads requests from its standard
input and answers each on its standard output, in turn; it ends when its input closes, as when the
window's process ends, however that ends.  It ignores Ctrl+C, which the terminal sends to both
processes: the window's process decides how to end.  If the process cannot be started, or dies,
formulas are typeset in this process again, as before (the same pictures, a slower window).

No Qt here: the child loads numpy and matplotlib's mathtext only.
"""

from __future__ import annotations

import os
import pickle
import subprocess
import sys
import threading
from pathlib import Path


def ink(text: str, size_pt: float, color: str, dpi: float):
    """(H, W, 4) uint8 RGBA of ``text`` typeset by mathtext at ``size_pt`` in ``color``, transparent
    around it, typeset by the process that calls this.

    Raises ValueError if ``text`` is not valid mathtext (the message says where)."""
    import numpy as np
    from matplotlib.colors import to_rgb
    from matplotlib.font_manager import FontProperties

    from views.images.matplotlib_lock import MATPLOTLIB

    with MATPLOTLIB:  # in the window's process, the parser and its fonts are shared with the plots
        alpha = np.asarray(_parser().parse(text, dpi=dpi, prop=FontProperties(size=size_pt)).image)
    pad = max(2, int(round(0.15 * size_pt * dpi / 72.0)))  # room for glyphs at the box's edge
    alpha = np.pad(alpha, pad)
    rgba = np.empty((*alpha.shape, 4), np.uint8)
    rgba[..., :3] = np.round(np.array(to_rgb(color)) * 255).astype(np.uint8)
    rgba[..., 3] = alpha
    return rgba


_parsers = []


def _parser():
    if not _parsers:
        from matplotlib.mathtext import MathTextParser

        _parsers.append(MathTextParser("agg"))  # typesets straight into an 8-bit coverage image
    return _parsers[0]


class _Child:
    """The typesetting process, asked one formula at a time."""

    def __init__(self):
        root = str(Path(__file__).resolve().parents[2])  # where the views package is, installed or not
        env = dict(os.environ, PYTHONPATH=os.pathsep.join(filter(None, [root, os.environ.get("PYTHONPATH")])))
        self.process = subprocess.Popen([sys.executable, "-m", "views.text.typesetting_process"],
                                        stdin=subprocess.PIPE, stdout=subprocess.PIPE, env=env)

    def ask(self, request: tuple):
        pickle.dump(request, self.process.stdin)
        self.process.stdin.flush()
        ok, answer = pickle.load(self.process.stdout)  # EOFError if the child died
        if not ok:
            raise ValueError(answer)
        return answer


_lock = threading.Lock()  # one request at a time: the typesetter's thread, now and then the GUI thread
_child: list[_Child | None] = []  # empty until started; [None] once it could not start or died


def typeset(text: str, size_pt: float, color: str, dpi: float):
    """:func:`ink` of the arguments, typeset in the typesetting process (started on first use)."""
    with _lock:
        if not _child:
            try:
                _child.append(_Child())
            except OSError:
                _child.append(None)
        child = _child[0]
        if child is not None:
            try:
                return child.ask((text, size_pt, color, dpi))
            except (OSError, EOFError, pickle.UnpicklingError):  # the process is gone: typeset here
                _child[0] = None
    return ink(text, size_pt, color, dpi)


def _serve(requests, answers) -> None:
    """The child's loop: typeset each request, answer ``(True, rgba)`` or ``(False, message)``."""
    while True:
        try:
            request = pickle.load(requests)
        except EOFError:  # the window's process closed its end: it has ended
            return
        try:
            answer = (True, ink(*request))
        except ValueError as exc:
            answer = (False, str(exc))
        pickle.dump(answer, answers)
        answers.flush()


if __name__ == "__main__":
    import signal

    signal.signal(signal.SIGINT, signal.SIG_IGN)
    answers = os.fdopen(os.dup(1), "wb")  # the answers' own copy of standard output ...
    os.dup2(2, 1)  # ... and whatever a library prints goes to standard error, not among them
    sys.stdout = sys.stderr
    _serve(sys.stdin.buffer, answers)
