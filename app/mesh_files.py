"""Reading triangle meshes from OBJ, STL and PLY files (with pyvista).

:func:`read_mesh` is the ``read_mesh`` that :func:`core.scene_file.load` needs
for ``mesh_file`` objects.  pyvista is imported only when a file is read, so
importing this module is cheap.
"""

from __future__ import annotations

import logging
import os
import warnings
from contextlib import nullcontext

import numpy as np

from core.scene_file import degenerate

EXTENSIONS = (".obj", ".stl", ".ply")


class _Collect(logging.Filter):
    """Swallows the VTK errors pyvista sends to the root logger, keeping their text."""

    def __init__(self):
        super().__init__()
        self.messages: list[str] = []

    def filter(self, record: logging.LogRecord) -> bool:
        self.messages.append(record.getMessage())
        return False


def read_mesh(path) -> tuple[np.ndarray, np.ndarray]:
    """Read the triangles of an OBJ, STL or PLY file.

    Polygons are split into triangles; points, lines and triangles of zero
    area are left out.  Vertices are not merged, so an STL file (which repeats
    the corners of every triangle) gives three vertices per triangle.

    Parameters
    ----------
    path : str or os.PathLike

    Returns
    -------
    vertices : (N, 3) float64
    triangles : (M, 3) int64, M >= 1, indices into ``vertices``.

    Raises
    ------
    ValueError
        Naming the file and what is wrong: not found, not a supported type,
        unreadable, or without triangles.
    """
    path = os.fspath(path)
    ext = os.path.splitext(path)[1].lower()
    if ext not in EXTENSIONS:
        raise ValueError(
            f"unsupported mesh file type {ext or '(no extension)'!r}: {path}; "
            f"use one of {', '.join(EXTENSIONS)}"
        )
    if not os.path.exists(path):
        raise ValueError(f"mesh file not found: {path}")
    try:
        with open(path, "rb"):
            pass
    except OSError as exc:
        raise ValueError(f"cannot read mesh file {path}: {exc.strerror or exc}") from None

    import pyvista as pv

    collect = _Collect()
    quiet = pv.vtk_verbosity("off") if hasattr(pv, "vtk_verbosity") else nullcontext()
    logging.root.addFilter(collect)
    try:
        with quiet, warnings.catch_warnings():
            warnings.simplefilter("ignore")
            mesh = pv.read(path)
            if isinstance(mesh, pv.MultiBlock):
                mesh = mesh.combine()
            if not isinstance(mesh, pv.PolyData):
                mesh = mesh.extract_surface()
            mesh = mesh.triangulate()
    except Exception as exc:  # whatever VTK or pyvista raise, the file is unreadable
        raise ValueError(f"cannot read mesh file {path}: {exc}") from None
    finally:
        logging.root.removeFilter(collect)
    reasons = [m.strip() for m in collect.messages if "returned failure" not in m]
    if collect.messages:
        reason = reasons[0] if reasons else "the file is damaged or not in this format"
        raise ValueError(f"cannot read mesh file {path}: {reason}")

    vertices = np.asarray(mesh.points, dtype=np.float64).reshape(-1, 3)
    triangles = np.asarray(mesh.faces, dtype=np.int64).reshape(-1, 4)[:, 1:]
    if len(triangles) and not np.isfinite(vertices).all():
        raise ValueError(f"cannot read mesh file {path}: vertices are not finite numbers")
    triangles = triangles[~degenerate(vertices, triangles)]
    if len(triangles) == 0:
        raise ValueError(f"mesh file has no triangles: {path}")
    return vertices, np.ascontiguousarray(triangles)
