"""A display name no X server serves on this machine, for the tests of what runs without a screen."""

from __future__ import annotations

from pathlib import Path


def unserved_display() -> str:
    """``":N"`` for the first ``N`` from 90 with no X server socket in ``/tmp/.X11-unix``."""
    return f":{next(n for n in range(90, 200) if not Path(f'/tmp/.X11-unix/X{n}').exists())}"
