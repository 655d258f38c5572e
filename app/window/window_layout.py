"""How the window's panes share its screen: the tabs' images get the most room.

The tabs (the images and their tables) fill the window's middle; on the left,
the 3D scene sits above the controls and the lessons.  :func:`fit_window`
keeps that order at every size and text scale: the left column takes
:data:`LEFT_SHARE` of the width (a little more at larger text, so the
lesson's words keep a readable line length) and the 3D pane
:data:`SCENE_SHARE` of the left column's height, less when the lesson
step's words (or, with the exercises in front, the question and what
follows it) need the room (large text on a small screen; without the 3D
pane, the column widens for them), but never less
than :data:`MIN_SCENE_SHARE` (then the column widens, up to
:data:`MAX_LEFT_SHARE`); the column is never so narrow that the names on
its dock tabs are cut (up to :data:`MAX_LEFT_SHARE` too); the window never
grows beyond its screen's available area.  The window calls it when it is shown, resized, its text
scale changes or a lesson step is shown.
"""

from __future__ import annotations

from PySide6.QtCore import Qt
from PySide6.QtGui import QAction, QKeySequence
from PySide6.QtWidgets import QDockWidget, QTabBar

from views.dock_title import DockTitle

LEFT_SHARE = {1.0: 0.28, 1.5: 0.31, 2.0: 0.34}
"""Share of the window's width for the left column (3D pane, controls, lessons), by text scale."""
SCENE_SHARE = 0.42
"""Share of the left column's height for the 3D pane (the rest: controls and lessons)."""
MIN_SCENE_SHARE = 0.3
"""The least share of the left column's height the 3D pane keeps when a lesson's words need room."""
MAX_LEFT_SHARE = 0.42
"""The widest share the left column takes when a lesson's words need room (large text, small screen)."""


def tabbed_dock(window, title: str, name: str, widget, beside):
    """A closable dock of ``widget`` titled ``title`` (saved as ``name``), as one more tab of the
    left column beside the dock ``beside``; the dock shown stays the one that was."""
    dock = QDockWidget(title, window)
    dock.setObjectName(name)
    dock.setFeatures(QDockWidget.DockWidgetFeature.DockWidgetMovable
                     | QDockWidget.DockWidgetFeature.DockWidgetClosable)
    dock.setWidget(widget)
    DockTitle(dock)
    window.addDockWidget(Qt.DockWidgetArea.LeftDockWidgetArea, dock)
    window.tabifyDockWidget(beside, dock)
    keys_only_in_front(dock)
    return dock


def keys_only_in_front(dock: QDockWidget) -> None:
    """Keep the keyboard out of ``dock`` while another tab of its group covers it: Qt keeps a covered
    dock "visible", only moved off screen, so Tab walked into its fields and title buttons unseen (and
    an arrow key there moved the observer).  Its contents and title bar are disabled meanwhile, which
    takes them out of the focus chain and keeps their size (hidden, they gave up their room and the
    column narrowed)."""
    def changed(seen: bool) -> None:
        usable = seen or not dock.isVisible()  # a closed dock keeps them as they are
        for part in (dock.widget(), dock.titleBarWidget()):
            if part is not None:
                part.setEnabled(usable)

    dock.visibilityChanged.connect(changed)


def in_front(dock: QDockWidget) -> bool:
    """Whether ``dock`` is seen: shown and, if tabbed with others, the tab in front (a dock behind
    another tab stays "visible" to Qt, only covered)."""
    return dock.isVisible() and not dock.visibleRegion().isEmpty()


def dock_action(dock: QDockWidget, text: str, key: str) -> QAction:
    """The View menu's entry for ``dock``, checked while it is in front: it brings the dock to the
    front (shown, its tab raised) and hides it only when it is in front already.  (The dock's own
    toggle hid a dock tabbed behind another, and showed it again behind.)"""
    action = QAction(text, dock.parent())
    action.setCheckable(True)
    action.setShortcut(QKeySequence(key))

    def toggle() -> None:
        if in_front(dock):
            dock.hide()
        else:
            dock.show()
            dock.raise_()
        action.setChecked(dock.isVisible())

    action.triggered.connect(toggle)
    dock.visibilityChanged.connect(action.setChecked)  # a tab chosen or covered: in front or not
    action.setChecked(in_front(dock))
    return action


