"""``python -m app``: the Render Explorer command line (see :mod:`app.cli`)."""

import sys

try:
    from app.cli import main
    from app.freed_memory import keep_freed_memory

    keep_freed_memory()  # process-wide: the memory of one frame's arrays is reused by the next
    status = main()
except KeyboardInterrupt:  # Ctrl+C while the program loads, before the command's own handler
    print("python -m app: interrupted; no output file was written or changed", file=sys.stderr)
    status = 130
sys.exit(status)
