"""Typeset formulas kept on disk, so that the window's first frame needs no matplotlib.

The first formula typeset in a process costs about half a second: matplotlib,
its mathtext parser, its Agg backend and the fonts load first.  The window
opens on a lesson step with formulas, so :mod:`views.text.math_view` looks here
before it typesets: each formula drawn at its natural size is kept as a small
``.npy`` file (its RGBA pixels) named after a hash of everything that decides
them: the formula, its size, colour and resolution, and the matplotlib
installed (its location and the stamp of its ``__init__.py``, read without
importing it).  A missing, unreadable or damaged file is simply typeset
again; a cache that cannot be written (read-only home) only costs that time.
The folder is ``$XDG_CACHE_HOME/render-explorer/formulas`` (``~/.cache/...``)
and may be deleted at any time.
"""

from __future__ import annotations

import hashlib
import importlib.util
import io
import os
from functools import lru_cache
from pathlib import Path

import numpy as np

from core.files.safe_files import OutputError, write_atomic


def folder() -> Path:
    """Where the typeset formulas are kept."""
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "render-explorer" / "formulas"


@lru_cache(maxsize=1)
def _matplotlib_stamp() -> str:
    spec = importlib.util.find_spec("matplotlib")
    if spec is None or spec.origin is None:
        return "no matplotlib"
    st = os.stat(spec.origin)
    return f"{spec.origin} {st.st_size} {st.st_mtime_ns}"


def _path(text: str, size_pt: float, color: str, dpi: float) -> Path:
    key = repr((text, float(size_pt), color, float(dpi), _matplotlib_stamp())).encode("utf-8")
    return folder() / f"{hashlib.sha1(key).hexdigest()}.npy"


def load(text: str, size_pt: float, color: str, dpi: float) -> np.ndarray | None:
    """The kept (H, W, 4) uint8 image of ``text`` so typeset; ``None`` if none is kept or it is damaged."""
    try:
        rgba = np.load(_path(text, size_pt, color, dpi), allow_pickle=False)
    except (OSError, ValueError, EOFError):
        return None
    if rgba.dtype != np.uint8 or rgba.ndim != 3 or rgba.shape[2] != 4:
        return None
    return rgba


def store(text: str, size_pt: float, color: str, dpi: float, rgba: np.ndarray) -> None:
    """Keep ``rgba``, the image of ``text`` so typeset, for later processes (written atomically)."""
    buffer = io.BytesIO()
    np.save(buffer, np.ascontiguousarray(rgba), allow_pickle=False)
    path = _path(text, size_pt, color, dpi)
    try:
        path.parent.mkdir(parents=True, exist_ok=True)
        write_atomic(path, buffer.getvalue())
    except (OSError, OutputError):
        pass  # the formula is typeset again next time
