"""Starting a command so that Ctrl+C reaches it, however the test run itself was started.

A process started in the background by a shell without job control (``command &`` in a
script, or under ``nohup``) ignores SIGINT, and every process it starts inherits that:
Python then installs no ``KeyboardInterrupt`` handler, and the command rightly ignores
Ctrl+C, as whoever started it in the background asked.  Tests of what Ctrl+C does give the
command SIGINT's default back first, so they test the command and not the way the test run
was started.
"""

from __future__ import annotations

import signal


def ctrl_c_reaches() -> None:
    """``preexec_fn`` for :class:`subprocess.Popen`: SIGINT at its default in the child, before Python
    starts."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def ctrl_c_ignored() -> None:
    """``preexec_fn`` for :class:`subprocess.Popen`: SIGINT ignored in the child, as under ``nohup``."""
    signal.signal(signal.SIGINT, signal.SIG_IGN)
