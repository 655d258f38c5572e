"""Compiled (numba) versions of the hot loops.

Every kernel here is ``@njit(cache=True, nogil=True)``: compiled once and
cached on disk, and it releases the GIL so a worker thread really runs in
parallel with the GUI.  Each kernel has a plain numpy reference in the module
named after its lecture concept, and a test checks that both agree.
"""
