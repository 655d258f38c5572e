"""A lesson step shows its words first and builds its 3D marks a turn later, so the window answers
between the two; anything that asks the 3D pane meanwhile gets the step's answer."""

import numpy as np
from PySide6.QtWidgets import QApplication

from core.lessons.lesson_file import shipped_lessons

LESSONS = {lesson.id: i for i, lesson in enumerate(shipped_lessons())}


def test_a_step_lays_out_and_paints_its_words_before_the_3d_pane_builds_its_marks(qtbot, window, monkeypatch):
    # The 3D pane built a step's scene and marks (17-23 ms) in the turn that also laid out and painted
    # its words: the window answered nothing for up to 100 ms.
    panel, view = window.lesson_panel, window.scene_view.view
    panel.select(LESSONS["zbuffer"], 0)  # another scene, without a highlighted face
    window.scene_view.overlay_names()  # asked, the pane has made that step's changes
    built: list[str] = []
    add_actor = view.plotter.add_actor

    def add_and_tell(actor, name=None, **kwargs):
        built.append(name)
        return add_actor(actor, name=name, **kwargs)

    monkeypatch.setattr(view.plotter, "add_actor", add_and_tell)

    panel.select(LESSONS["back_faces"], 0)  # the pyramid, its back face highlighted with its normal
    assert not built  # nothing of the 3D pane in the step's own turn
    QApplication.sendPostedEvents()  # what the step asked of the window: its layout, the paint of its words
    assert not built and panel.text.text().startswith(panel.current_step().text[:20])
    qtbot.waitUntil(lambda: any(name.startswith("lesson:") for name in built))  # then, a turn of its own
    assert window.lessons.highlighted == "triangle 2 of 'pyramid'"
    pyramid = next(o for o in window.model.scene.objects if o.name == "pyramid")
    face = pyramid.vertices[pyramid.triangles[2]]
    assert any(part.n_points == 3 and np.allclose(part.points, face)  # the face's outline, drawn
               for part in window.scene_view.overlay_parts("lesson"))


def test_asked_before_its_turn_the_3d_pane_answers_for_the_step(qtbot, window):
    panel = window.lesson_panel
    panel.select(LESSONS["zbuffer"], 0)
    panel.select(LESSONS["back_faces"], 0)
    # At once, before the turn that builds them: the step's marks and its framing.
    assert window.scene_view.overlay_parts("lesson")
    objects = {o.name for o in window.model.scene.objects}
    assert "pyramid" in objects
    pyramid = next(o for o in window.model.scene.objects if o.name == "pyramid")
    assert window.scene_view.actor_of(("object", window.model.scene.objects.index(pyramid))) is not None


def test_steps_taken_faster_than_the_pane_follows_leave_it_showing_the_last(qtbot, window):
    # Three steps with no turn of the event loop between them, as keys held down may give: each step's
    # changes wait behind the one before, and the pane ends where the last step is.
    panel = window.lesson_panel
    panel.select(LESSONS["back_faces"], 0)  # the pyramid, its triangle 2
    panel.select(LESSONS["zbuffer"], 0)
    panel.select(LESSONS["back_faces"], 1)  # the notched prism, its triangle 13
    view = window.scene_view.view
    qtbot.waitUntil(lambda: not view._waiting)  # made in their own turn, not by a question
    prism = next(o for o in window.model.scene.objects if o.name == "notched prism")
    face = prism.vertices[prism.triangles[13]]
    parts = window.scene_view.overlay_parts("lesson")
    assert any(part.n_points == 3 and np.allclose(part.points, face) for part in parts)
    objects = window.model.scene.objects
    drawn = {id(window.scene_view.actor_of(("object", k))) for k in range(len(objects))}
    shown = {id(actor) for name, actor in view.plotter.renderer.actors.items() if name.startswith("object:")}
    assert drawn == shown and len(shown) == len(objects)  # its objects, none of the other steps'


def test_back_on_a_step_whose_picture_is_current_the_bar_says_done(qtbot, window):
    """From the shadow step (Image order) to the z-buffer steps and back: the Object order tab showed
    its full picture of the step's scene under a bar reading "Object order: not rendered yet" (its
    redundant render, cancelled as another tab came to the front, set that)."""
    from window_helpers import RENDER_TIMEOUT_MS

    for lesson, step in (("ray_casting", 1), ("zbuffer", 2), ("ray_casting", 1), ("zbuffer", 3)):
        window.lesson_panel.select(LESSONS[lesson], step)
        qtbot.waitUntil(lambda: window.showing_full(window.current.title.lower()), timeout=RENDER_TIMEOUT_MS)
    qtbot.waitUntil(lambda: window.renders.status(window.current)[1] == "Object order: done",
                    timeout=RENDER_TIMEOUT_MS)
    assert window.current.title == "Object order" and window.renders.status(window.current)[0] == 100
