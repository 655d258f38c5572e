"""A scrubber over the steps of a render: drag, single-step, or play.

Step k means "after the first k polygons"; step 0 is the cleared buffers.
"""

from __future__ import annotations

from PySide6.QtCore import Qt, QTimer, Signal
from PySide6.QtWidgets import QHBoxLayout, QLabel, QSlider, QStyle, QToolButton, QWidget

from views.text.text_scale import icons_follow_text

PLAY_INTERVAL_MS = 120


class StepScrubber(QWidget):
    """Slider, first/back/play/forward/last buttons and a caption.

    Signals
    -------
    step_changed(int) : the step now shown, 0..count.
    """

    step_changed = Signal(int)

    def __init__(self, parent: QWidget | None = None):
        super().__init__(parent)
        self.slider = QSlider(Qt.Orientation.Horizontal)
        self.slider.setToolTip("Step k: image memory and z-buffer after the first k polygons")
        self.caption = QLabel()
        self._timer = QTimer(self)
        self._timer.setInterval(PLAY_INTERVAL_MS)
        self._timer.timeout.connect(self._advance)
        layout = QHBoxLayout(self)
        layout.setContentsMargins(0, 0, 0, 0)
        icon = self.style().standardIcon
        buttons = [
            (QStyle.StandardPixmap.SP_MediaSkipBackward, "First step: the cleared buffers", self.first),
            (QStyle.StandardPixmap.SP_MediaSeekBackward, "Previous polygon",
             lambda: self.set_step(self.step - 1)),
            (QStyle.StandardPixmap.SP_MediaPlay, "Play / pause", self.toggle_play),
            (QStyle.StandardPixmap.SP_MediaSeekForward, "Next polygon",
             lambda: self.set_step(self.step + 1)),
            (QStyle.StandardPixmap.SP_MediaSkipForward, "Last step: the finished image", self.last),
        ]
        tools = []
        for pixmap, tip, slot in buttons:
            button = QToolButton()
            tools.append(button)
            button.setIcon(icon(pixmap))
            button.setToolTip(tip)
            button.clicked.connect(slot)
            layout.addWidget(button)
            if pixmap == QStyle.StandardPixmap.SP_MediaPlay:
                self.play_button = button
        icons_follow_text(self, tools)
        layout.addWidget(self.slider, 1)
        layout.addWidget(self.caption)
        self.slider.valueChanged.connect(self.step_changed)
        self.set_count(0)

    @property
    def step(self) -> int:
        return self.slider.value()

    @property
    def playing(self) -> bool:
        return self._timer.isActive()

    def set_count(self, count: int) -> None:
        """Steps run from 0 to ``count``; the scrubber moves to the last one."""
        self.slider.setRange(0, count)
        self.slider.setValue(count)

    def set_step(self, step: int) -> None:
        self.slider.setValue(max(0, min(self.slider.maximum(), step)))

    def first(self) -> None:
        self.set_step(0)

    def last(self) -> None:
        self.set_step(self.slider.maximum())

    def toggle_play(self) -> None:
        # The icons are asked for each time, not kept: a kept icon outlived its scrubber in a cycle,
        # which a render's thread could free, and an icon's pixmaps are the GUI thread's only.
        if self.playing:
            self._timer.stop()
            self.play_button.setIcon(self.style().standardIcon(QStyle.StandardPixmap.SP_MediaPlay))
        else:
            if self.step >= self.slider.maximum():
                self.first()
            self._timer.start()
            self.play_button.setIcon(self.style().standardIcon(QStyle.StandardPixmap.SP_MediaPause))

    def _advance(self) -> None:
        if self.step >= self.slider.maximum():
            self.toggle_play()
        else:
            self.set_step(self.step + 1)
