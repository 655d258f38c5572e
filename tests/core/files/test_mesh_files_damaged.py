"""Damaged and hostile mesh files: refused with a message that says what disagrees, never a crash.

Each file here once crashed, hung or misled the VTK-based reader (issue 11).
Valid binary files are checked against VTK's own reading of them in
``tests/views/scene3d/test_mesh_files_as_vtk_reads_them.py`` (VTK is tested there).
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from checkout import ROOT
from mesh_bytes import TETRA_F, TETRA_V, binary_ply, binary_stl

from core.files.mesh_files import MAX_FILE_BYTES, read_mesh


def put(tmp_path, name, data) -> Path:
    path = tmp_path / name
    path.write_bytes(data if isinstance(data, bytes) else data.encode())
    return path


@pytest.mark.parametrize(
    "name, data, fragments",
    [
        ("short.ply", binary_ply(TETRA_V, TETRA_F, cut=30), ["4 face", "ends inside face 1"]),
        ("more_vertices.ply", binary_ply(TETRA_V, TETRA_F, declared_vertices=400),
         ["400 vertex", "bytes are left"]),
        ("past.ply", binary_ply(TETRA_V, np.array([[0, 1, 98]])),
         ["face 0", "vertex 98", "4 vertices"]),
        ("huge.ply", "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\n"
                     "property float y\nproperty float z\nend_header\n0 0 0\n",
         ["2,000,000,000 vertex"]),
        ("fewer.ply", "ply\nformat ascii 1.0\nelement vertex 5\nproperty float x\n"
                      "property float y\nproperty float z\nelement face 1\n"
                      "property list uchar int vertex_indices\nend_header\n"
                      "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n",
         ["5 vertex", "1 face", "only 4 lines"]),
        ("no_end.ply", "ply\nformat ascii 1.0\nelement vertex 3\n", ["end_header"]),
        ("float_count.ply", "ply\nformat binary_little_endian 1.0\nelement face 1\n"
                            "property list float int vertex_indices\nend_header\n",
         ["header line 4", "not understood"]),
        ("huge_list.ply", binary_ply(TETRA_V, []).replace(b"element face 0", b"element face 1")
         + b"\xff" * 5, ["1 face", "ends inside face 0"]),
        ("past.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 99\n",
         ["line 4", "vertex 99", "3 vertices", "valid: 1 to 3"]),
        ("short.stl", binary_stl(TETRA_V[TETRA_F], declared=1000), ["1,000 triangles", "bytes"]),
    ],
)
def test_a_file_that_disagrees_with_its_header_says_so(tmp_path, name, data, fragments):
    path = put(tmp_path, name, data)
    with pytest.raises(ValueError) as info:
        read_mesh(path)
    message = str(info.value)
    assert str(path) in message
    for fragment in fragments:
        assert fragment in message


def test_obj_faces_naming_missing_texture_coordinates_still_give_their_triangle(tmp_path):
    # VTK's reader crashed on this; only the vertex index of each corner matters.
    path = put(tmp_path, "uv.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nf 1/7 2/8 3/9\n")
    vertices, triangles = read_mesh(path)
    assert vertices[triangles[0]].tolist() == [[0, 0, 0], [2, 0, 0], [0, 2, 0]]


def test_obj_negative_indices_count_back_from_the_last_vertex(tmp_path):
    path = put(tmp_path, "neg.obj", "v 0 0 0\nv 2 0 0\nv 0 2 0\nf -3 -2 -1\n")
    assert read_mesh(path)[1].tolist() == [[0, 1, 2]]


def test_a_byte_order_mark_does_not_lose_the_first_vertex(tmp_path):
    path = put(tmp_path, "bom.obj", b"\xef\xbb\xbfv 5 0 0\nv 6 0 0\nv 5 1 0\nf 1 2 3\n")
    vertices, triangles = read_mesh(path)
    assert len(vertices) == 3 and vertices[0].tolist() == [5, 0, 0]


def test_a_fifo_is_refused_without_blocking(tmp_path):
    fifo = tmp_path / "pipe.obj"
    os.mkfifo(fifo)
    with pytest.raises(ValueError, match="not a regular file"):
        read_mesh(fifo)


def test_a_file_above_the_size_limit_is_refused_before_reading(tmp_path):
    path = tmp_path / "big.stl"
    with open(path, "wb") as f:
        f.truncate(MAX_FILE_BYTES + 1)  # sparse: no disk used
    with pytest.raises(ValueError, match="too large"):
        read_mesh(path)


def test_the_two_billion_vertex_ply_is_refused_by_render_quickly_and_cleanly(tmp_path):
    put(tmp_path, "huge.ply", "ply\nformat ascii 1.0\nelement vertex 2000000000\nproperty float x\n"
                              "property float y\nproperty float z\nend_header\n0 0 0\n")
    scene = put(tmp_path, "s.json", '{"objects": [{"type": "mesh_file", "path": "huge.ply"}]}')
    # Once this ran forever growing by 70 MB/s; the timeout only guards against a hang.
    out = subprocess.run([sys.executable, "-m", "app", "render", str(scene), "--out",
                          str(tmp_path / "x.png")], cwd=ROOT, capture_output=True, text=True,
                         timeout=120)
    assert out.returncode == 2
    assert "objects[0].path" in out.stderr and "2,000,000,000" in out.stderr
    assert "Traceback" not in out.stderr
    assert not (tmp_path / "x.png").exists()
