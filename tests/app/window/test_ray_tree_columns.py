"""The ray tree's columns are seen whole while presenting at x2, the returned colours last."""

from window_helpers import RENDER_TIMEOUT_MS

from core.presets_trace import mirror_and_glass


def test_every_ray_tree_column_is_seen_whole_presenting_at_x2(qtbot, window):
    # Presenting at x2 on a 1920x1080 screen, the "returns colour" column was cut off at the right.
    window.presentation.set_presenting(True)
    window.presentation.set_scale(2.0)
    window.model.set_scene(mirror_and_glass())  # a tree with reflected and refracted rays
    qtbot.waitUntil(lambda: window.showing_full("image order"), timeout=RENDER_TIMEOUT_MS)
    cam = window.model.camera
    with qtbot.waitSignal(window._tree_renderer.finished, timeout=RENDER_TIMEOUT_MS):
        window.pick_ray_tree(cam.width // 2, cam.height // 2)
    tree = window.tab("image order").widget.tree
    assert tree.topLevelItemCount() == 1 and tree.topLevelItem(0).childCount() > 0
    qtbot.waitUntil(lambda: tree.header().length() <= tree.viewport().width(), timeout=5000)
    window.presentation.set_presenting(False)
