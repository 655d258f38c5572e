"""The z-buffer steps' scrubber: Play runs the steps to the last and stops there, its button showing
what a click would do; and the scrubber keeps no icon of its own, which a thread collecting Python's
garbage could free (pixmaps are the GUI thread's)."""

import pytest
from PySide6.QtGui import QIcon
from PySide6.QtWidgets import QStyle

from views.panels.step_scrubber import StepScrubber


def _shows(button, pixmap) -> bool:
    drawn = button.style().standardIcon(pixmap).pixmap(16).toImage()
    return button.icon().pixmap(16).toImage() == drawn


@pytest.mark.gui
def test_play_runs_the_steps_to_the_last_and_stops(qtbot):
    scrubber = StepScrubber()
    qtbot.addWidget(scrubber)
    scrubber.set_count(4)
    scrubber.first()
    scrubber.toggle_play()
    assert scrubber.playing and _shows(scrubber.play_button, QStyle.StandardPixmap.SP_MediaPause)
    qtbot.waitUntil(lambda: not scrubber.playing)
    assert scrubber.step == 4
    assert _shows(scrubber.play_button, QStyle.StandardPixmap.SP_MediaPlay)


@pytest.mark.gui
def test_the_scrubber_keeps_no_icon_of_its_own(qtbot):
    scrubber = StepScrubber()
    qtbot.addWidget(scrubber)
    scrubber.toggle_play()
    scrubber.toggle_play()
    assert not [v for v in vars(scrubber).values() if isinstance(v, QIcon)]
