"""``python -m app``: the Render Explorer command line (see :mod:`app.cli`)."""

import sys

from app.cli import main
from app.freed_memory import keep_freed_memory

keep_freed_memory()  # process-wide: the memory of one frame's arrays is reused by the next
sys.exit(main())
