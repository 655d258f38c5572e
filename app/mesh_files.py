"""Reading triangle meshes from OBJ, STL and PLY files, safely.

:func:`read_mesh` is the ``read_mesh`` that :func:`core.scene_file.load` needs
for ``mesh_file`` objects.  The three formats are parsed here with numpy and
the standard library, not by VTK's readers: those crash the process on some
damaged files (an OBJ face naming texture coordinates that do not exist, a
binary PLY shorter than its header says) and run forever on others (an ASCII
PLY that declares two billion vertices).  Here every count a header declares
is checked against the bytes the file really has *before* anything is
allocated, every face index is checked against the vertices, and a file that
disagrees with its own header is refused with a message that says so.
"""

from __future__ import annotations

import os

import numpy as np

from core import safe_files
from core.scene_file import MAX_TRIANGLES, degenerate

EXTENSIONS = (".obj", ".stl", ".ply")
MAX_FILE_BYTES = 256_000_000
MAX_HEADER_BYTES = 65_536  # of a PLY header


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
    triangles = faces[~degenerate(vertices, faces)] if len(faces) else faces
    if len(triangles) == 0:
        raise MeshFileError(f"mesh file has no triangles: {path}")
    return vertices, np.ascontiguousarray(triangles)


class _DamagedError(Exception):
    """Raised by the parsers: what is wrong, without the file name."""


def _check_count(n: int, what: str, limit: int = MAX_TRIANGLES) -> None:
    if n > limit:
        raise _DamagedError(f"{n:,} {what}; at most {limit:,} are allowed (a scene holds at most "
                       f"{MAX_TRIANGLES:,} triangles)")


def _fan(polygons) -> np.ndarray:
    """Triangles of polygons (lists of vertex indices), each as a fan from its first corner."""
    if isinstance(polygons, np.ndarray):  # (F, k) polygons of k corners each
        k = polygons.shape[1]
        fans = [polygons[:, [0, i, i + 1]] for i in range(1, k - 1)]
        return np.stack(fans, axis=1).reshape(-1, 3).astype(np.int64) if fans else \
            np.zeros((0, 3), np.int64)
    tris = [(p[0], p[i], p[i + 1]) for p in polygons for i in range(1, len(p) - 1)]
    return np.array(tris, dtype=np.int64).reshape(-1, 3)


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


# --- OBJ -----------------------------------------------------------------------


def _parse_obj(data: bytes) -> tuple[np.ndarray, np.ndarray]:
    """Vertices (``v x y z``) and faces (``f a b c ...``, each ``a``, ``a/t``, ``a//n`` or ``a/t/n``).

    Only the vertex index of each corner is used, so texture and normal
    indices need not exist.  Indices count from 1; negative ones count back
    from the last vertex read so far, as the format says.
    """
    text = data.decode("utf-8", errors="replace")
    fast = _parse_obj_triangles(text)
    if fast is not None:
        return fast
    vertices: list[tuple[float, float, float]] = []
    polygons: list[list[int]] = []
    lines: list[int] = []
    for number, line in enumerate(text.splitlines(), start=1):
        parts = line.split()
        if not parts:
            continue
        if parts[0] == "v":
            try:
                vertices.append((float(parts[1]), float(parts[2]), float(parts[3])))
            except (IndexError, ValueError):
                raise _DamagedError(f"line {number}: a vertex needs three numbers, "
                                    f"got {line.strip()[:60]!r}") from None
        elif parts[0] == "f":
            corners = []
            for corner in parts[1:]:
                try:
                    i = int(corner.split("/")[0])
                except ValueError:
                    raise _DamagedError(f"line {number}: face corner {corner[:30]!r} is not a vertex "
                                   "index") from None
                if i == 0:
                    raise _DamagedError(f"line {number}: vertex index 0 (OBJ counts from 1)")
                corners.append(i - 1 if i > 0 else len(vertices) + i)
            if len(corners) >= 3:
                polygons.append(corners)
                lines.append(number)
            _check_count(len(polygons), "faces")
    faces = _fan(polygons)
    corner_line = np.repeat(lines, [len(p) - 2 for p in polygons]) if polygons else []
    _check_indices(faces, len(vertices), lambda k: f"line {corner_line[k]}: face", base=1)
    return np.array(vertices, dtype=np.float64).reshape(-1, 3), faces


