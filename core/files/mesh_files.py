"""Reading triangle meshes from OBJ, STL and PLY files, safely.

:func:`read_mesh` is the ``read_mesh`` that :func:`core.files.scene_file.load` needs
for ``mesh_file`` objects.  The three formats are parsed here with numpy and
the standard library, not by VTK's readers: those crash the process on some
damaged files (an OBJ face naming texture coordinates that do not exist, a
binary PLY shorter than its header says) and run forever on others (an ASCII
PLY that declares two billion vertices).  Here every count a header declares
is checked against the bytes the file really has *before* anything is
allocated, every face index is checked against the vertices, and a file that
disagrees with its own header is refused with a message that says so.

Text (ASCII OBJ, STL and PLY) is parsed :data:`CHUNK_BYTES` at a time, each
chunk's numbers going straight into numpy arrays (:func:`numpy.loadtxt`, with
a line-by-line reader for what it does not take), so that reading a file near
the size limit needs a small multiple of the file's size, not Python objects
for every number.
"""

from __future__ import annotations

import os
import re
from itertools import chain
from typing import NamedTuple

import numpy as np

from core.files import safe_files
from core.files.checked_json import MAX_MAGNITUDE
from core.files.scene_file import MAX_TRIANGLES, degenerate

EXTENSIONS = (".obj", ".stl", ".ply")
MAX_FILE_BYTES = 256_000_000
MAX_HEADER_BYTES = 65_536  # of a PLY header
CHUNK_BYTES = 1_000_000  # of text parsed at a time


class MeshFileError(ValueError):
    """A mesh file that cannot be read; the message names the file and what is wrong."""


def read_mesh(path) -> tuple[np.ndarray, np.ndarray]:
    """Read the triangles of an OBJ, STL or PLY file.

    Polygons are split into triangles (a fan from their first corner);
    points, lines and triangles of zero area are left out.  Vertices are not
    merged, so an STL file (which repeats the corners of every triangle) gives
    three vertices per triangle.  A leading UTF-8 byte-order mark is ignored.

    Parameters
    ----------
    path : str or os.PathLike
        A regular file of at most :data:`MAX_FILE_BYTES` bytes.

    Returns
    -------
    vertices : (N, 3) float64
    triangles : (M, 3) int64, M >= 1, indices into ``vertices``.

    Raises
    ------
    MeshFileError
        A ``ValueError`` naming the file and what is wrong: not found, not a
        regular file, too large, not a supported type, damaged (with the line
        or the count that disagrees), or without triangles.
    """
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in EXTENSIONS:
        raise MeshFileError(
            f"unsupported mesh file type {ext or '(no extension)'!r}: {path}; "
            f"use one of {', '.join(EXTENSIONS)}"
        )
    problem = safe_files.input_file_problem(path, MAX_FILE_BYTES)
    if problem == "file not found":
        raise MeshFileError(f"mesh file not found: {path}")
    if problem is not None:
        raise MeshFileError(f"cannot read mesh file {path}: "
                            f"{problem.removeprefix('cannot read the file: ')}")
    try:
        data = safe_files.read_bytes_limited(path, MAX_FILE_BYTES)
    except OSError as exc:
        raise MeshFileError(f"cannot read mesh file {path}: {exc.strerror or exc}") from None
    if data.startswith(b"\xef\xbb\xbf"):
        data = data[3:]
    parse = {".obj": _parse_obj, ".stl": _parse_stl, ".ply": _parse_ply}[ext]
    try:
        vertices, faces = parse(data)
    except _DamagedError as exc:
        raise MeshFileError(f"cannot read mesh file {path}: {exc}") from None
    except (ValueError, OverflowError, IndexError) as exc:  # a damage no check above foresaw
        raise MeshFileError(f"cannot read mesh file {path}: the file is damaged ({exc})") from None
    if len(faces) and not np.isfinite(vertices).all():
        raise MeshFileError(f"cannot read mesh file {path}: vertices are not finite numbers")
    if len(faces) and np.abs(vertices).max() > MAX_MAGNITUDE:  # before any area: squares would overflow
        raise MeshFileError(f"cannot read mesh file {path}: coordinates must be within "
                            f"±{MAX_MAGNITUDE:,.0f}, found {np.abs(vertices).max():g}")
    zero_area = degenerate(vertices, faces)
    triangles = faces[~zero_area] if zero_area.any() else faces
    if len(triangles) == 0:
        every = ("" if not len(faces) else " (its one triangle has zero area)" if len(faces) == 1
                 else f" (all {len(faces):,} of its triangles have zero area)")
        raise MeshFileError(f"mesh file has no triangles{every}: {path}")
    return vertices, np.ascontiguousarray(triangles)


