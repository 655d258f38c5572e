"""Formulas are typeset in a process of their own (:mod:`core.helper_process`).

mathtext is pure Python.  Typeset on a thread of the window's process, it held the interpreter's lock
in turns with the GUI thread: after a change of text size, the thread typesetting the formulas at the
new size ran 230 ms of a 330 ms stall of the window, whose own work was 120 ms (``bench gui``, each
thread's CPU time read from ``/proc``).  In a process of its own it runs on the other core, and the
window waits for nothing.

No Qt here: the helper loads numpy and matplotlib's mathtext only.
"""

from __future__ import annotations

from core import helper_process


def typeset(text: str, size_pt: float, color: str, dpi: float):
    """:func:`ink` of the arguments, typeset in the typesetting process (started on first use)."""
    return helper_process.call(__name__, "ink", text, size_pt, color, dpi)


def ink(text: str, size_pt: float, color: str, dpi: float):
    """(H, W, 4) uint8 RGBA of ``text`` typeset by mathtext at ``size_pt`` in ``color``, transparent
    around it, typeset by the process that calls this.

    Raises ValueError if ``text`` is not valid mathtext (the message says where)."""
    import numpy as np
    from matplotlib.colors import to_rgb
    from matplotlib.font_manager import FontProperties

    from views.matplotlib_lock import MATPLOTLIB

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
