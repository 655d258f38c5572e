"""Reading a large text mesh file takes memory in proportion to the file, not Python objects per number.

Each file (about 20 MB) is read in a subprocess whose peak resident memory
(``VmHWM``, the high-water mark of the process's own memory) is compared with
the file's size.  The bound, 5 x the file, allows for the file's bytes held
while it is parsed (1 x); the mesh's arrays, 24 bytes per vertex and per
triangle, which for these files is 0.4 to 1.1 x the text; building them (the
chunks joined, polygons split into triangles), which at most doubles them; and
the parser's working memory of a chunk of about 1 MB at a time.  A reader
holding a Python float per coordinate and a list per face, as the one this
replaced did, needs 9 to 20 x these files.
"""

import io
import json
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from checkout import ROOT

MEASURE = """
import json, os, sys
from core.files.mesh_files import read_mesh

def peak_bytes():
    with open("/proc/self/status") as status:
        return next(int(line.split()[1]) * 1024 for line in status if line.startswith("VmHWM:"))

before = peak_bytes()
vertices, triangles = read_mesh(sys.argv[1])
print(json.dumps({"peak": peak_bytes() - before, "vertices": len(vertices), "triangles": len(triangles)}))
"""

RNG = np.random.default_rng(7)


def _obj_triangles(path: Path, n: int) -> tuple[int, int]:
    """v, vt and vn lines, and triangles written ``a/t/n``: the line-at-once reader's case."""
    v = RNG.random((n, 3))
    corners = RNG.integers(1, n - 1, 2 * n)[:, None] + np.arange(3)
    with open(path, "w") as f:
        np.savetxt(f, v, fmt="v %.6f %.6f %.6f")
        np.savetxt(f, v[:, :2], fmt="vt %.4f %.4f")
        np.savetxt(f, v, fmt="vn %.5f %.5f %.5f")
        np.savetxt(f, np.repeat(corners, 3, axis=1), fmt="f %d/%d/%d %d/%d/%d %d/%d/%d")
    return n, 2 * n


def _obj_quads_counting_back(path: Path, n: int) -> tuple[int, int]:
    """Each quad after its own four vertices, its corners counted back: the line-by-line reader's case."""
    text = io.StringIO()
    np.savetxt(text, RNG.random((4 * n, 3)), fmt="v %.6f %.6f %.6f")
    lines = text.getvalue().splitlines()
    path.write_text("".join("\n".join(lines[k:k + 4]) + "\nf -4 -3 -2 -1\n" for k in range(0, 4 * n, 4)))
    return 4 * n, 2 * n


def _ply(path: Path, n: int, mixed: bool) -> tuple[int, int]:
    """Vertices with normals; triangles only, or triangles and quads mixed (lists of two lengths)."""
    faces = RNG.integers(0, n - 4, n)
    header = (f"ply\nformat ascii 1.0\nelement vertex {n}\n"
              + "".join(f"property float {p}\n" for p in ("x", "y", "z", "nx", "ny", "nz"))
              + f"element face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
    with open(path, "w") as f:
        f.write(header)
        np.savetxt(f, RNG.random((n, 6)), fmt="%.6f")
        quads = (faces % 2 == 0) if mixed else np.zeros(len(faces), bool)
        for first, quad in zip(faces, quads, strict=True):
            f.write(f"4 {first} {first + 1} {first + 2} {first + 3}\n" if quad else
                    f"3 {first} {first + 1} {first + 2}\n")
    return n, len(faces) + int(quads.sum())


CASES = {
    "triangles.obj": lambda p: _obj_triangles(p, 100_000),
    "quads.obj": lambda p: _obj_quads_counting_back(p, 140_000),
    "triangles.ply": lambda p: _ply(p, 300_000, mixed=False),
    "mixed.ply": lambda p: _ply(p, 300_000, mixed=True),
}


@pytest.mark.parametrize("name", CASES)
def test_a_20_mb_text_mesh_is_read_in_at_most_5_times_its_size(tmp_path, name):
    path = tmp_path / name
    n_vertices, n_triangles = CASES[name](path)
    size = path.stat().st_size
    assert 15e6 < size < 25e6
    out = subprocess.run([sys.executable, "-c", MEASURE, str(path)], cwd=ROOT, capture_output=True,
                         text=True, timeout=300)
    assert out.returncode == 0, out.stderr[-3000:]
    read = json.loads(out.stdout)
    assert (read["vertices"], read["triangles"]) == (n_vertices, n_triangles)
    assert read["peak"] < 5 * size