def _parse_obj_triangles(text: str):
    """The common OBJ read with numpy: ``v x y z`` lines and triangles with positive indices.

    None when the file is anything else (or damaged), so that the line-by-line
    reader handles it and names the line that is wrong.
    """
    rows = [line.split() for line in text.splitlines() if line.startswith(("v ", "f "))]
    v_rows = [r[1:] for r in rows if r[0] == "v"]
    f_rows = [r[1:] for r in rows if r[0] == "f"]
    if len(f_rows) > MAX_TRIANGLES or any(len(r) != 3 for r in v_rows) or any(
            len(r) != 3 for r in f_rows):
        return None
    try:  # Python's float() and int() per token: far faster than numpy's string parsing
        vertices = np.array([float(c) for r in v_rows for c in r], dtype=np.float64).reshape(-1, 3)
        faces = np.array([int(c.split("/")[0]) for r in f_rows for c in r], dtype=np.int64)
    except ValueError:
        return None
    faces = faces.reshape(-1, 3) - 1
    if faces.size and not ((faces >= 0) & (faces < len(vertices))).all():
        return None
    return vertices, faces


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
    vertices = []
    for number, line in enumerate(data.decode("utf-8", errors="replace").splitlines(), start=1):
        parts = line.split()
        if parts[:1] == ["vertex"]:
            try:
                vertices.append((float(parts[1]), float(parts[2]), float(parts[3])))
            except (IndexError, ValueError):
                raise _DamagedError(f"line {number}: a vertex needs three numbers") from None
    if len(vertices) % 3:
        raise _DamagedError(f"ASCII STL has {len(vertices):,} vertices, not three per facet")
    _check_count(len(vertices) // 3, "facets")
    return (np.array(vertices, dtype=np.float64).reshape(-1, 3),
            np.arange(len(vertices), dtype=np.int64).reshape(-1, 3))


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
        values = _ply_ascii_elements(data[body:], elements)
    else:
        values = _ply_binary_elements(data, body, elements, "<" if fmt.endswith("little_endian") else ">")
    vertices = np.stack([values["vertex"][k] for k in "xyz"], axis=1).astype(np.float64)
    if "face" not in values:
        return vertices, np.zeros((0, 3), np.int64)
    lists = values["face"].get("vertex_indices", values["face"].get("vertex_index"))
    if isinstance(lists, np.ndarray):  # every face has the same number of corners
        faces = _fan(lists) if lists.shape[1] >= 3 else np.zeros((0, 3), np.int64)
        k = max(lists.shape[1] - 2, 1)
        _check_indices(faces, n_vertices, lambda i: f"face {i // k}")
        return vertices, faces
    faces = _fan([list(p) for p in lists if len(p) >= 3])
    first_face = np.repeat(np.flatnonzero([len(p) >= 3 for p in lists]),
                           [len(p) - 2 for p in lists if len(p) >= 3]) if len(faces) else []
    _check_indices(faces, n_vertices, lambda k: f"face {first_face[k]}")
    return vertices, faces


def _ply_ascii_elements(body: bytes, elements) -> dict:
    lines = body.split(b"\n")
    needed = sum(count for _, count, _ in elements)
    available = sum(1 for line in lines if line.strip())
    if available < needed:
        declared = ", ".join(f"{count:,} {name}" for name, count, _ in elements)
        raise _DamagedError(f"the header declares {declared} ({needed:,} lines of data), "
                       f"but only {available:,} lines follow it")
    rows = (line for line in lines if line.strip())
    values = {}
    for name, count, props in elements:
        columns: dict[str, list] = {p[0]: [] for p in props}
        for row in range(count):
            fields = next(rows).split()
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
                text = b" ".join(fields).decode("ascii", "replace")[:60]
                raise _DamagedError(f"{name} {row}: does not match the header's properties: "
                               f"{text!r}") from None
        values[name] = {k: (v if any(p[0] == k and p[2] for p in props) else np.array(v))
                        for k, v in columns.items()}
    return values


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
            columns[prop].append(np.frombuffer(data, item, k, offset).astype(np.int64).tolist())
            offset += k * item.itemsize
    return {k: (v if any(p[0] == k and p[2] for p in props) else np.array(v))
            for k, v in columns.items()}, offset


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
