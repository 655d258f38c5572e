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
and may be deleted at any time.  It never grows past :data:`MAX_BYTES`: worked
math with the picked pixel's numbers makes new formulas all the time, so the
files used longest ago (a formula shown again is marked used) are deleted
first.
"""

from __future__ import annotations

import contextlib
import hashlib
import importlib.util
import io
import os
import threading
from functools import lru_cache
from pathlib import Path

import numpy as np

from core.files.safe_files import OutputError, write_atomic

MAX_BYTES = 64 * 2**20
"""The folder is trimmed to three quarters of this when it grows past it (about 3000 formulas)."""
CHECK_EVERY = 200
"""The folder's size is read at a process's first store, then after every this many stores."""
_stores = {"count": 0}
_trimming = threading.Lock()


def folder() -> Path:
    """Where the typeset formulas are kept."""
    return _folder(os.environ.get("XDG_CACHE_HOME", ""))


@lru_cache(maxsize=4)
def _folder(cache_home: str) -> Path:  # each formula looked up asks: worked out once per cache home
    return Path(cache_home or Path.home() / ".cache") / "render-explorer" / "formulas"


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
    with contextlib.suppress(OSError):
        os.utime(_path(text, size_pt, color, dpi))  # used now: trimmed last
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
        return  # the formula is typeset again next time
    with _trimming:
        check = _stores["count"] % CHECK_EVERY == 0
        _stores["count"] += 1
        if check:
            trim(path.parent)


def trim(where: Path, most: int = MAX_BYTES) -> None:
    """Delete the files of ``where`` used longest ago until they take at most ¾ of ``most`` bytes,
    if they take more than ``most``."""
    try:
        files = [(stat.st_mtime_ns, stat.st_size, entry.path)
                 for entry in os.scandir(where) if entry.name.endswith(".npy") for stat in [entry.stat()]]
    except OSError:
        return
    total = sum(size for _, size, _ in files)
    if total <= most:
        return
    for _, size, path in sorted(files):
        if total <= most * 3 // 4:
            break
        try:
            os.remove(path)
        except OSError:
            continue  # gone already (another process trims too)
        total -= size
