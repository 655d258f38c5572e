"""The files a sweep writes: ``cost.csv``, ``cost.png`` and ``cost.svg``.

Each file is written to a temporary file in its own folder, checked complete
and then renamed into place (:mod:`core.files.safe_files`), so a reader never sees
half a file and a failed or interrupted write leaves the old one.
"""

from __future__ import annotations

import csv
import io
from pathlib import Path
from typing import TYPE_CHECKING

from core.accuracy.sweep import CSV_COLUMNS, Row
from core.files.safe_files import write_atomic
from views.matplotlib_lock import MATPLOTLIB

if TYPE_CHECKING:  # matplotlib loads with the first figure, not with this module
    from matplotlib.figure import Figure


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
    """Write ``cost.csv`` atomically; a failure raises :class:`core.files.safe_files.OutputError`."""
    write_atomic(path, csv_text(rows).encode("utf-8"))


def figure_bytes(figure: Figure, suffix: str, dpi: int = 120) -> bytes:
    """``figure`` as a file's bytes; the format follows ``suffix`` (``".png"``, ``".svg"``)."""
    buffer = io.BytesIO()
    with MATPLOTLIB:  # saving draws the figure again
        figure.savefig(buffer, format=suffix.lstrip(".").lower(), dpi=dpi)
    return buffer.getvalue()


def save_figure(figure: Figure, path, dpi: int = 120) -> None:
    """Save ``figure`` atomically; the format follows the suffix (``.png``, ``.svg``)."""
    write_atomic(path, figure_bytes(figure, Path(path).suffix, dpi))
