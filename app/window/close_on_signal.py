"""Ctrl+C in the terminal, SIGTERM, or the terminal closing, closes the window as its close button does.

The window is opened from a terminal (the README's first command), where Ctrl+C is how a program
is stopped.  Qt's event loop runs in C++, so Python's handler of a signal only runs when some
Python code next does, and the ``KeyboardInterrupt`` it raised came out of whatever slot that
was: a traceback on the terminal, and the window stayed open.  SIGTERM ended the process on the
spot, so the session (:mod:`app.window.session`: the scene and the observer) was not remembered,
and the background compile it started (:mod:`app.window.background_compile`) ran on without it;
so did SIGHUP, which the program gets when the terminal it was started from is closed.

:class:`CloseOnSignal` makes each of them close the window instead, at once: the signal's number is
written to a socket that the event loop watches (:func:`signal.set_wakeup_fd`), which wakes it,
and the window closes as if its close button were pressed (unsaved edits are asked about first).
A second signal while it closes (say, that question is still open) ends the program at once.
The program then ends with the status of a program stopped by that signal, ``128 + signum``.
A signal the program was started to ignore (Ctrl+C under ``nohup``, or after ``&`` in a script)
stays ignored.
"""

from __future__ import annotations

import os
import signal
import socket
import sys

from PySide6.QtCore import QObject, QSocketNotifier

SIGNALS = (signal.SIGINT, signal.SIGTERM, signal.SIGHUP)


class CloseOnSignal(QObject):
    """While it lives, Ctrl+C, SIGTERM and SIGHUP close ``window`` (see the module).

    ``received``: the signal that closed the window, or ``None``.
    """

    def __init__(self, window):
        super().__init__(window)
        self.window = window
        self.received: int | None = None
        self._closing = False
        self._woken, self._wake = socket.socketpair()
        for end in (self._woken, self._wake):
            end.setblocking(False)
        signal.set_wakeup_fd(self._wake.fileno(), warn_on_full_buffer=False)
        self._taken = [signum for signum in SIGNALS if signal.getsignal(signum) is not signal.SIG_IGN]
        for signum in self._taken:
            signal.signal(signum, self._received)
        self._notifier = QSocketNotifier(self._woken.fileno(), QSocketNotifier.Type.Read, self)
        self._notifier.activated.connect(self._close)

    def _received(self, signum, frame) -> None:
        if self._closing:  # asked again while the window closes: end now
            sys.stderr.flush()
            os._exit(128 + signum)
        self.received = signum

    def _close(self) -> None:
        while True:  # the signals' bytes; their Python handler has run before this slot
            try:
                if not self._woken.recv(64):
                    break
            except BlockingIOError:
                break
        if self.received is None or self._closing:
            return
        self._closing = True
        try:
            self.window.close()
        finally:
            self._closing = False
        if self.window.isVisible():  # the user chose to keep it open
            self.received = None

    def release(self) -> None:
        """Give the signals back to Python's defaults (the window has closed)."""
        signal.set_wakeup_fd(-1)
        for signum in self._taken:
            signal.signal(signum, signal.default_int_handler if signum == signal.SIGINT else signal.SIG_DFL)
        self._notifier.setEnabled(False)
        self._woken.close()
        self._wake.close()

