"""Files read and written safely: inputs that end, outputs that are never half-written.

Reading: a scene or mesh path must name a *regular* file no larger than a
stated limit, checked with ``os.stat`` before the file is opened, so a FIFO
(which would block forever on open), a device such as ``/dev/zero`` (which
never ends) or a huge file is refused with a message instead of hanging the
program or filling its memory.

Writing: :func:`write_atomic` writes to a temporary file in the target's own
folder, checks that the file holds every byte (its size), and renames it over
the target (``os.replace``) only then.  A write that fails part-way (a full disk, a file-size limit, Ctrl-C)
removes the temporary file and leaves the old target byte-for-byte as it was.
The rename is atomic because both names are in the same folder, hence on the
same file system.
"""

from __future__ import annotations

import contextlib
import errno
import os
import stat
import tempfile
from pathlib import Path


class OutputError(OSError):
    """An output file that could not be written; the message names the file."""


def input_file_problem(path, limit_bytes: int) -> str | None:
    """Why ``path`` cannot be read as an input file, or None if it can.

    Parameters
    ----------
    path : str or os.PathLike
    limit_bytes : largest size accepted, in bytes.

    Returns
    -------
    str or None
        ``"file not found"``, ``"not a regular file (a FIFO, device or
        folder)"``, ``"too large: ... (the limit is ...)"``, or the reason the
        file system gives.
    """
    try:
        info = os.stat(path)
    except FileNotFoundError:
        return "file not found"
    except OSError as exc:
        return f"cannot read the file: {exc.strerror or exc}"
    if stat.S_ISDIR(info.st_mode):
        return "cannot read the file: it is a folder"
    if not stat.S_ISREG(info.st_mode):
        return ("cannot read the file: not a regular file (a FIFO, device or socket may "
                "block or never end)")
    if info.st_size > limit_bytes:
        return f"too large: {info.st_size:,} bytes (the limit is {limit_bytes:,})"
    return None


def read_bytes_limited(path, limit_bytes: int) -> bytes:
    """The bytes of a regular file, reading at most ``limit_bytes + 1`` of them.

    Call :func:`input_file_problem` first; reading is bounded here as well in
    case the file grew in between.  Raises ``OSError`` (with a reason) if it
    cannot be read or is longer than the limit.
    """
    with open(path, "rb") as f:
        data = f.read(limit_bytes + 1)
    if len(data) > limit_bytes:
        raise OSError(f"too large: more than {limit_bytes:,} bytes")
    return data


def _mode_for_new_file() -> int:
    """Permission bits a newly created file gets under the current umask."""
    umask = os.umask(0)
    os.umask(umask)
    return 0o666 & ~umask


def _stage(path: Path, data: bytes) -> str:
    """Write ``data`` to a new temporary file beside ``path``; its name."""
    try:
        mode = stat.S_IMODE(os.stat(path).st_mode)
    except OSError:
        mode = _mode_for_new_file()
    fd, temp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".part")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
            f.flush()
            os.fsync(f.fileno())
            written = os.fstat(f.fileno()).st_size
            if written != len(data):  # never trust a write that did not raise
                raise OSError(errno.EIO, f"only {written:,} of {len(data):,} bytes were written")
        os.chmod(temp, mode)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(temp)
        raise
    return temp


def write_atomic_all(contents: dict) -> None:
    """Write ``{path: bytes}``: every file is either left as it was or replaced whole.

    All files are first written to temporary files; only when every one of
    them is complete are they renamed over their targets.  So a failure (or
    Ctrl-C) while writing leaves *all* the old files unchanged.

    Raises
    ------
    OutputError
        Naming the file that failed and the reason; no temporary file is left.
    """
    staged: list[tuple[str, Path]] = []
    try:
        for path, data in contents.items():
            path = Path(path)
            try:
                staged.append((_stage(path, data), path))
            except OSError as exc:
                raise OutputError(f"cannot write {path}: {exc.strerror or exc}; "
                                  "any previous file there is unchanged") from None
        while staged:
            temp, path = staged[0]
            try:
                os.replace(temp, path)
            except OSError as exc:
                raise OutputError(f"cannot write {path}: {exc.strerror or exc}") from None
            staged.pop(0)
    finally:
        for temp, _ in staged:
            with contextlib.suppress(OSError):
                os.unlink(temp)


def write_atomic(path, data: bytes) -> None:
    """Write ``data`` to ``path`` so that ``path`` is either the old file or the whole new one.

    Raises
    ------
    OutputError
        Naming ``path`` and the reason, if the write fails (the old file is
        then unchanged and no temporary file is left behind).
    """
    write_atomic_all({path: data})
