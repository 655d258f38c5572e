"""Primitive meshes (core.shapes) and the lecture's question scene (core.presets)."""

from __future__ import annotations

import math
from collections import Counter

import numpy as np
import pytest

from core import presets, shapes
from core.camera import Camera
from core.scene import Material, Mesh

# --- geometry helpers, written independently of core ------------------------


def signed_volume(mesh: Mesh) -> float:
    """Divergence theorem: positive for a closed mesh with outward normals."""
    a, b, c = (mesh.corners[:, k] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def edge_counts(mesh: Mesh) -> Counter:
    edges = Counter()
    for a, b, c in mesh.triangles.tolist():
        edges.update([(a, b), (b, c), (c, a)])
    return edges


def segment_hits(start, ends, corners, eps=1e-9) -> np.ndarray:
    """(len(ends),) bool: does the open segment start -> end cross any triangle?

    Moller-Trumbore for every (segment, triangle) pair; hits right at either
    end of the segment (t <= eps or t >= 1 - eps) do not count.
    """
    start = np.asarray(start, float)
    d = np.asarray(ends, float) - start  # (S, 3)
    a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]  # (T, 3)
    e1, e2 = b - a, c - a
    p = np.cross(d[:, None, :], e2[None])  # (S, T, 3)
    det = np.einsum("stk,tk->st", p, e1)
    with np.errstate(divide="ignore", invalid="ignore"):
        s = start - a  # (T, 3)
        u = np.einsum("stk,tk->st", p, s) / det
        q = np.cross(s, e1)  # (T, 3)
        v = np.einsum("sk,tk->st", d, q) / det
        t = np.einsum("tk,tk->t", q, e2)[None] / det
    hit = (np.abs(det) > 1e-15) & (u >= 0) & (v >= 0) & (u + v <= 1) & (t > eps) & (t < 1 - eps)
    return hit.any(axis=1)


def inside(mesh: Mesh, points) -> np.ndarray:
    """Point-in-solid by the parity of crossings of a long ray in an odd direction."""
    direction = np.array([0.3127, 0.5711, 0.7589])
    points = np.asarray(points, float)
    corners = mesh.corners
    result = []
    for p in points:
        far = p + 1e3 * direction
        a, b, c = corners[:, 0], corners[:, 1], corners[:, 2]
        e1, e2, d = b - a, c - a, far - p
        pv = np.cross(d, e2)
        det = np.einsum("tk,tk->t", pv, e1)
        s = p - a
        u = np.einsum("tk,tk->t", pv, s) / det
        q = np.cross(s, e1)
        v = q @ d / det
        t = np.einsum("tk,tk->t", q, e2) / det
        crossings = ((u >= 0) & (v >= 0) & (u + v <= 1) & (t > 0) & (t < 1)).sum()
        result.append(crossings % 2 == 1)
    return np.array(result)


CLOSED = {
    "box": lambda: shapes.box((1.0, 2.0, -3.0), (2.0, 1.0, 3.0)),
    "cube": lambda: shapes.box((0.0, 0.8, 0.0), 1.6),
    "cone": lambda: shapes.cone((0.5, 0.0, 1.0), 1.0, 2.2, segments=24),
    "pyramid": lambda: shapes.pyramid((0.0, 1.0, 0.0), 2.0, 3.0),
    "uv_sphere": lambda: shapes.uv_sphere((1.0, 1.0, 1.0), 1.5, rings=8, segments=12),
    "notched_prism": lambda: shapes.notched_prism((0.0, 0.0, 0.0), (3.0, 2.0, 4.0), (1.0, 1.5)),
}


@pytest.mark.parametrize("kind", CLOSED)
def test_closed_solids_are_watertight(kind):
    mesh = CLOSED[kind]()
    edges = edge_counts(mesh)
    for (a, b), n in edges.items():
        assert n == 1, f"edge {a}->{b} used {n} times in the same direction"
        assert edges[(b, a)] == 1, f"edge {a}-{b} is not shared by exactly two triangles"


