"""The ray tree's rows never say "not traced" for a shadow ray whose light share is known."""

import numpy as np

from core.image_order.ray_tree import trace_pixel
from core.lessons.lesson_file import shipped_lessons
from views.panels.raytree_view import RayTreeWidget

BY_ID = {lesson.id: lesson for lesson in shipped_lessons()}


def _rows(item, out):
    out.append(item)
    for i in range(item.childCount()):
        _rows(item.child(i), out)
    return out


def test_a_lone_triangles_shadow_ray_reads_lit_with_the_colour_it_adds(qtbot):
    step = BY_ID["ray_triangle"].steps[0]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    (shadow,) = [c for c in root.children if c.kind == "shadow"]
    # Nothing else is in the scene, so the light is never blocked: no ray is sent, yet it lights the point.
    assert not shadow.traced and np.all(shadow.color > 0)
    tree = RayTreeWidget()
    qtbot.addWidget(tree)
    tree.set_tree(root)
    (row,) = [r for r in _rows(tree.topLevelItem(0), []) if r.text(0).startswith("shadow")]
    assert row.text(1) == "lit: no ray needed" and row.text(4) != ""


def test_a_shadow_ray_to_a_light_behind_the_surface_reads_unlit(qtbot):
    step = BY_ID["ray_tracing"].steps[0]  # inside the glass ball one light is behind a surface
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    behind = [n for n in root.walk() if n.kind == "shadow" and not n.traced]
    assert behind and all(not np.any(n.color > 0) for n in behind)
    tree = RayTreeWidget()
    qtbot.addWidget(tree)
    tree.set_tree(root)
    texts = [r.text(1) for r in _rows(tree.topLevelItem(0), []) if r.text(0).startswith("shadow")]
    assert "unlit: light behind" in texts and "not traced" not in texts


def test_a_rays_tooltip_counts_its_tests_in_words(qtbot):
    """The lone triangle's primary ray makes one intersection test: "1 intersection test", not
    "1 intersection tests"."""
    step = BY_ID["ray_triangle"].steps[0]
    root = trace_pixel(step.scene, *step.pixel, step.image_order)
    assert root.tests == 1  # one triangle, tested once
    boxes = root.bounds_tests
    tree = RayTreeWidget()
    qtbot.addWidget(tree)
    tree.set_tree(root)
    tip = tree.topLevelItem(0).toolTip(0)
    assert f"1 intersection test, {boxes} box and sphere test{'s' * (boxes != 1)}" in tip.splitlines()
