"""How the window's panes share its screen: the tabs' images get the most room.

The tabs (the images and their tables) fill the window's middle; on the left,
the 3D scene sits above the controls and the lessons.  :func:`fit_window`
keeps that order at every size and text scale: the left column takes
:data:`LEFT_SHARE` of the width (a little more at larger text, so the
lesson's words keep a readable line length) and the 3D pane
:data:`SCENE_SHARE` of the left column's height; the window never grows
beyond its screen's available area.  The window calls it when it is shown,
resized, or its text scale changes.
"""

from __future__ import annotations

from PySide6.QtCore import Qt

LEFT_SHARE = {1.0: 0.28, 1.5: 0.31, 2.0: 0.34}
"""Share of the window's width for the left column (3D pane, controls, lessons), by text scale."""
SCENE_SHARE = 0.42
"""Share of the left column's height for the 3D pane (the rest: controls and lessons)."""


def left_share(scale: float) -> float:
    """:data:`LEFT_SHARE` at ``scale`` (the nearest scale offered below it)."""
    return LEFT_SHARE[max((s for s in LEFT_SHARE if s <= scale), default=1.0)]


def fit_window(window, scale: float = 1.0) -> None:
    """Share ``window``'s room (a :class:`app.main_window.MainWindow`) for text scale ``scale``."""
    available = window.screen().availableGeometry()
    if window.width() > available.width() or window.height() > available.height():
        window.resize(min(window.width(), available.width()), min(window.height(), available.height()))
    docks = [window.scene_pane, window.lesson_dock]
    window.resizeDocks([window.lesson_dock], [round(window.width() * left_share(scale))],
                       Qt.Orientation.Horizontal)
    if window.scene_pane.isVisible():
        column = window.centralWidget().height()
        scene = round(column * SCENE_SHARE)
        window.resizeDocks(docks, [scene, column - scene], Qt.Orientation.Vertical)