@pytest.mark.parametrize("kind", [*CLOSED, "quad"])
def test_no_degenerate_triangles_and_finite_normals(kind):
    mesh = CLOSED[kind]() if kind in CLOSED else shapes.quad((0, 0, 0), (3, 2))
    c = mesh.corners
    areas = np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1) / 2
    assert areas.min() > 1e-6
    assert np.isfinite(mesh.normals).all()
    assert mesh.vertices.dtype == np.float64 and mesh.triangles.dtype == np.int64


@pytest.mark.parametrize("kind", CLOSED)
def test_normals_point_out_of_the_solid(kind):
    mesh = CLOSED[kind]()
    centroids = mesh.corners.mean(axis=1)
    step = 1e-3
    assert not inside(mesh, centroids + step * mesh.normals).any()
    assert inside(mesh, centroids - step * mesh.normals).all()


def test_volumes_of_box_pyramid_and_notched_prism_are_exact():
    assert signed_volume(shapes.box((1, 2, 3), (2.0, 1.0, 3.0))) == pytest.approx(6.0)
    assert signed_volume(shapes.box((0, 0, 0), 1.6)) == pytest.approx(1.6**3)
    assert signed_volume(shapes.pyramid((0, 0, 0), 2.0, 3.0)) == pytest.approx(2 * 2 * 3 / 3)
    # an L footprint: 3 x 4 rectangle minus the 1 x 1.5 notch, 2 high
    prism = shapes.notched_prism((5, 1, -2), (3.0, 2.0, 4.0), (1.0, 1.5))
    assert signed_volume(prism) == pytest.approx((3 * 4 - 1 * 1.5) * 2)


def test_cone_volume_is_that_of_its_polygon_and_approaches_the_cone():
    r, h = 1.0, 2.2
    for n in (3, 8, 64):
        polygon_area = n / 2 * r * r * math.sin(2 * math.pi / n)
        assert signed_volume(shapes.cone((0, 0, 0), r, h, n)) == pytest.approx(polygon_area * h / 3)
    exact = math.pi * r * r * h / 3
    assert signed_volume(shapes.cone((0, 0, 0), r, h, 256)) == pytest.approx(exact, rel=1e-3)


def test_uv_sphere_volume_approaches_the_sphere_from_below():
    exact = 4 / 3 * math.pi * 2.0**3
    errors = [
        exact - signed_volume(shapes.uv_sphere((0, 1, 0), 2.0, rings, 2 * rings))
        for rings in (4, 8, 16, 64)
    ]
    assert all(e > 0 for e in errors)
    assert errors == sorted(errors, reverse=True)
    assert errors[-1] / exact < 2e-3


def test_uv_sphere_vertices_lie_on_the_sphere():
    mesh = shapes.uv_sphere((1, 2, 3), 0.5, rings=6, segments=10)
    assert np.allclose(np.linalg.norm(mesh.vertices - [1, 2, 3], axis=1), 0.5)
    assert len(mesh.triangles) == 2 * 10 * (6 - 1)


def test_cone_stands_along_plus_y_on_its_base():
    mesh = shapes.cone((0.5, 0.25, 1.0), 1.0, 2.2, segments=16)
    ys = mesh.vertices[:, 1]
    assert ys.min() == pytest.approx(0.25) and ys.max() == pytest.approx(2.45)
    apex = mesh.vertices[np.argmax(ys)]
    assert apex == pytest.approx([0.5, 2.45, 1.0])
    base = mesh.vertices[np.isclose(ys, 0.25)]
    assert np.linalg.norm(base[:, [0, 2]] - [0.5, 1.0], axis=1).max() == pytest.approx(1.0)
    # the base is closed by triangles facing straight down
    assert np.isclose(mesh.normals[:, 1], -1).sum() == 16


def test_pyramid_has_a_square_base_and_four_sides():
    mesh = shapes.pyramid((0, 0, 0), 2.0, 3.0)
    assert len(mesh.vertices) == 5 and len(mesh.triangles) == 6
    base = mesh.vertices[mesh.vertices[:, 1] == 0]
    assert sorted(map(tuple, base[:, [0, 2]].tolist())) == [(-1, -1), (-1, 1), (1, -1), (1, 1)]


