"""matplotlib is for one thread at a time.

Its settings (``rcParams``) are global, and its fonts (FreeType faces, cached
per thread but shared by the mathtext parser's cached results) and the
mathtext parser itself are shared: a formula typeset on one thread while a plot
is drawn on another has failed with FreeType's "invalid outline".  Whoever
draws a figure or typesets a formula, on any thread, holds :data:`MATPLOTLIB`
meanwhile.  (No Qt here: the command line's pictures hold it too.)
"""

import threading

MATPLOTLIB = threading.RLock()  # re-entrant: a drawing may save its figure while it holds it
"""Held by any thread while it draws with matplotlib or typesets a formula with it."""
