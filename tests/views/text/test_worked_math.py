"""The worked math of a picked ray or vertex shows numbers equal to an independent computation."""

import json
import math
import os
import re
import subprocess
import sys
from fractions import Fraction

import mpmath
import numpy as np
import pytest
from qt_fixtures import shown_widget

from core import presets
from core.image_order.intersect_sphere import intersect_sphere_segment
from core.image_order.intersect_triangle import intersect_triangle
from core.image_order.ray_tree import trace_pixel
from core.lessons.lesson_file import shipped_lessons
from views.text.math_view import MathView, MatrixView
from views.text.worked_math import WorkedMath

LESSONS = {lesson.id: lesson for lesson in shipped_lessons()}


def _last_number(text: str) -> float:
    return float(re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", text)[-1])


def _close(shown: float, exact, digits: int = 6) -> bool:
    """``shown`` is ``exact`` rounded to ``digits`` significant digits."""
    exact = float(exact)
    return abs(shown - exact) <= 0.51 * 10 ** (math.floor(math.log10(abs(exact))) - digits + 1)


@pytest.fixture
def math_pane(qtbot):
    return shown_widget(qtbot, WorkedMath(), 700, 900)


def test_a_picked_ray_on_a_sphere_shows_a_b_c_delta_and_both_roots(math_pane, qtbot):
    step = LESSONS["ray_sphere"].steps[1]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    math_pane.show_ray(step.scene, root)
    mpmath.mp.dps = 40
    o = [mpmath.mpf(float(v)) for v in root.origin]
    d = [mpmath.mpf(float(v)) for v in root.direction]
    sphere = step.scene.objects[0]
    c = [mpmath.mpf(v) for v in sphere.center]
    f = [o[k] - c[k] for k in range(3)]
    a = sum(x * x for x in d)
    b = 2 * sum(f[k] * d[k] for k in range(3))
    cc = sum(x * x for x in f) - mpmath.mpf(sphere.radius) ** 2
    delta = b * b - 4 * a * cc
    t1, t2 = (-b - mpmath.sqrt(delta)) / (2 * a), (-b + mpmath.sqrt(delta)) / (2 * a)
    for label, exact in (("a", a), ("b", b), ("c", cc), ("Δ", delta), ("t_near", t1), ("t_far", t2)):
        assert _close(_last_number(math_pane.value(label)), exact), (label, math_pane.value(label))
    # the start point is inside, so the far root is the hit
    assert "inside" in math_pane.value("choice")
    assert _close(_last_number(math_pane.value("t")), t2)
    views = math_pane.findChildren(MathView)
    qtbot.waitUntil(lambda: not math_pane.typesetting())  # typeset off the GUI thread
    assert views and all(v.error is None and not v.pixmap().isNull() for v in views if v.formula())


def test_the_exercise_segment_shows_the_lectures_numbers(math_pane):
    math_pane.show_sphere(intersect_sphere_segment((2, 1, 2), (10, 6, 6), (6, 4, 6), 10), "exercise")
    assert math_pane.value("a").endswith("= 105$")
    assert math_pane.value("b").endswith("= -126$")
    assert math_pane.value("c").endswith("= -59$")
    assert math_pane.value("Δ").endswith("= 40656$")
    assert "both ends of the segment are inside" in math_pane.value("choice")
    assert "14.4813" in math_pane.value("ray beyond")  # the exit of the continued ray


def test_a_picked_ray_on_a_triangle_shows_the_solved_system(math_pane):
    step = LESSONS["ray_triangle"].steps[0]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    math_pane.show_ray(step.scene, root)
    A, B, C = (np.asarray(v) for v in step.scene.objects[0].vertices)
    # o + t d = αA + βB + (1 - α - β)C, solved exactly by Gaussian elimination in fractions
    rows = [[Fraction(float(A[k] - C[k])), Fraction(float(B[k] - C[k])), -Fraction(float(root.direction[k])),
             Fraction(float(root.origin[k])) - Fraction(float(C[k]))] for k in range(3)]
    for col in range(3):
        pivot = next(r for r in range(col, 3) if rows[r][col] != 0)
        rows[col], rows[pivot] = rows[pivot], rows[col]
        for r in range(3):
            if r != col:
                factor = rows[r][col] / rows[col][col]
                rows[r] = [x - factor * y for x, y in zip(rows[r], rows[col], strict=True)]
    alpha, beta, t = (rows[k][3] / rows[k][k] for k in range(3))
    for label, exact in (("α", alpha), ("β", beta), ("γ", 1 - alpha - beta), ("t", t)):
        assert _close(_last_number(math_pane.value(label)), exact), (label, math_pane.value(label))
    assert "<" not in math_pane.value("test")  # all three weights and t are >= 0: a hit
    assert [len(r) for r in math_pane.findChildren(MatrixView)[0].cells()] == [4, 4, 4]


def test_a_picked_ray_into_glass_shows_snells_law_and_fresnel(math_pane):
    step = LESSONS["ray_tracing"].steps[0]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    math_pane.show_ray(step.scene, root)
    theta1 = math.radians(_last_number(math_pane.value("θ1")))
    theta2 = math.radians(_last_number(math_pane.value("θ2")))
    assert math.sin(theta1) == pytest.approx(1.5 * math.sin(theta2), rel=1e-5)  # air to glass, n2 = 1.5
    fresnel = math_pane.value("Fresnel")
    r, t = (float(x) for x in re.findall(r"[RT] = (\d+(?:\.\d+)?)", fresnel)[:2])
    assert r + t == pytest.approx(1.0, abs=2e-6)
    # the incidence angle is the angle between the ray and the normal, computed here directly
    d = root.direction / np.linalg.norm(root.direction)
    assert math.degrees(theta1) == pytest.approx(math.degrees(math.acos(-d @ root.normal)), abs=1e-4)
    reflected = [float(x) for x in re.findall(r"-?\d+\.\d+", math_pane.value("r"))]
    assert np.allclose(reflected, d - 2 * (d @ root.normal) * root.normal, atol=1e-5)


def _shown_corner(math_pane, lesson: str):
    """Show the vertex path of the cube's corner that ``lesson``'s step follows; its camera, the
    corner's offset from the eye and the camera's own axes (forward, right, up), built by hand."""
    step = LESSONS[lesson].steps[0]
    cam = step.scene.camera
    cube = next(o for o in step.scene.objects if o.name == "cube")
    point = cube.vertices[step.highlight["vertex"]["index"]]
    math_pane.show_vertex(point, cam, "vertex 6 of 'cube'")
    eye = np.asarray(cam.eye)
    forward = (np.asarray(cam.target) - eye) / np.linalg.norm(np.asarray(cam.target) - eye)
    right = np.cross(forward, cam.up) / np.linalg.norm(np.cross(forward, cam.up))
    return cam, point - eye, (forward, right, np.cross(right, forward))


def test_a_picked_vertex_shows_its_path_to_the_pixel(math_pane):
    cam, rel, (forward, right, up) = _shown_corner(math_pane, "perspective")
    # pixel of the point from the camera's own axes and the viewing angle, no matrices
    half_h = math.tan(math.radians(cam.fov_y_deg) / 2)
    sx = (rel @ right) / (rel @ forward) / (half_h * cam.width / cam.height)
    sy = (rel @ up) / (rel @ forward) / half_h
    px, py = (sx + 1) / 2 * cam.width, (1 - sy) / 2 * cam.height
    pixel = [float(x) for x in re.findall(r"= (-?\d+(?:\.\d+)?)", math_pane.value("pixel"))]
    assert pixel == [pytest.approx(px, rel=1e-5), pytest.approx(py, rel=1e-5)]
    assert _close(_last_number(math_pane.value("camera")), rel @ forward)  # the depth
    assert len(math_pane.findChildren(MatrixView)) == 2  # view <- world and clip <- view


def _numbers(text: str) -> list[float]:
    return [float(x) for x in re.findall(r"-?\d+(?:\.\d+)?(?:e[-+]?\d+)?", text)]


@pytest.mark.parametrize("lesson", ["perspective", "orthographic"])
def test_a_picked_vertex_is_also_worked_in_the_lectures_coordinates_with_the_screen_at_z_0(math_pane, lesson):
    # The perspective step works x' = x d / (z + d) with the screen at z = 0 and the eye at z = -d; the
    # pane showed only the window's matrices.  Its rows "Fig. VII.6" (A) and "A′" now work the step's
    # formula with the picked corner's numbers (Fig. VII.7 for the orthographic step).  By hand, in world
    # space: the screen is the near plane, n in front of the eye along the viewing axis; A' is where the
    # line from the corner to the eye crosses it (similar triangles), or, for parallel rays, the corner
    # moved along the axis onto it.
    cam, rel, (forward, right, up) = _shown_corner(math_pane, lesson)
    z = rel @ forward - cam.near  # the corner's distance beyond the screen: the lecture's z
    crossing = rel * (cam.near / (rel @ forward)) if cam.projection == "perspective" else rel
    image = [crossing @ right, crossing @ up]
    corner = (rel @ right, rel @ up, z)
    figure = "Fig. VII.6" if lesson == "perspective" else "Fig. VII.7"
    assert _numbers(math_pane.value(figure).partition("A = ")[2])[:3] == [
        pytest.approx(v, rel=1e-5) for v in corner]
    assert _numbers(math_pane.value("A′"))[-2:] == [pytest.approx(v, rel=1e-5) for v in image]


def test_formulas_grow_with_the_scale(math_pane, qtbot):
    math_pane.show_sphere(intersect_sphere_segment((2, 1, 2), (10, 6, 6), (6, 4, 6), 10))
    view = math_pane.findChildren(MathView)[0]
    qtbot.waitUntil(lambda: not math_pane.typesetting())  # typeset off the GUI thread
    before = view.pixmap().deviceIndependentSize().height()
    math_pane.set_scale(2.0)
    qtbot.waitUntil(lambda: not math_pane.typesetting())
    after = view.pixmap().deviceIndependentSize().height()
    assert after == pytest.approx(2 * before, rel=0.15)


def test_the_pane_shows_the_numbers_the_intersect_command_prints(math_pane):
    """The same ray through ``python -m app intersect`` (a separate process) and the pane."""
    step = LESSONS["ray_tracing"].steps[0]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    math_pane.show_ray(step.scene, root)
    ball = next(o for o in step.scene.objects if o.name == "glass ball")
    vec = ",".join
    args = ["--origin", vec(repr(float(v)) for v in root.origin),
            "--direction", vec(repr(float(v)) for v in root.direction),
            "--center", vec(repr(float(v)) for v in ball.center), "--radius", repr(ball.radius), "--json"]
    out = subprocess.run([sys.executable, "-m", "app", "intersect", "sphere", *args], capture_output=True,
                         text=True, check=True, env={**os.environ, "PYTHONPATH": os.getcwd()}).stdout
    printed = json.loads(out)
    for label, key in (("a", "a"), ("b", "b"), ("c", "c"), ("Δ", "discriminant"), ("t_near", "t_near"),
                       ("t_far", "t_far"), ("t", "t")):
        assert _close(_last_number(math_pane.value(label)), printed[key]), (label, printed[key])


def test_the_triangle_shown_is_the_nearest_one_the_ray_crosses(math_pane):
    """On the cube (12 triangles) the pane works out the triangle a brute-force search finds first."""
    scene = presets.lecture_scene()
    cube = scene.objects[0]
    root = trace_pixel(scene, 120, 95)
    assert root.hit_name == "cube"
    math_pane.show_ray(scene, root)
    hits = [(h.t, k) for k, tri in enumerate(cube.triangles)
            if (h := intersect_triangle(root.origin, root.direction, *cube.vertices[tri])).hit]
    nearest = min(hits)[1]
    assert math_pane.rows()[0][1].endswith(f"cube, triangle {nearest}")


def test_a_presented_pane_typesets_its_formulas_only_at_the_size_shown(qtbot, present, monkeypatch, tmp_path):
    # Each typesetting is a parse of a few milliseconds. A new formula was typeset at scale 1 before its
    # scale reached it, and wrapped to fit Qt's default width before its layout gave it one: a picked
    # pixel held the GUI thread 0.1-0.4 s at x2.
    from views.text import math_view

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))  # nothing typeset before
    pane = WorkedMath()
    window, presentation = present(pane)
    presentation.set_scale(2.0)
    pane.set_scale(2.0)  # as the window does for its panes
    assert math_view._typesetter().waitForDone(30_000)  # what earlier tests' panes asked of it
    sizes = []
    typeset = math_view._typeset
    monkeypatch.setattr(math_view, "_typeset", lambda *args: (sizes.append(args[1]), typeset(*args))[1])
    pane.show_sphere(intersect_sphere_segment((2.5, 1.25, 2.125), (10, 6, 6), (6, 4, 6), 10), "ball")
    views = [v for v in pane.findChildren(MathView) if v.formula()]
    qtbot.waitUntil(lambda: all(not v.pixmap().isNull() for v in views))
    assert views and sizes
    least = min(v.size_pt() for v in views) * math_view.MIN_SHRINK
    assert min(sizes) >= least - 1e-9  # never at scale 1 (half the size), nor shrunk to a default width