def test_box_corners_and_faces():
    mesh = shapes.box((1, 2, 3), (2, 4, 6))
    assert len(mesh.triangles) == 12
    assert mesh.vertices.min(axis=0) == pytest.approx([0, 0, 0])
    assert mesh.vertices.max(axis=0) == pytest.approx([2, 4, 6])
    # every normal is one of the six axis directions, each used by two triangles
    axes = Counter(tuple(np.round(n).astype(int)) for n in mesh.normals)
    assert sorted(axes.values()) == [2] * 6 and len(axes) == 6


def test_quad_is_a_horizontal_single_sided_ground_plane():
    mesh = shapes.quad((1.0, -0.5, 2.0), (14.0, 10.0))
    assert len(mesh.triangles) == 2
    assert np.all(mesh.vertices[:, 1] == -0.5)
    assert mesh.normals == pytest.approx(np.array([[0, 1, 0], [0, 1, 0]]))
    c = mesh.corners
    area = np.linalg.norm(np.cross(c[:, 1] - c[:, 0], c[:, 2] - c[:, 0]), axis=1).sum() / 2
    assert area == pytest.approx(140.0)
    assert mesh.vertices.min(axis=0)[[0, 2]] == pytest.approx([-6.0, -3.0])
    assert shapes.quad((0, 0, 0), 14.0).source["size"] == [14.0, 14.0]


def test_notched_prism_is_not_convex():
    mesh = shapes.notched_prism((0, 0, 0), (3.0, 2.0, 4.0), (1.0, 1.5))
    # some face's plane has vertices of the solid on both sides
    sides = np.einsum("tvk,tk->tv", mesh.vertices[None] - mesh.corners[:, :1], mesh.normals)
    assert ((sides > 1e-9).any(axis=1) & (sides < -1e-9).any(axis=1)).any()
    # its volume is less than that of its convex hull (L footprint's hull: cut the
    # notch corner off diagonally, losing only half the notch)
    hull = (3 * 4 - 1 * 1.5 / 2) * 2
    assert signed_volume(mesh) < hull - 1


def test_notched_prism_has_a_front_facing_wall_only_partly_visible():
    """The lecture's Fig. VII.4b: back-face culling keeps a wall that is partly hidden."""
    mesh = shapes.notched_prism((0, 0, 0), (2.0, 1.5, 2.0), (1.0, 1.0))
    eye = np.array(Camera().eye)
    centroids = mesh.corners.mean(axis=1)
    front = np.einsum("ij,ij->i", mesh.normals, eye - centroids) > 0
    partly = []
    for k in np.flatnonzero(front):
        a, b, c = mesh.corners[k]
        w = np.random.default_rng(k).dirichlet([1, 1, 1], 200)
        samples = w @ np.array([a, b, c])
        hidden = segment_hits(eye, samples, mesh.corners)
        if hidden.any() and not hidden.all():
            partly.append(k)
    assert partly, "no front-facing triangle is partly hidden"
    assert all(np.allclose(mesh.normals[k], [0, 0, 1]) for k in partly)


def test_sources_describe_the_primitive():
    assert shapes.box((0, 0.8, 0), 1.6).source == {
        "type": "box",
        "center": [0.0, 0.8, 0.0],
        "size": [1.6, 1.6, 1.6],
    }
    assert shapes.cone((0, 0, 0), 1, 2).source == {
        "type": "cone",
        "base_center": [0.0, 0.0, 0.0],
        "radius": 1.0,
        "height": 2.0,
        "segments": 32,
    }


