"""The files a sweep writes: ``cost.csv``, ``cost.png`` and ``cost.svg``.

Each file is written to a temporary file in its own folder and then renamed
into place, so a reader never sees half a file and an interrupted write
leaves the old one.
"""

from __future__ import annotations

import csv
import io
import os
import tempfile
from pathlib import Path
from typing import TYPE_CHECKING

from core.accuracy.sweep import CSV_COLUMNS, Row

if TYPE_CHECKING:  # matplotlib loads with the first figure, not with this module
    from matplotlib.figure import Figure


def _umask() -> int:
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


#: Permissions of a written file: as ``open`` would give it (mkstemp makes it private).
_MODE = 0o666 & ~_umask()


def write_atomically(path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and a rename."""
    path = Path(path)
    fd, tmp = tempfile.mkstemp(dir=path.parent, prefix=f".{path.name}.", suffix=".tmp")
    try:
        with os.fdopen(fd, "wb") as f:
            f.write(data)
        os.chmod(tmp, _MODE)
        os.replace(tmp, path)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def csv_text(rows: list[Row]) -> str:
    """The rows as CSV with the header :data:`core.accuracy.sweep.CSV_COLUMNS`; ``knee`` is 1 or 0."""
    out = io.StringIO()
    writer = csv.writer(out, lineterminator="\n")
    writer.writerow(CSV_COLUMNS)
    for r in rows:
        values = []
        for name in CSV_COLUMNS:
            v = getattr(r, name)
            values.append(int(v) if isinstance(v, bool) else "" if v is None else
                          f"{v:.6g}" if isinstance(v, float) else v)
        writer.writerow(values)
    return out.getvalue()


def write_csv(rows: list[Row], path) -> None:
    """Write ``cost.csv`` atomically."""
    write_atomically(path, csv_text(rows).encode("utf-8"))


def save_figure(figure: Figure, path, dpi: int = 120) -> None:
    """Save ``figure`` atomically; the format follows the suffix (``.png``, ``.svg``)."""
    buffer = io.BytesIO()
    figure.savefig(buffer, format=Path(path).suffix.lstrip(".").lower(), dpi=dpi)
    write_atomically(path, buffer.getvalue())
