"""The user's settings that outlive the window, kept by ``QSettings`` in the user's configuration folder.

On Linux that is ``~/.config/Render Explorer/Render Explorer.conf``.  Tests
point ``QSettings`` at a temporary folder (``tests/conftest.py``), so they
never read or change the user's own settings.
"""

from __future__ import annotations

from PySide6.QtCore import QSettings

ORGANIZATION = APPLICATION = "Render Explorer"


def user_settings() -> QSettings:
    """The application's settings (read and written at once; Qt saves them to disk)."""
    return QSettings(ORGANIZATION, APPLICATION)
