"""Ctrl+C on the command line stops a compiled kernel too, within a pixel or a ray.

Python runs its SIGINT handler (``KeyboardInterrupt``) only when the main
thread is between two of its own statements.  While the main thread waits in
a compiled kernel for hours, that never happens.  But the C-level handler
still runs at once, and with :func:`signal.set_wakeup_fd` it writes the
signal's number to a pipe: a small thread waiting on that pipe sets
:data:`core.stopping.EVERY_JOB`, the kernels see their stop flag and return,
and the main thread meets its ``KeyboardInterrupt`` as soon as it is back in
Python (``python -m app`` then exits with status 130, writing nothing).

Where Python cannot raise it, inside a weakref callback or a finalizer (the import system's module
locks have one), it printed "Exception ignored in ... KeyboardInterrupt" with a traceback, and went
on as if Ctrl+C had not been pressed: such an interrupt is delivered to the main thread again
instead, and nothing is printed (:func:`_interrupt_again`).
"""

from __future__ import annotations

import _thread
import os
import signal
import sys
import threading

from core import stopping


def _relay(read_end: int) -> None:
    while True:
        try:
            received = os.read(read_end, 64)
        except InterruptedError:
            continue
        if not received:
            return
        if signal.SIGINT in received:
            stopping.EVERY_JOB.set()


def _interrupt_again(unraisable, print_it=sys.unraisablehook) -> None:
    """``sys.unraisablehook``: an interrupt that came where Python could only print it is raised in the
    main thread again (kernels stopping meanwhile); any other exception is printed as before.

    Another thread asks for it once this hook has returned: asked in the hook, it was raised in the
    hook, and printed as ignored again.  (That thread needs the interpreter's lock, which this one
    holds until it is back in the command's code.)
    """
    if not isinstance(unraisable.exc_value, KeyboardInterrupt):
        print_it(unraisable)
        return
    stopping.EVERY_JOB.set()
    hook_running = threading.Lock()
    hook_running.acquire()

    def once_returned():
        with hook_running:
            _thread.interrupt_main()

    threading.Thread(target=once_returned, name="ctrl-c again", daemon=True).start()
    hook_running.release()


def stop_kernels_on_ctrl_c() -> None:
    """Call once, from the main thread, before a command's work: Ctrl+C then stops kernels too.

    Does nothing when SIGINT is ignored (a command started in the background
    or under ``nohup``): Ctrl+C is then meant not to stop it.
    """
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        return
    read_end, write_end = os.pipe()
    os.set_blocking(write_end, False)  # the C handler must never wait on a full pipe
    signal.set_wakeup_fd(write_end, warn_on_full_buffer=False)
    threading.Thread(target=_relay, args=(read_end,), name="ctrl-c relay", daemon=True).start()
    sys.unraisablehook = _interrupt_again