class _DamagedError(Exception):
    """Raised by the parsers: what is wrong, without the file name."""


def _check_count(n: int, what: str, limit: int = MAX_TRIANGLES) -> None:
    if n > limit:
        raise _DamagedError(f"{n:,} {what}; at most {limit:,} are allowed (a scene holds at most "
                       f"{MAX_TRIANGLES:,} triangles)")


def _fan(polygons: np.ndarray) -> np.ndarray:
    """Triangles of (F, k) polygons of k corners each, each as a fan from its first corner."""
    k = polygons.shape[1]
    if k == 3:
        return polygons.astype(np.int64, copy=False)
    triangles = np.empty((len(polygons), max(k - 2, 0), 3), np.int64)
    for i in range(1, k - 1):
        triangles[:, i - 1] = polygons[:, [0, i, i + 1]]
    return triangles.reshape(-1, 3)


def _fan_ragged(corners: np.ndarray, counts: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Triangles of polygons given as their corners one after another and their sizes.

    Returns the triangles (a fan from each polygon's first corner; polygons of
    fewer than three corners give none) and, for each, the polygon it comes from.
    """
    starts = np.cumsum(counts) - counts  # of each polygon's corners
    per_polygon = np.maximum(counts - 2, 0)
    polygon = np.repeat(np.arange(len(counts)), per_polygon)
    # Triangle t of polygon p, the j-th of p's, has corners 0, j + 1 and j + 2 of p.
    second = np.repeat(starts - (np.cumsum(per_polygon) - per_polygon), per_polygon)
    second += np.arange(1, len(polygon) + 1)
    triangles = np.empty((len(polygon), 3), np.int64)
    triangles[:, 0] = corners[starts[polygon]]
    triangles[:, 1] = corners[second]
    second += 1
    triangles[:, 2] = corners[second]
    return triangles, polygon


def _check_indices(faces: np.ndarray, n_vertices: int, where, base: int = 0) -> None:
    """Refuse a face index outside ``[0, n_vertices)``; ``where(k)`` names face k.

    ``base`` is where the file's own numbering starts (OBJ counts from 1), so
    the message shows the index as the file wrote it.
    """
    bad = np.flatnonzero(((faces < 0) | (faces >= n_vertices)).any(axis=1))
    if len(bad):
        k = int(bad[0])
        raise _DamagedError(f"{where(k)} refers to vertex {_first_bad(faces[k], n_vertices) + base}, "
                       f"but the file has {n_vertices:,} vertices (valid: {base} to "
                       f"{n_vertices - 1 + base})"
                       + (f"; {len(bad) - 1:,} more faces like it" if len(bad) > 1 else ""))


def _first_bad(face: np.ndarray, n: int) -> int:
    return int(next(i for i in face if not 0 <= i < n))


# --- text ----------------------------------------------------------------------


def _text_chunks(data: bytes, start: int = 0):
    """``data[start:]`` as lists of lines, about :data:`CHUNK_BYTES` at a time, and each list's
    first line number (counting from 1 at ``start``).  A chunk ends at a line break (``\\n``, or
    ``\\r`` in a file without ``\\n``), so no line is cut in two."""
    number = 1
    while start < len(data):
        stop = min(start + CHUNK_BYTES, len(data))
        if stop < len(data):
            cut = data.rfind(b"\n", start, stop)
            if cut < 0:  # a line longer than a chunk, or a file of ``\r`` line breaks
                cut = data.find(b"\n", stop)
            stop = len(data) if cut < 0 else cut + 1
        lines = data[start:stop].splitlines()
        yield number, lines
        number += len(lines)
        start = stop


_PLAIN = bytes(range(0x20, 0x7F)) + b"\t\n\x0b\x0c\r"
"""The bytes numpy's reader takes as Python's ``split`` does; it would read others differently (it
decodes the text and splits at Unicode spaces such as ``\\xa0``, ``\\x85``, ``\\x1c``)."""


def _table(lines: list, dtype, usecols=None) -> np.ndarray | None:
    """Whitespace-separated numbers of ``lines`` as an (N, K) array, each line a row of the same K
    numbers (or of at least the columns ``usecols``, the others skipped); None for anything numpy
    does not read as such, which a line-by-line reader then explains."""
    if b"\n".join(lines).translate(None, _PLAIN):
        return None
    try:
        return np.loadtxt(lines, dtype=dtype, comments=None, ndmin=2, usecols=usecols)
    except ValueError:
        return None


class _Ragged(NamedTuple):
    """Lists of whole numbers of varying lengths: their values one after another, and the lengths."""

    values: np.ndarray
    lengths: np.ndarray

    @staticmethod
    def of(lists: list) -> _Ragged:
        """From a list of lists (or of 1-D arrays) of whole numbers."""
        return _Ragged(np.fromiter(chain.from_iterable(lists), np.int64),
                       np.array([len(item) for item in lists], dtype=np.int64))

    @staticmethod
    def joined(parts: list) -> _Ragged:
        """One list of lists from ``parts``, each a :class:`_Ragged` or an (N, k) array of N lists of k."""
        parts = [p if isinstance(p, _Ragged) else _Ragged(p.ravel(), np.full(len(p), p.shape[1]))
                 for p in parts]
        return _Ragged(np.concatenate([p.values for p in parts]),
                       np.concatenate([p.lengths for p in parts]))


# --- OBJ -----------------------------------------------------------------------


_BLANKS = (b" ", b"\t", b"\x0b", b"\x0c", b"\r")  # what ``bytes.split`` splits at, within a line


def _parse_obj(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (``v x y z``) and faces (``f a b c ...``, each ``a``, ``a/t``, ``a//n`` or ``a/t/n``).

    Only the vertex index of each corner is used, so texture and normal
    indices need not exist.  Indices count from 1; negative ones count back
    from the last vertex read so far, as the format says.
    """
    # Room for every line written "v ...", so that the vertices are not copied once more at the end.
    vertices = np.empty((data.count(b"\nv ") + data.startswith(b"v "), 3))
    polygons = []
    n_vertices = n_polygons = 0
    for number, lines in _text_chunks(data):
        chunk_vertices, chunk_polygons = _obj_chunk_fast(lines) or _obj_chunk(lines, number, n_vertices)
        end = n_vertices + len(chunk_vertices)
        if end > len(vertices):  # vertices written otherwise: twice the room
            grown = np.empty((max(2 * len(vertices), end), 3))
            grown[:n_vertices] = vertices[:n_vertices]
            vertices = grown
        vertices[n_vertices:end] = chunk_vertices
        polygons.append(chunk_polygons)
        n_vertices = end
        n_polygons += len(chunk_polygons) if isinstance(chunk_polygons, np.ndarray) else \
            len(chunk_polygons.lengths)  # (a _Ragged is a pair)
        _check_count(n_polygons, "faces")
    vertices = vertices if n_vertices == len(vertices) else vertices[:n_vertices].copy()
    faces, polygon_of = _polygon_triangles(polygons)
    _check_indices(faces, n_vertices, lambda k: f"line {_obj_polygon_line(data, polygon_of(k))}: face",
                   base=1)
    return vertices, faces


def _polygon_triangles(parts: list):
    """Triangles of polygons read in parts (each an (F, k) array or a :class:`_Ragged`), and a
    function giving the polygon that triangle ``t`` comes from."""
    if all(isinstance(p, np.ndarray) for p in parts) and len({p.shape[1] for p in parts if len(p)}) <= 1:
        polygons = np.concatenate([p for p in parts if len(p)] or [np.zeros((0, 3), np.int64)])
        per_polygon = max(polygons.shape[1] - 2, 1)
        return _fan(polygons), lambda t: t // per_polygon
    joined = _Ragged.joined(parts)
    triangles, polygon = _fan_ragged(joined.values, joined.lengths)
    return triangles, lambda t: polygon[t]


def _obj_chunk_fast(lines: list):
    """The common chunk read by numpy: ``v x y z`` lines, and ``f`` lines of positive indices with
    the same number of corners; its vertices and (F, k) polygons, or None for anything else,
    which :func:`_obj_chunk` reads."""
    if _unusual_statements(b"\n" + b"\n".join(lines) + b"\n"):
        return None
    v = [line for line in lines if line.startswith(b"v ")]
    f = [line[2:] for line in lines if line.startswith(b"f ")]
    vertices = _table(v, np.float64, usecols=(1, 2, 3)) if v else np.zeros((0, 3))
    if any(b"/" in line for line in f):  # only the vertex index of each corner counts
        f = re.sub(rb"/\S*", b"", b"\n".join(f)).split(b"\n")
    polygons = _table(f, np.int64) if f else np.zeros((0, 3), np.int64)
    if vertices is None or polygons is None or (polygons.size and polygons.min() < 1):
        return None
    if polygons.shape[1] < 3:  # points and lines have no triangles
        polygons = np.zeros((0, 3), np.int64)
    return vertices, polygons - 1


def _unusual_statements(text: bytes) -> bool:
    """Whether a line of ``text`` (lines between ``\\n``) may be a ``v`` or ``f`` statement not
    written ``v ...`` or ``f ...``: indented, or with a tab after the keyword, or without values."""
    if any(b"\n" + blank in text for blank in _BLANKS):  # indented lines: look at each
        return any(line.split(None, 1)[:1] in ([b"v"], [b"f"]) for line in text.split(b"\n")
                   if line[:1] in b" \t\x0b\x0c\r")
    return any(b"\n" + key + after in text for key in (b"v", b"f") for after in (*_BLANKS[1:], b"\n"))


def _obj_chunk(lines: list, number: int, n_before: int):
    """A chunk of OBJ lines (the first is line ``number``; ``n_before`` vertices came before),
    line by line: its vertices and its polygons (an (F, k) array, or a :class:`_Ragged`)."""
    vertices: list[tuple[float, float, float]] = []
    corners: list[int] = []
    counts: list[int] = []
    for number, line in enumerate(lines, start=number):  # noqa: B020 (numbering goes on from the chunk's)
        parts = line.split()
        if not parts:
            continue
        if parts[0] == b"v":
            try:
                vertices.append((float(parts[1]), float(parts[2]), float(parts[3])))
            except (IndexError, ValueError):
                raise _DamagedError(f"line {number}: a vertex needs three numbers, "
                                    f"got {_shown(line)!r}") from None
        elif parts[0] == b"f":
            face = []
            for corner in parts[1:]:
                try:
                    i = int(corner.split(b"/")[0])
                except ValueError:
                    raise _DamagedError(f"line {number}: face corner {_shown(corner, 30)!r} is not "
                                        "a vertex index") from None
                if i == 0:
                    raise _DamagedError(f"line {number}: vertex index 0 (OBJ counts from 1)")
                face.append(i - 1 if i > 0 else n_before + len(vertices) + i)
            if len(face) >= 3:  # points and lines have no triangles
                corners += face
                counts.append(len(face))
    corners = np.array(corners, dtype=np.int64)
    if len(set(counts)) == 1:  # polygons of one size, such as quads: the cheaper fan
        polygons = corners.reshape(len(counts), counts[0])
    else:
        polygons = _Ragged(corners, np.array(counts, dtype=np.int64))
    return np.array(vertices, dtype=np.float64).reshape(-1, 3), polygons


def _obj_polygon_line(data: bytes, polygon: int) -> int:
    """The line number of the ``polygon``-th face (of three corners or more) of an OBJ file."""
    seen = 0
    for number, lines in _text_chunks(data):
        for k, line in enumerate(lines):
            parts = line.split()
            if parts[:1] == [b"f"] and len(parts) >= 4:
                if seen == polygon:
                    return number + k
                seen += 1
    raise ValueError(f"no face {polygon}")


def _shown(text: bytes, limit: int = 60) -> str:
    """The start of ``text`` (a line or a word of the file) for a message."""
    return text.strip()[:limit].decode("utf-8", errors="replace")


# --- STL -----------------------------------------------------------------------


def _parse_stl(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Binary STL (80-byte header, count, 50 bytes per triangle) or ASCII (``vertex x y z``)."""
    if len(data) >= 84:
        n = int(np.frombuffer(data, "<u4", 1, 80)[0])
        if len(data) == 84 + 50 * n:
            _check_count(n, "triangles declared")
            records = np.frombuffer(data, np.dtype([("normal", "<f4", 3), ("v", "<f4", (3, 3)),
                                                    ("attr", "<u2")]), n, 84)
            vertices = records["v"].reshape(-1, 3).astype(np.float64)
            return vertices, np.arange(3 * n, dtype=np.int64).reshape(-1, 3)
    if not data.lstrip().startswith(b"solid"):
        if len(data) >= 84:
            n = int(np.frombuffer(data, "<u4", 1, 80)[0])
            raise _DamagedError(f"binary STL declares {n:,} triangles, which take {84 + 50 * n:,} "
                           f"bytes, but the file has {len(data):,} bytes")
        raise _DamagedError("neither a binary STL (too short for its header) nor an ASCII one "
                       "(it does not start with 'solid')")
    chunks = []
    for number, lines in _text_chunks(data):
        rows = [(k, line) for k, line in enumerate(lines, start=number)
                if b"vertex" in line and line.split(None, 1)[0] == b"vertex"]
        table = _table([line for _, line in rows], np.float64, usecols=(1, 2, 3)) if rows else \
            np.zeros((0, 3))
        if table is None:  # line by line, to say which one is wrong
            table = np.array([_stl_vertex(line, k) for k, line in rows])
        chunks.append(table)
    vertices = np.concatenate(chunks) if chunks else np.zeros((0, 3))
    if len(vertices) % 3:
        raise _DamagedError(f"ASCII STL has {len(vertices):,} vertices, not three per facet")
    _check_count(len(vertices) // 3, "facets")
    return vertices, np.arange(len(vertices), dtype=np.int64).reshape(-1, 3)


def _stl_vertex(line: bytes, number: int) -> tuple[float, float, float]:
    parts = line.split()
    try:
        return float(parts[1]), float(parts[2]), float(parts[3])
    except (IndexError, ValueError):
        raise _DamagedError(f"line {number}: a vertex needs three numbers") from None


# --- PLY -----------------------------------------------------------------------

_PLY_TYPES = {
    "char": "i1", "int8": "i1", "uchar": "u1", "uint8": "u1",
    "short": "i2", "int16": "i2", "ushort": "u2", "uint16": "u2",
    "int": "i4", "int32": "i4", "uint": "u4", "uint32": "u4",
    "float": "f4", "float32": "f4", "double": "f8", "float64": "f8",
}


def _ply_header(data: bytes):
    """Format, elements ``[(name, count, [(prop, type, count_type or None)])]`` and body offset."""
    end = data.find(b"end_header", 0, MAX_HEADER_BYTES)
    if not data.startswith(b"ply") or end < 0:
        raise _DamagedError("not a PLY file: it must start with 'ply' and its header end with "
                       f"'end_header' within {MAX_HEADER_BYTES:,} bytes")
    newline = data.find(b"\n", end)
    body = len(data) if newline < 0 else newline + 1
    fmt, elements = None, []
    for number, line in enumerate(data[:end].decode("ascii", errors="replace").splitlines(), 1):
        parts = line.split()
        if not parts or parts[0] in ("ply", "comment", "obj_info"):
            continue
        if parts[0] == "format" and len(parts) >= 2:
            fmt = parts[1]
        elif parts[0] == "element" and len(parts) == 3 and parts[2].isdigit():
            elements.append((parts[1], int(parts[2]), []))
        elif parts[0] == "property" and elements and len(parts) == 3 and parts[1] in _PLY_TYPES:
            elements[-1][2].append((parts[2], _PLY_TYPES[parts[1]], None))
        elif (parts[0] == "property" and elements and len(parts) == 5 and parts[1] == "list"
              and parts[2] in _PLY_TYPES and parts[3] in _PLY_TYPES
              and _PLY_TYPES[parts[2]][0] in "iu"):  # a list's length is a whole number
            elements[-1][2].append((parts[4], _PLY_TYPES[parts[3]], _PLY_TYPES[parts[2]]))
        else:
            raise _DamagedError(f"header line {number}: not understood: {line.strip()[:60]!r}")
    if fmt not in ("ascii", "binary_little_endian", "binary_big_endian"):
        raise _DamagedError(f"unknown PLY format {fmt!r}; expected ascii, binary_little_endian or "
                       "binary_big_endian")
    return fmt, elements, body


_PLY_USED = {"vertex": ("x", "y", "z"), "face": ("vertex_indices", "vertex_index")}
"""The properties a mesh is made of; an ASCII file's others are checked, not kept."""


def _parse_ply(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """The ``vertex`` element's x, y, z and the ``face`` element's vertex index lists."""
    fmt, elements, body = _ply_header(data)
    names = [e[0] for e in elements]
    if "vertex" not in names:
        raise _DamagedError("the header declares no 'vertex' element")
    _, n_vertices, vprops = elements[names.index("vertex")]
    if not {"x", "y", "z"} <= {p[0] for p in vprops}:
        raise _DamagedError("the 'vertex' element has no x, y, z properties")
    for name, count, props in elements:
        if name == "face" and not any(p[2] for p in props if p[0] in ("vertex_indices", "vertex_index")):
            raise _DamagedError("the 'face' element has no 'vertex_indices' list")
        _check_count(count, f"{name} elements declared", 3 * MAX_TRIANGLES)
    if fmt == "ascii":
        values = _ply_ascii_elements(data, body, elements, _PLY_USED)
    else:
        values = _ply_binary_elements(data, body, elements, "<" if fmt.endswith("little_endian") else ">")
    vertices = np.stack([values["vertex"][k] for k in "xyz"], axis=1).astype(np.float64, copy=False)
    if "face" not in values:
        return vertices, np.zeros((0, 3), np.int64)
    lists = values["face"].get("vertex_indices", values["face"].get("vertex_index"))
    if isinstance(lists, np.ndarray):  # every face has the same number of corners
        faces = _fan(lists) if lists.shape[1] >= 3 else np.zeros((0, 3), np.int64)
        k = max(lists.shape[1] - 2, 1)
        _check_indices(faces, n_vertices, lambda i: f"face {i // k}")
        return vertices, faces
    faces, face_of = _fan_ragged(lists.values, lists.lengths)
    _check_indices(faces, n_vertices, lambda k: f"face {face_of[k]}")
    return vertices, faces


def _ply_ascii_elements(data: bytes, body: int, elements, used: dict) -> dict:
    """The elements of an ASCII PLY whose data starts at ``body`` (one non-blank line per element,
    read a chunk at a time): element -> property -> values, for the properties ``used[element]``."""
    needed = sum(count for _, count, _ in elements)
    if data.count(b"\n", body) + data.count(b"\r", body) + 1 < needed:  # more lines than there can be
        _ply_too_few_lines(data, body, elements)
    try:
        return _ply_ascii_rows(data, body, elements, used)
    except _DamagedError:
        _ply_too_few_lines(data, body, elements)  # a file shorter than its header says is told so first
        raise


def _ply_ascii_rows(data: bytes, body: int, elements, used: dict) -> dict:
    stream, pending = _ply_rows(data, body), []
    values = {}
    for name, count, props in elements:
        wanted = [p for p in props if p[0] in used.get(name, ())]
        scalars = {prop: np.empty(count) for prop, _, c in wanted if c is None}  # filled batch by batch
        lists: dict[str, list] = {prop: [] for prop, _, c in wanted if c is not None}
        row = 0
        while row < count:
            if not pending:
                pending = next(stream, None)
                if pending is None:
                    raise _DamagedError("the file ends before its elements do")
            batch, pending = pending[:count - row], pending[count - row:]
            kept = _ply_ascii_batch(batch, name, row, props)
            for prop, column in scalars.items():
                column[row:row + len(batch)] = kept[prop]
            for prop, parts in lists.items():
                parts.append(kept[prop])
            row += len(batch)
        values[name] = {**scalars, **{prop: _ply_lists(parts) for prop, parts in lists.items()}}
    return values


def _ply_lists(parts: list):
    """A list property's values from its batches: an (N, k) array if every list has the same
    length k, else a :class:`_Ragged`."""
    if not parts:
        return np.zeros((0, 0), np.int64)
    if any(isinstance(p, _Ragged) for p in parts) or len({p.shape[1] for p in parts}) > 1:
        return _Ragged.joined(parts)
    return parts[0] if len(parts) == 1 else np.concatenate(parts)


def _ply_rows(data: bytes, body: int):
    """The non-blank lines after the header, a chunk's worth at a time."""
    for _, lines in _text_chunks(data, body):
        rows = [line for line in lines if line.strip()]
        if rows:
            yield rows


def _ply_too_few_lines(data: bytes, body: int, elements) -> None:
    """Refuse an ASCII PLY with fewer lines of data than its header declares elements."""
    needed = sum(count for _, count, _ in elements)
    available = sum(len(rows) for rows in _ply_rows(data, body))
    if available < needed:
        declared = ", ".join(f"{count:,} {name}" for name, count, _ in elements)
        raise _DamagedError(f"the header declares {declared} ({needed:,} lines of data), "
                            f"but only {available:,} lines follow it")


def _ply_ascii_batch(rows: list, name: str, first: int, props) -> dict:
    """Rows ``first``, ``first + 1``, ... of element ``name``: property -> values.

    Scalars are float64 arrays; a list property is an (N, k) array when every
    list has k values, else a :class:`_Ragged`.
    """
    if all(c is None for _, _, c in props):
        table = _table(rows, np.float64, usecols=range(len(props)))
        if table is not None:  # columns copied, so that the batch's table is not kept
            return {prop: table[:, i].copy() for i, (prop, _, _) in enumerate(props)}
    elif len(props) == 1:
        table = _table(rows, np.int64)
        if table is not None and (table[:, 0] == table.shape[1] - 1).all():
            return {props[0][0]: table[:, 1:]}
    columns: dict[str, list] = {p[0]: [] for p in props}
    for row, line in enumerate(rows, start=first):  # line by line, to say which one is wrong
        fields = line.split()
        try:
            at = 0
            for prop, _, count_type in props:
                if count_type is None:
                    columns[prop].append(float(fields[at]))
                    at += 1
                else:
                    k = int(fields[at])
                    if k < 0 or at + 1 + k > len(fields):
                        raise ValueError
                    columns[prop].append([int(x) for x in fields[at + 1: at + 1 + k]])
                    at += 1 + k
        except (IndexError, ValueError):
            raise _DamagedError(f"{name} {row}: does not match the header's properties: "
                                f"{_shown(b' '.join(fields))!r}") from None
    return {prop: _Ragged.of(columns[prop]) if c is not None else np.array(columns[prop], dtype=np.float64)
            for prop, _, c in props}


def _ply_binary_elements(data: bytes, offset: int, elements, order: str) -> dict:
    values = {}
    for name, count, props in elements:
        scalar = [(p, order + t) for p, t, c in props if c is None]
        if all(c is None for _, _, c in props):
            dtype = np.dtype(scalar)
            need = count * dtype.itemsize
            if offset + need > len(data):
                raise _DamagedError(f"the header declares {count:,} {name} elements ({need:,} bytes), "
                               f"but only {len(data) - offset:,} bytes are left in the file")
            table = np.frombuffer(data, dtype, count, offset)
            values[name] = {p: table[p] for p, _ in scalar}
            offset += need
        else:
            values[name], offset = _ply_binary_lists(data, offset, name, count, props, order)
    return values


def _ply_binary_lists(data: bytes, offset: int, name: str, count: int, props, order: str):
    """An element with list properties, read row by row with bounds checks."""
    least = sum(np.dtype(c or t).itemsize for _, t, c in props)
    if offset + count * least > len(data):
        raise _DamagedError(f"the header declares {count:,} {name} elements (at least "
                       f"{count * least:,} bytes), but only {len(data) - offset:,} bytes are "
                       "left in the file")
    fixed = _ply_fixed_lists(data, offset, count, props, order)
    if fixed is not None:
        return fixed
    columns: dict[str, list] = {p[0]: [] for p in props}
    for row in range(count):
        for prop, t, c in props:
            dt = np.dtype(order + (c or t))
            if offset + dt.itemsize > len(data):
                raise _DamagedError(f"the header declares {count:,} {name} elements, but the "
                                    f"file ends inside {name} {row}")
            value = np.frombuffer(data, dt, 1, offset)[0]
            offset += dt.itemsize
            if c is None:
                columns[prop].append(value)
                continue
            k = int(value)
            item = np.dtype(order + t)
            if k < 0 or offset + k * item.itemsize > len(data):
                raise _DamagedError(f"the header declares {count:,} {name} elements, but the "
                                    f"file ends inside {name} {row} (a list of {k} values)")
            columns[prop].append(np.frombuffer(data, item, k, offset).astype(np.int64))
            offset += k * item.itemsize
    return {prop: _Ragged.of(columns[prop]) if c is not None else np.array(columns[prop])
            for prop, _, c in props}, offset


def _ply_fixed_lists(data: bytes, offset: int, count: int, props, order: str):
    """The common case read at once: one list property whose lists all have the first one's length."""
    if len(props) != 1 or count == 0:
        return None
    prop, t, c = props[0]
    if offset + np.dtype(c).itemsize > len(data):
        return None
    k = int(np.frombuffer(data, order + c, 1, offset)[0])
    row_bytes = np.dtype(c).itemsize + k * np.dtype(t).itemsize
    if k < 1 or offset + count * row_bytes > len(data):
        return None
    dtype = np.dtype([("k", order + c), ("i", order + t, (k,))])
    table = np.frombuffer(data, dtype, count, offset)
    if not (table["k"] == k).all():
        return None
    return {prop: table["i"].astype(np.int64)}, offset + count * dtype.itemsize
