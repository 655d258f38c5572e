"""Write an RGB image as a PNG file with the standard library alone (zlib, struct)."""

from __future__ import annotations

import struct
import zlib
from pathlib import Path

import numpy as np


def _chunk(kind: bytes, data: bytes) -> bytes:
    return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))


def write_png(path, rgb: np.ndarray) -> None:
    """Save ``rgb``, an (H, W, 3) float image in [0, 1] with row 0 at the top, as 8-bit PNG."""
    data = np.clip(np.asarray(rgb) * 255.0 + 0.5, 0, 255).astype(np.uint8)
    h, w, _ = data.shape
    rows = np.hstack([np.zeros((h, 1), np.uint8), data.reshape(h, w * 3)])  # filter 0 per row
    header = struct.pack(">IIBBBBB", w, h, 8, 2, 0, 0, 0)  # 8-bit RGB, no interlace
    Path(path).write_bytes(
        b"\x89PNG\r\n\x1a\n" + _chunk(b"IHDR", header)
        + _chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)) + _chunk(b"IEND", b"")
    )
