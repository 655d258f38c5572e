"""The 3D pane built once the window is on screen (views/scene3d/deferred_scene_view.py): one deleted
while its import thread tells it pyvista is in does not crash the process, and one closed waits for
its import to end."""

import threading
import time

from turns_in_a_process import ran_to_the_end


def test_a_pane_deleted_while_its_import_thread_tells_it_does_not_crash_the_process(tmp_path):
    # The thread emitted a signal of an object the pane owned, deleted with it: a segmentation fault
    # in three runs of four of this script.
    ran_to_the_end("""
    pane = DeferredSceneView(None)  # never built: deleted before its thread's word arrives
    pane.build_soon()
    shiboken6.delete(pane)  # while its thread tells it
""", tmp_path, """
import pyvista  # imported once: each pane's import thread then tells it at once
from views.scene3d.deferred_scene_view import DeferredSceneView
""")


def test_closing_the_pane_waits_for_its_import_to_end(qtbot, monkeypatch):
    # The window closes and the process may end next: an import left running on a thread while the
    # interpreter ends may crash it.  Here the import takes half a second.
    from views.scene3d import deferred_scene_view

    importing = threading.Event()
    real = deferred_scene_view._import_pyvista

    def slow_import(pane):
        importing.set()
        time.sleep(0.5)  # the import's own work, on its thread
        real(pane)

    monkeypatch.setattr(deferred_scene_view, "_import_pyvista", slow_import)
    pane = deferred_scene_view.DeferredSceneView(None)
    qtbot.addWidget(pane)
    pane.build_soon()
    qtbot.waitUntil(importing.is_set)
    pane.close()
    assert not [t for t in threading.enumerate() if t.name == "import pyvista" and t.is_alive()]
