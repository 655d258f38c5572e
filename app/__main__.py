"""``python -m app``: the Render Explorer command line (see :mod:`app.cli`).

Ctrl+C while the modules load is held until they are loaded: numpy turns an
interrupt inside its C extension's import into an ``ImportError``, which would
end the program with a traceback and status 1 instead of the one line and 130.

A terminal whose encoding lacks a character of the lecture's notation gets it spelled out
(:mod:`app.process.terminal_text`) rather than a ``UnicodeEncodeError``.

A reader that stops reading (``python -m app pixel ... | head -3``) ends the
program quietly with status 141, as the shell's own tools end by SIGPIPE.
"""

import os
import signal
import sys

_pressed = []
_held = signal.getsignal(signal.SIGINT) is signal.default_int_handler
if _held:
    signal.signal(signal.SIGINT, lambda signum, frame: _pressed.append(signum))
try:
    from app.cli import interrupted, main
    from app.process.freed_memory import keep_freed_memory
    from app.process.terminal_text import spell_out_what_the_terminal_cannot_show
    from app.process.thread_waits import let_waiting_threads_sleep
finally:
    if _held:
        signal.signal(signal.SIGINT, signal.default_int_handler)
if _pressed:
    interrupted()
try:
    spell_out_what_the_terminal_cannot_show()  # a terminal without "²" or "Δ" gets "^2" and "Delta"
    keep_freed_memory()  # process-wide: the memory of one frame's arrays is reused by the next
    let_waiting_threads_sleep()  # process-wide, before numba loads OpenMP: no core spent spinning
    status = main()
except KeyboardInterrupt:  # while the command line is read, before the command's own handler
    interrupted()
except BrokenPipeError:  # nobody reads the output any more: nothing left to say, nowhere to say it
    os.dup2(os.open(os.devnull, os.O_WRONLY), sys.stdout.fileno())  # no second error at exit's flush
    status = 128 + signal.SIGPIPE
sys.exit(status)
