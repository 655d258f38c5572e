"""The checkout under test: the folder that holds ``app``, ``core``, ``views`` and ``tests``."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

TYPESETTING = '''
def typesetting():
    """Whether this process has typeset a formula: it started the typesetting process (its child for
    as long as it lives), or loaded matplotlib to typeset one itself."""
    import os
    import sys

    for pid in filter(str.isdigit, os.listdir("/proc")):
        try:
            with open(f"/proc/{pid}/stat") as stat, open(f"/proc/{pid}/cmdline", "rb") as cmdline:
                parent, command = int(stat.read().rsplit(")", 1)[1].split()[1]), cmdline.read()
        except (OSError, ValueError, IndexError):  # ended meanwhile
            continue
        if parent == os.getpid() and b"views.text.typesetting_process" in command:
            return True
    return "matplotlib" in sys.modules
'''
"""Source of ``typesetting()``, for the scripts tests run in processes of their own."""
