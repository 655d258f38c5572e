"""Compiled kernels kept in the user's cache folder, shared by every checkout and install of the same code.

numba caches a compiled kernel beside its source (``__pycache__``) and checks it
only against the file that defines it.  That has two costs:

- a stale formula: a kernel compiles in the ``register_jitable`` formulas of
  other files (:mod:`core.compiling.jitable`), so after an edit of, say,
  :mod:`core.object_order.rasterization` the cached rasterizer would silently
  keep the old fill rule;
- a second clone, a second virtual environment or a read-only install compiles
  everything again (minutes on a small machine).

So each half's kernel package calls :func:`share_cache` on import, before any of
its kernels is defined, with every file its kernels are made of.  Its kernels are
then cached in one folder named after those files' contents::

    $XDG_CACHE_HOME/render-explorer/kernels/<tag>-<sources' hash>-numba<version>-<cpu>/<sub-folder>

The same code finds the same folder wherever it lives; a changed formula gets a
new folder, so it is never served from an old kernel.  Inside it numba's own
index still checks each kernel's file, signature and CPU features.  numba's own
setting ``NUMBA_CACHE_DIR``, where set, takes the place of the user's cache
folder (the compile benchmark points it at an empty folder).  Where the folder
cannot be written, the kernels are cached in a temporary folder for this process
only: never beside the sources, which may be read-only or shared.
"""

from __future__ import annotations

import hashlib
import os
import shutil
import tempfile
from pathlib import Path

#: Folders kept per kernel group: the newest ones, by when they were last used.
KEEP = 4

_shared: dict[Path, Path] = {}
"""Each kernel package's folder -> the cache folder of its current sources."""
_by_tag: dict[str, Path] = {}
"""Each kernel group's tag -> the same cache folder."""


def cache_root() -> Path:
    """The folder holding every kernel group's cache (``NUMBA_CACHE_DIR`` if set)."""
    if os.environ.get("NUMBA_CACHE_DIR"):
        return Path(os.environ["NUMBA_CACHE_DIR"])
    base = os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache"
    return Path(base) / "render-explorer" / "kernels"


def group_folder_name(tag: str, sources: list[Path]) -> str:
    """The cache folder's name for a kernel group: its tag, its sources' hash, numba's version, the CPU."""
    import numba
    from llvmlite import binding

    digest = hashlib.sha256()
    for path in sources:
        digest.update(path.name.encode() + b"\0" + path.read_bytes() + b"\0")
    return f"{tag}-{digest.hexdigest()[:16]}-numba{numba.__version__}-{binding.get_host_cpu_name()}"


def share_cache(kernel_dir: Path, sources: list[Path], tag: str) -> Path:
    """Cache the kernels defined below ``kernel_dir`` in the shared folder of ``sources``; returns it.

    Parameters
    ----------
    kernel_dir : the kernel package's folder (its sub-folders are included).
    sources : every file whose code ends up inside those kernels.
    tag : the kernel group's short name (``raster``, ``trace``).
    """
    _install_locator()
    root = cache_root()
    folder = root / group_folder_name(tag, sources)
    try:
        folder.mkdir(parents=True, exist_ok=True)
        os.utime(folder)  # last used now: the newest folders are the ones kept
        _forget_old(root, tag, keep=folder)
    except OSError:
        folder = Path(tempfile.mkdtemp(prefix=f"render-explorer-{tag}-"))
    _shared[kernel_dir.resolve()] = folder
    _by_tag[tag] = folder
    return folder


def compiled_marker(tag: str, name: str) -> Path:
    """The file that says the warm-up ``name`` of kernel group ``tag`` has been compiled into the
    shared cache (its kernels load from disk in a second or two); the group must be imported."""
    return _by_tag[tag] / f"{name}.compiled"


def _forget_old(root: Path, tag: str, keep: Path) -> None:
    """Delete all but the :data:`KEEP` most recently used folders of ``tag`` (older code's kernels)."""
    folders = sorted((f for f in root.glob(f"{tag}-*") if f.is_dir() and f != keep),
                     key=lambda f: f.stat().st_mtime, reverse=True)
    for old in folders[KEEP - 1:]:
        shutil.rmtree(old, ignore_errors=True)


def folder_for(py_file: str) -> Path | None:
    """Where the kernels defined in ``py_file`` are cached, or None if it is no shared kernel's file."""
    path = Path(py_file).resolve()
    for kernel_dir, folder in _shared.items():
        if path.is_relative_to(kernel_dir):
            return folder / path.parent.relative_to(kernel_dir)
    return None


_installed = False


def _install_locator() -> None:
    """Put :class:`SharedLocator` before numba's own locators (once)."""
    global _installed
    if _installed:
        return
    from numba.core import caching

    impl = getattr(caching, "CacheImpl", None) or caching._CacheImpl  # renamed in numba 0.68
    impl._locator_classes.insert(0, _shared_locator_class())
    _installed = True


def _shared_locator_class():
    from numba.core.caching import _CacheLocator

    class SharedLocator(_CacheLocator):
        """numba's cache locator for the shared kernels: the folder of :func:`folder_for`.

        The source stamp is the defining file's content hash (not its time, as numba's own
        locators had it before 0.68), so a copy of the same file elsewhere finds the same kernels.
        """

        def __init__(self, py_func, py_file):
            self._lineno = py_func.__code__.co_firstlineno
            self._stamp = hashlib.sha256(Path(py_file).read_bytes()).hexdigest()
            self._cache_path = str(folder_for(py_file))

        def get_cache_path(self):
            return self._cache_path

        def get_source_stamp(self):
            return self._stamp

        def get_disambiguator(self):
            return str(self._lineno)

        @classmethod
        def from_function(cls, py_func, py_file):
            if folder_for(py_file) is None:
                return None
            self = cls(py_func, py_file)
            try:
                self.ensure_cache_path()
            except OSError:  # not writable after all: this process keeps its kernels apart
                self._cache_path = tempfile.mkdtemp(prefix="render-explorer-kernels-")
            return self

    return SharedLocator
