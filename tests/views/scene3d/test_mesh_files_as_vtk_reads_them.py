"""Valid binary mesh files read by our reader as VTK's own reader reads them (issue 11)."""

import numpy as np
import pyvista as pv
from mesh_bytes import TETRA_F, TETRA_V, binary_ply, binary_stl

from core.files.mesh_files import read_mesh


def test_valid_binary_ply_reads_as_vtk_reads_it(tmp_path):
    path = tmp_path / "tetra.ply"
    path.write_bytes(binary_ply(TETRA_V, TETRA_F))
    vertices, triangles = read_mesh(path)
    reference = pv.read(str(path))
    assert np.array_equal(vertices, np.asarray(reference.points, dtype=np.float64))
    assert np.array_equal(triangles, reference.faces.reshape(-1, 4)[:, 1:])


def test_valid_binary_stl_reads_as_vtk_reads_it(tmp_path):
    path = tmp_path / "tetra.stl"
    path.write_bytes(binary_stl(TETRA_V[TETRA_F]))
    vertices, triangles = read_mesh(path)
    reference = pv.read(str(path))
    assert len(triangles) == reference.n_cells == 4
    # VTK merges the repeated corners; compare the triangles' corner positions instead.
    ours = np.sort(vertices[triangles].reshape(-1, 9), axis=0)
    theirs = np.sort(np.asarray(reference.points)[reference.faces.reshape(-1, 4)[:, 1:]]
                     .reshape(-1, 9), axis=0)
    assert np.array_equal(ours, theirs)