def left_share(scale: float) -> float:
    """:data:`LEFT_SHARE` at ``scale`` (the nearest scale offered below it)."""
    return LEFT_SHARE[max((s for s in LEFT_SHARE if s <= scale), default=1.0)]


def fit_window(window, scale: float = 1.0) -> None:
    """Share ``window``'s room (a :class:`app.window.main_window.MainWindow`) for text scale ``scale``."""
    available = window.screen().availableGeometry()
    if window.width() > available.width() or window.height() > available.height():
        window.resize(min(window.width(), available.width()), min(window.height(), available.height()))
    column = window.centralWidget().height()
    least_scene = round(column * MIN_SCENE_SHARE)
    docks = _left_docks(window)
    share, short = max(left_share(scale), min(_dock_tabs_share(window, docks), MAX_LEFT_SHARE)), 0
    # The lesson step's words shown whole, if the 3D pane can spare the room, else if the left
    # column may widen that much (the docks take their new sizes after this call).
    # The exercise's question and its Show answers button, when the exercises are in front.
    # Without the 3D pane (a lesson hid it), only a wider column gives them room.
    panel = window.exercise_panel if in_front(window.exercise_dock) else window.lesson_panel
    words = panel.isVisible()
    spare = window.scene_pane.height() - least_scene if window.scene_pane.isVisible() else 0
    while words:
        wider = round(window.width() * share) - docks.width()
        short = _words_short_by(panel, wider)
        if short <= spare or share >= MAX_LEFT_SHARE:
            break
        share = min(share + 0.02, MAX_LEFT_SHARE)
    window.resizeDocks([docks], [round(window.width() * share)], Qt.Orientation.Horizontal)
    if window.scene_pane.isVisible():
        scene = round(column * SCENE_SHARE)
        if words:
            scene = max(least_scene, min(scene, window.scene_pane.height() - short))
        window.resizeDocks([window.scene_pane, docks], [scene, column - scene],
                           Qt.Orientation.Vertical)


def _left_docks(window) -> QDockWidget:
    """The dock in front among the lessons' and the docks tabbed with it (the lessons' if none is):
    the one whose width is the left column's.  A dock behind another tab keeps the width it had when
    it was last in front (the lessons' kept 388 px while the exercises, in front, had 434)."""
    lessons = window.lesson_dock
    tabbed = [lessons, *window.tabifiedDockWidgets(lessons)]
    return next((dock for dock in tabbed if in_front(dock)), lessons)


def _dock_tabs_share(window, docks: QDockWidget) -> float:
    """The share of ``window``'s width the left column needs to show its dock tabs' names whole
    ("Controls", "Lessons", "Exercises", "Editor"; at x2 on a 1280 px screen they need 476 px of
    it), 0 while the lessons' dock is not tabbed with others; ``docks`` is the one in front."""
    for bar in window.findChildren(QTabBar, options=Qt.FindChildOption.FindDirectChildrenOnly):
        names = [bar.tabText(i) for i in range(bar.count())]
        if bar.isVisible() and window.lesson_dock.windowTitle() in names:
            beyond = bar.width() - docks.width()  # the bar's width beyond the dock's
            return (bar.sizeHint().width() - beyond) / max(window.width(), 1)
    return 0.0


def _words_short_by(panel, wider: int) -> int:
    """How many pixels taller the lesson (or exercise) panel's words area must be to show the step (the
    question) whole (negative: how many it has to spare) once the panel is ``wider`` pixels wider."""
    viewport = panel.scroll.viewport()
    words = panel.scroll.widget()  # as tall as its lines at that width, and never below its minimum
    tall = max(words.layout().totalHeightForWidth(viewport.width() + wider), words.minimumSizeHint().height())
    return tall - viewport.height()
