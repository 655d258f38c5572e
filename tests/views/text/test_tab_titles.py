"""Tab titles that fit (views.text.tab_titles): short forms, whole, before elided ones; whole titles
again when they fit; the whole title always in the tooltip."""

from PySide6.QtWidgets import QTabBar, QTabWidget, QWidget
from window_helpers import presenting_on_1280x720

from views.text.tab_titles import TitlesThatFit

TITLES = {"Image order": "Image", "Object order": "Object", "Four views": "Views", "Compare": "Compare"}


def _tabs(qtbot, width: int) -> QTabWidget:
    tabs = QTabWidget()
    qtbot.addWidget(tabs)
    for title in TITLES:
        tabs.addTab(QWidget(), title)
    TitlesThatFit(tabs, TITLES)
    tabs.resize(width, 200)
    tabs.show()
    return tabs


def _texts(tabs) -> list[str]:
    return [tabs.tabText(i) for i in range(tabs.count()) if tabs.isTabVisible(i)]


def _needed(tabs) -> int:
    return sum(tabs.tabBar().tabSizeHint(i).width() for i in range(tabs.count()) if tabs.isTabVisible(i))


def test_a_bar_too_narrow_for_the_titles_shows_their_short_forms_and_the_whole_ones_when_there_is_room(qtbot):
    tabs = _tabs(qtbot, 1200)
    qtbot.waitUntil(lambda: [tabs.tabToolTip(i) for i in range(4)] == list(TITLES))
    assert _texts(tabs) == list(TITLES)
    whole = _needed(tabs)
    tabs.resize(whole - 20, 200)
    qtbot.waitUntil(lambda: _texts(tabs) == list(TITLES.values()))
    assert _needed(tabs) <= tabs.width()  # the short forms fit, whole
    assert [tabs.tabToolTip(i) for i in range(4)] == list(TITLES)
    tabs.setTabVisible(1, False)  # fewer tabs: the others' whole titles fit again
    tabs.setTabVisible(2, False)
    qtbot.waitUntil(lambda: _texts(tabs) == ["Image order", "Compare"])
    tabs.setTabVisible(1, True)
    tabs.setTabVisible(2, True)
    tabs.resize(1200, 200)
    qtbot.waitUntil(lambda: _texts(tabs) == list(TITLES))


def test_presenting_at_twice_the_text_size_on_1280x720_no_tab_title_is_cut(qtbot, monkeypatch):
    """The six tabs' whole titles need more than the room they have; they read "Image", "Object",
    "Views", "Compare", "Hard cases", "Cost" (elided, they read "Image …", "Com…").  The left
    column's tabs keep their titles whole too (with "Edit scene" for "Editor" they read "Cont…",
    "Less…", "Exerc…", "Edit sc…" once the Object order tab had narrowed the column)."""
    window = presenting_on_1280x720(qtbot, monkeypatch, scale=2.0)
    tabs = window.tab_widget
    docks = next(bar for bar in window.findChildren(QTabBar) if bar.parent() is window and bar.isVisible())
    for title in window.tab_titles():
        window.show_tab(title)
        qtbot.waitUntil(lambda: _needed(tabs) <= tabs.width())
        assert _texts(tabs) == ["Image", "Object", "Views", "Compare", "Hard cases", "Cost"]
        assert [docks.tabText(i) for i in range(4)] == ["Controls", "Lessons", "Exercises", "Editor"]
        qtbot.waitUntil(lambda: sum(docks.tabSizeHint(i).width() for i in range(4)) <= docks.width())
    window.presentation.set_scale(1.0)
    window.presentation.set_presenting(False)
    qtbot.waitUntil(lambda: _texts(tabs) == window.tab_titles())
