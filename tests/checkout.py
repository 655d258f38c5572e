"""The checkout under test: the folder that holds ``app``, ``core``, ``views`` and ``tests``."""

from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