def test_registry_lists_every_primitive_and_rebuilds_from_source():
    assert set(shapes.PRIMITIVES) == {
        "box", "cone", "pyramid", "quad", "uv_sphere", "notched_prism"
    }
    meshes = [f() for f in CLOSED.values()] + [shapes.quad((0, 0, 0), 3)]
    material = Material(color=(0.1, 0.2, 0.3))
    for mesh in meshes:
        kind = mesh.source["type"]
        prim = shapes.PRIMITIVES[kind]
        assert mesh.name == kind
        assert set(mesh.source) == {"type", *(p.name for p in prim.params)}
        params = {k: v for k, v in mesh.source.items() if k != "type"}
        again = prim.builder(**params, material=material, name="again")
        assert np.array_equal(again.vertices, mesh.vertices)
        assert again.source == mesh.source and again.material == material


@pytest.mark.parametrize(
    "build, fragment",
    [
        (lambda: shapes.box((0, 0, 0), (1, -1, 1)), "size"),
        (lambda: shapes.box((0, 0), 1), "center"),
        (lambda: shapes.cone((0, 0, 0), 0, 1), "radius"),
        (lambda: shapes.cone((0, 0, 0), 1, 1, segments=2), "segments"),
        (lambda: shapes.uv_sphere((0, 0, 0), 1, rings=1), "rings"),
        (lambda: shapes.pyramid((0, 0, 0), 1, float("nan")), "height"),
        (lambda: shapes.notched_prism((0, 0, 0), (1, 1, 1), (1, 0.5)), "notch"),
    ],
)
def test_bad_parameters_raise_value_error_naming_them(build, fragment):
    with pytest.raises(ValueError, match=fragment):
        build()


# --- the lecture scene --------------------------------------------------------


def test_lecture_scene_has_cube_and_cone_on_an_opaque_plane():
    scene = presets.lecture_scene()
    assert scene.camera == Camera()
    names = {obj.name: obj for obj in scene.objects}
    assert set(names) == {"cube", "cone", "ground"}
    cube, cone, ground = names["cube"], names["cone"], names["ground"]
    assert cube.source["type"] == "box" and len(set(cube.source["size"])) == 1
    assert cone.source["type"] == "cone"
    assert ground.source["type"] == "quad" and ground.material.opacity == 1.0
    # both stand on the plane y = 0
    assert cube.vertices[:, 1].min() == pytest.approx(0.0)
    assert cone.vertices[:, 1].min() == pytest.approx(0.0)
    assert np.all(ground.vertices[:, 1] == 0.0)
    # they do not overlap: the cone's footprint circle misses the cube's square
    cube_c, half = np.array(cube.source["center"])[[0, 2]], cube.source["size"][0] / 2
    cone_c = np.array(cone.source["base_center"])[[0, 2]]
    nearest = np.clip(cone_c, cube_c - half, cube_c + half)
    assert np.linalg.norm(cone_c - nearest) > cone.source["radius"]
    # distinct colours, a light above and in front
    colors = {obj.material.color for obj in scene.objects}
    assert len(colors) == 3
    assert len(scene.lights) == 1 and scene.lights[0].position[1] > 3


def test_lecture_scene_objects_are_in_view():
    scene = presets.lecture_scene()
    m = scene.camera.clip_from_world
    for obj in scene.objects[:2]:
        clip = np.c_[obj.vertices, np.ones(len(obj.vertices))] @ m.T
        ndc = clip[:, :3] / clip[:, 3:]
        assert np.all(clip[:, 3] > 0) and np.all(np.abs(ndc) < 1), obj.name


def test_lecture_scene_cone_partly_hides_the_cube():
    """Some cube corners are hidden from the eye by the cone, some are seen."""
    scene = presets.lecture_scene()
    cube, cone, ground = scene.objects
    eye = np.array(scene.camera.eye)
    corners = np.unique(cube.vertices, axis=0)
    behind_cone = segment_hits(eye, corners, cone.corners)
    assert behind_cone.any(), "the cone hides no corner of the cube"
    seen = ~segment_hits(eye, corners, np.vstack([cone.corners, cube.corners, ground.corners]))
    assert seen.any(), "no corner of the cube is visible"
    # and the cube is the farther of the two
    assert np.linalg.norm(cube.bounding_sphere()[0] - eye) > np.linalg.norm(
        cone.bounding_sphere()[0] - eye
    )
