"""Text meshes are parsed a chunk at a time: what a file says must not depend on where chunks end.

With chunks of a few dozen bytes, every file here spans many chunks; each
is read as a reader that sees the whole file at once reads it (the expected
values are written out by hand from the file's text).
"""

import numpy as np
import pytest

from core.files import mesh_files
from core.files.mesh_files import read_mesh


@pytest.fixture(params=[24, 64, mesh_files.CHUNK_BYTES])
def chunk_bytes(request, monkeypatch):
    monkeypatch.setattr(mesh_files, "CHUNK_BYTES", request.param)
    return request.param


def put(tmp_path, name, text):
    path = tmp_path / name
    path.write_bytes(text.encode())
    return path


def test_negative_indices_count_back_across_chunks(tmp_path, chunk_bytes):
    text = "".join(f"v {k} {k * k} 0\nv {k} 0 1\nv 0 {k} 2\nf -3 -2 -1\n" for k in range(1, 6))
    vertices, triangles = read_mesh(put(tmp_path, "strip.obj", text))
    assert triangles.tolist() == [[3 * k, 3 * k + 1, 3 * k + 2] for k in range(5)]
    assert vertices[triangles[4]].tolist() == [[5, 25, 0], [5, 0, 1], [0, 5, 2]]


def test_polygons_of_different_sizes_in_different_chunks(tmp_path, chunk_bytes):
    text = ("v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 0 0\n"
            + "f 1 2 3\n" * 4 + "f 1 2 3 4\n" * 4 + "f 2 5 3\n")
    _, triangles = read_mesh(put(tmp_path, "mixed.obj", text))
    assert triangles.tolist() == [[0, 1, 2]] * 4 + [[0, 1, 2], [0, 2, 3]] * 4 + [[1, 4, 2]]


def test_a_bad_line_is_named_by_its_number_in_the_whole_file(tmp_path, chunk_bytes):
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "# a comment line\n" * 20 + "f 1 2 3\nf 1 2 9\n"
    with pytest.raises(ValueError, match="line 25: face refers to vertex 9"):
        read_mesh(put(tmp_path, "past.obj", text))
    with pytest.raises(ValueError, match="line 22: a vertex needs three numbers"):
        read_mesh(put(tmp_path, "short.obj", "# c\n" * 21 + "v 1 2\n"))


def test_indented_and_tab_separated_vertices_count_like_any_other(tmp_path, chunk_bytes):
    # A quick reader once skipped the indented vertex, so face 1 2 3 took the wrong corners.
    text = "v 0 0 0\n  v 1 0 0\nv 0 1 0\nv 1 1 0\nv\t2 2 0\nf 1 2 3\n"
    vertices, triangles = read_mesh(put(tmp_path, "spaced.obj", text))
    assert len(vertices) == 5 and vertices[4].tolist() == [2, 2, 0]
    assert vertices[triangles[0]].tolist() == [[0, 0, 0], [1, 0, 0], [0, 1, 0]]


def test_ply_lists_of_different_lengths_in_different_chunks(tmp_path, chunk_bytes):
    header = ("ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\nproperty float y\n"
              "property float z\nelement face 7\nproperty list uchar int vertex_indices\nend_header\n")
    body = "0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0 0\n" + "3 0 1 2\n" * 3 + "4 0 1 2 3\n" * 3 + "3 1 4 2\n"
    vertices, triangles = read_mesh(put(tmp_path, "mixed.ply", header + body))
    assert vertices.tolist() == [[0, 0, 0], [1, 0, 0], [1, 1, 0], [0, 1, 0], [2, 0, 0]]
    assert triangles.tolist() == [[0, 1, 2]] * 3 + [[0, 1, 2], [0, 2, 3]] * 3 + [[1, 4, 2]]


def test_a_ply_shorter_than_its_header_says_so_whatever_the_chunks(tmp_path, chunk_bytes):
    header = ("ply\nformat ascii 1.0\nelement vertex 9\nproperty float x\nproperty float y\n"
              "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n")
    with pytest.raises(ValueError, match=r"9 vertex, 1 face \(10 lines of data\), but only 4"):
        read_mesh(put(tmp_path, "short.ply", header + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"))


def test_ascii_stl_across_chunks(tmp_path, chunk_bytes):
    facet = ("  facet normal 0 0 1\n    outer loop\n      vertex 0 0 {z}\n      vertex 2 0 {z}\n"
             "      vertex 0 3 {z}\n    endloop\n  endfacet\n")
    text = "solid s\n" + "".join(facet.format(z=z) for z in range(4)) + "endsolid s\n"
    vertices, triangles = read_mesh(put(tmp_path, "four.stl", text))
    assert triangles.shape == (4, 3)
    assert np.array_equal(vertices[triangles[3]], [[0, 0, 3], [2, 0, 3], [0, 3, 3]])
