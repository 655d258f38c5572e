"""Mesh files written byte by byte (struct), for the readers' tests: a tetrahedron, and binary PLY and
STL that may lie in their headers."""

import struct

import numpy as np

TETRA_V = np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [0, 0, 1]], dtype=np.float32)
TETRA_F = np.array([[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]], dtype=np.int32)


def binary_ply(vertices, faces, declared_vertices=None, declared_faces=None, cut=0) -> bytes:
    """A little-endian binary PLY written by hand (struct), optionally lying in its header."""
    header = (
        "ply\nformat binary_little_endian 1.0\n"
        f"element vertex {len(vertices) if declared_vertices is None else declared_vertices}\n"
        "property float x\nproperty float y\nproperty float z\n"
        f"element face {len(faces) if declared_faces is None else declared_faces}\n"
        "property list uchar int vertex_indices\nend_header\n"
    ).encode()
    body = b"".join(struct.pack("<3f", *v) for v in vertices)
    body += b"".join(struct.pack("<B3i", 3, *f) for f in faces)
    data = header + body
    return data[: len(data) - cut]


def binary_stl(triangles, declared=None) -> bytes:
    head = b"binary stl".ljust(80, b" ") + struct.pack("<I", len(triangles) if declared is None
                                                       else declared)
    return head + b"".join(struct.pack("<12fH", 0, 0, 0, *np.ravel(t), 0) for t in triangles)
