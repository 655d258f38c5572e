"""Reading OBJ, STL and PLY files (core.files.mesh_files) and using them in scene files."""

from __future__ import annotations

import json
import subprocess
import sys
import warnings

import numpy as np
import pytest

from core.files import scene_file
from core.files.mesh_files import read_mesh
from core.files.scene_file import SceneFileError

CUBE_OBJ = """\
# a unit cube, quads counter-clockwise seen from outside
v 0 0 0
v 1 0 0
v 1 1 0
v 0 1 0
v 0 0 1
v 1 0 1
v 1 1 1
v 0 1 1
f 1 4 3 2
f 5 6 7 8
f 1 2 6 5
f 2 3 7 6
f 3 4 8 7
f 4 1 5 8
"""

TRIANGLE_STL = """\
solid one
  facet normal 0 0 1
    outer loop
      vertex 0 0 0
      vertex 2 0 0
      vertex 0 3 0
    endloop
  endfacet
endsolid one
"""

SQUARE_PLY = """\
ply
format ascii 1.0
element vertex 4
property float x
property float y
property float z
element face 1
property list uchar int vertex_indices
end_header
0 0 0
1 0 0
1 1 0
0 1 0
4 0 1 2 3
"""


def write(tmp_path, name, text):
    path = tmp_path / name
    path.write_text(text)
    return path


def signed_volume(vertices, triangles):
    a, b, c = (vertices[triangles[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def test_obj_polygons_become_triangles_keeping_their_winding(tmp_path):
    vertices, triangles = read_mesh(write(tmp_path, "cube.obj", CUBE_OBJ))
    assert vertices.shape == (8, 3) and vertices.dtype == np.float64
    assert triangles.shape == (12, 3) and triangles.dtype == np.int64
    assert signed_volume(vertices, triangles) == pytest.approx(1.0)


def test_ascii_stl(tmp_path):
    vertices, triangles = read_mesh(str(write(tmp_path, "one.STL", TRIANGLE_STL)))
    assert triangles.shape == (1, 3)
    assert vertices[triangles[0]] == pytest.approx(np.array([[0, 0, 0], [2, 0, 0], [0, 3, 0]]))


def test_ascii_ply(tmp_path):
    vertices, triangles = read_mesh(write(tmp_path, "square.ply", SQUARE_PLY))
    assert vertices.shape == (4, 3) and triangles.shape == (2, 3)
    c = vertices[triangles]
    normals = np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0])
    assert np.all(normals[:, 2] > 0)


def test_zero_area_triangles_are_left_out(tmp_path):
    text = "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 2 0 0\nf 1 2 3\nf 1 2 4\n"
    _, triangles = read_mesh(write(tmp_path, "sliver.obj", text))
    assert triangles.tolist() == [[0, 1, 2]]


@pytest.mark.parametrize(
    "name, content, fragment",
    [
        ("missing.obj", None, "mesh file not found"),
        ("model.3ds", "x", "unsupported mesh file type '.3ds'"),
        ("model", "x", r"unsupported mesh file type '\(no extension\)'"),
        ("empty.obj", "", "mesh file has no triangles"),
        ("points.obj", "v 0 0 0\nv 1 0 0\nl 1 2\n", "mesh file has no triangles"),
        # In a line: no area (it was "no triangles" with no word why).
        ("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n",
         r"no triangles \(its one triangle has zero area\)"),
        # Beyond the range a scene allows: said so (it was "no triangles", its area overflowing to inf
        # with numpy's warning on the terminal).
        ("huge.obj", "v 0 0 0\nv 1e300 0 0\nv 0 1 0\nf 1 2 3\n", r"within ±1,000,000, found 1e\+300"),
        ("garbage.stl", b"\x00\x01garbage", "cannot read mesh file"),
        ("garbage.ply", "ply\nformat nonsense\n", "cannot read mesh file"),
    ],
)
def test_bad_files_give_a_value_error_naming_the_file(tmp_path, name, content, fragment):
    path = tmp_path / name
    if isinstance(content, bytes):
        path.write_bytes(content)
    elif content is not None:
        path.write_text(content)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no RuntimeWarning either
        with pytest.raises(ValueError, match=fragment) as info:
            read_mesh(path)
    assert str(path) in str(info.value)


def test_a_folder_is_not_a_mesh_file(tmp_path):
    (tmp_path / "d.obj").mkdir()
    with pytest.raises(ValueError, match="cannot read mesh file"):
        read_mesh(tmp_path / "d.obj")


def test_importing_the_module_does_not_import_pyvista():
    code = "import sys, core.files.mesh_files; print('pyvista' in sys.modules)"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert out.stdout.strip() == "False"


# --- mesh files in scene files ---------------------------------------------------


def test_scene_with_mesh_files_round_trips(tmp_path):
    (tmp_path / "meshes").mkdir()
    write(tmp_path / "meshes", "cube.obj", CUBE_OBJ)
    write(tmp_path, "one.stl", TRIANGLE_STL)
    scene_path = write(tmp_path, "scene.json", json.dumps({
        "objects": [
            {"type": "mesh_file", "path": "meshes/cube.obj",
             "material": {"color": [0.9, 0.5, 0.2]}},
            {"type": "mesh_file", "path": "one.stl", "name": "flat"},
            {"type": "box", "center": [3, 0.5, 0], "size": 1},
        ]
    }))
    scene = scene_file.load(scene_path, read_mesh=read_mesh)
    cube, flat, _ = scene.objects
    assert cube.name == "cube" and len(cube.triangles) == 12
    assert flat.name == "flat" and len(flat.triangles) == 1
    saved = tmp_path / "saved.json"
    scene_file.save(scene, saved)
    assert [o.get("path") for o in json.loads(saved.read_text())["objects"]] == [
        "meshes/cube.obj", "one.stl", None
    ]
    assert scene_file.load(saved, read_mesh=read_mesh) == scene


def test_mesh_file_problems_name_the_object_path(tmp_path):
    write(tmp_path, "empty.obj", "")
    scene_path = write(tmp_path, "scene.json", json.dumps({
        "objects": [
            {"type": "mesh_file", "path": "nowhere.obj"},
            {"type": "mesh_file", "path": "empty.obj"},
            {"type": "mesh_file", "path": "model.fbx"},
        ]
    }))
    with pytest.raises(SceneFileError) as info:
        scene_file.load(scene_path, read_mesh=read_mesh)
    problems = info.value.problems
    assert len(problems) == 3
    assert problems[0] == f"objects[0].path: mesh file not found: {tmp_path / 'nowhere.obj'}"
    assert problems[1] == f"objects[1].path: mesh file has no triangles: {tmp_path / 'empty.obj'}"
    assert problems[2].startswith("objects[2].path: unsupported mesh file type '.fbx'")
