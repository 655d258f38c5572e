"""Is there a screen to open the window on?  Asked before Qt is, which would abort the program.

Without a display (an ssh session without ``-X``, a server's console) Qt's X11 plugin cannot
connect, prints a hint about a library that is not the problem (``xcb-cursor0 ... is needed``)
and aborts the process (status 134, a core dump).  :func:`why_no_display` connects to the X server
first, the way Qt would (``xcb_connect``), and says in words what is wrong instead; so do the
benchmarks that open the window (:func:`require_display`).
"""

from __future__ import annotations

import ctypes
import os

from app.usage import UsageError

#: What to do about it, said after what is wrong.
ADVICE = ("run it in a desktop session, over `ssh -X`, or on a virtual screen (`xvfb-run -a python -m app`); "
          "the command-line commands need no screen (`python -m app --help`)")


def why_no_display() -> str | None:
    """What keeps the window from opening (``None``: nothing known), from this process's environment,
    and what to do about it: ``python -m app``'s error."""
    problem = display_problem()
    return None if problem is None else f"no screen to open the window on: {problem}; {ADVICE}"


def require_display(command: str) -> None:
    """Raise :class:`~app.usage.UsageError` where a window cannot open: for the benchmarks that open
    windows (``command``: how the user called one), before anything is timed."""
    problem = display_problem()
    if problem is not None:
        raise UsageError(f"{command} needs a screen to open the window on: {problem}; "
                         "run it under xvfb-run -a")


def display_problem() -> str | None:
    """Why no window can open on this process's display, in a few words (``None``: nothing known).

    A platform chosen with ``QT_QPA_PLATFORM``, or a Wayland session, is left to Qt.
    """
    if os.environ.get("QT_QPA_PLATFORM") or os.environ.get("WAYLAND_DISPLAY"):
        return None
    display = os.environ.get("DISPLAY", "")
    if not display:
        return "DISPLAY is not set"
    if not _x_server_answers(display):
        return f"no X server answers on display {display!r} (DISPLAY)"
    return None


def _x_server_answers(display: str) -> bool:
    """Whether an X server accepts a connection on ``display`` (true where libxcb is not found)."""
    try:
        xcb = ctypes.CDLL("libxcb.so.1")  # by its name: find_library would run ldconfig at every start
    except OSError:
        return True
    xcb.xcb_connect.restype = ctypes.c_void_p
    xcb.xcb_connect.argtypes = [ctypes.c_char_p, ctypes.c_void_p]
    xcb.xcb_connection_has_error.argtypes = [ctypes.c_void_p]
    xcb.xcb_disconnect.argtypes = [ctypes.c_void_p]
    connection = xcb.xcb_connect(display.encode(), None)
    try:
        return xcb.xcb_connection_has_error(connection) == 0
    finally:
        xcb.xcb_disconnect(connection)
