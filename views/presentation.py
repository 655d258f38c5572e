"""Presentation mode: the window made readable from the back of a lecture hall.

:class:`Presentation` works on any QMainWindow:

- F11 enters presentation mode (full screen, text scaled, high contrast) and
  leaves it again; Esc leaves it;
- the scale is 1, 1.5 or 2 times the normal text size; every widget that
  takes its size from the application's font (labels, check boxes, typeset
  formulas, matrices, and those made later: a table's new rows, the next
  exercise's answers, dialogs) follows, and ``scale_changed`` tells the 3D
  panes to widen their lines;
- ``.`` and ``B`` (what clickers send for "blank") black the window out and
  bring it back, while presenting;
- with a :class:`views.panels.lesson_panel.LessonPanel`, the arrow keys join
  PageDown/PageUp in moving through the steps while presenting, and the
  panel hides its lesson list so the step's text and formulas get the room.

:class:`PresenterWindow` is the lecturer's screen: the current lesson's notes,
the next step and a clock, shown on the second screen when there is one.
"""

from __future__ import annotations

from PySide6.QtCore import QEvent, QObject, Qt, QTime, QTimer, Signal
from PySide6.QtGui import QAction, QActionGroup, QFont, QGuiApplication, QKeySequence
from PySide6.QtWidgets import QApplication, QLabel, QMainWindow, QVBoxLayout, QWidget

from views.high_contrast import HighContrast
from views.panels.lesson_panel import ClickerKeys, LessonPanel
from views.text.text_scale import NORMAL_TEXT_PT, normal_text_pt

#: The text scales offered (1 is the normal size).
SCALES = (1.0, 1.5, 2.0)
#: The scale presentation mode starts with.
PRESENTING_SCALE = 1.5
#: On one screen, the share of its width the presenter window takes (at its right edge).
PRESENTER_SHARE = 0.25
#: What the presenter window says on one screen.
ONE_SCREEN = ("One screen only: a projector that shows this screen shows these notes too (they may "
              "hold the exercises' answers).")

class _Blank(QWidget):
    """A black sheet over the whole window."""

    def __init__(self, parent: QWidget):
        super().__init__(parent)
        self.setAutoFillBackground(True)
        self.setStyleSheet("background-color: #000000;")
        self.setAttribute(Qt.WidgetAttribute.WA_StyledBackground, True)
        self.hide()


class Presentation(QObject):
    """Presentation mode for ``window``; optional ``panel`` for clicker navigation.

    Signals
    -------
    scale_changed(float) : the text scale now applied (1, 1.5 or 2).
    presenting_changed(bool)
    blanked_changed(bool)

    Attributes
    ----------
    actions : dict of QAction, added to the window so their keys work without
        a menu; put them in a View menu: ``"present"`` (F11, checkable),
        ``"leave"`` (Esc), ``"blank"`` (``.`` and ``B``), ``"contrast"``
        (checkable), ``"presenter"`` (the presenter window) and
        ``"scale 1"``, ``"scale 1.5"``, ``"scale 2"`` (an exclusive group).
    """

    scale_changed = Signal(float)
    presenting_changed = Signal(bool)
    blanked_changed = Signal(bool)

    def __init__(self, window: QMainWindow, panel: LessonPanel | None = None):
        super().__init__(window)
        self.window = window
        self.panel = panel
        self._scale = 1.0
        self._presenting = False
        self._contrast = HighContrast(window)
        self._normal_pt = normal_text_pt()
        self._was_maximized = False
        self._normal_geometry = window.geometry()
        self._blank = _Blank(window)
        self._stages: list = []  # what entering or leaving presentation mode has still to do
        self._stage_timer = QTimer(self, singleShot=True, interval=0)
        self._stage_timer.timeout.connect(self._next_stage)
        # Style sheets (high contrast; a widget's own colours) would otherwise keep the widgets
        # under them at the font they had when styled: a new text size would not reach them.
        QApplication.setAttribute(Qt.ApplicationAttribute.AA_UseStyleSheetPropagationInWidgetStyles)
        window.installEventFilter(self)
        self.clicker = None
        if panel is not None:
            self.clicker = ClickerKeys(panel, self)
            self.clicker.install()
        self.presenter: PresenterWindow | None = None
        self.actions = self._make_actions()

    def _make_actions(self) -> dict[str, QAction]:
        w = self.window
        acts = {}

        def add(key, text, slot, shortcuts=(), checkable=False, toggles=True):
            a = QAction(text, w)
            a.setCheckable(checkable)
            a.setShortcuts([QKeySequence(s) for s in shortcuts])
            a.setShortcutContext(Qt.ShortcutContext.WindowShortcut)
            (a.toggled if checkable and toggles else a.triggered).connect(slot)
            w.addAction(a)
            acts[key] = a
            return a

        add("present", "Presentation mode", self.set_presenting, ["F11"], checkable=True)
        add("leave", "Leave presentation mode", lambda: self.set_presenting(False), ["Esc"])
        add("blank", "Blank the screen", self.toggle_blank, [".", "B"])
        add("contrast", "High contrast", self.set_high_contrast, checkable=True)
        add("presenter", "Presenter window", self.show_presenter)
        group = QActionGroup(w)
        for s in SCALES:
            a = add(f"scale {s:g}", f"Text size ×{s:g}", lambda _=False, s=s: self.set_scale(s),
                    checkable=True, toggles=False)
            group.addAction(a)
        acts["scale 1"].setChecked(True)
        acts["blank"].setEnabled(False)
        acts["leave"].setEnabled(False)
        return acts

    # --- state --------------------------------------------------------------

    def scale(self) -> float:
        return self._scale

    def presenting(self) -> bool:
        return self._presenting

    def blanked(self) -> bool:
        return self._blank.isVisible()

    def high_contrast(self) -> bool:
        return self._contrast.on()

    def set_scale(self, scale: float) -> None:
        """Scale the window's text (and all that follows its font) to ``scale`` times normal."""
        if scale not in SCALES:
            raise ValueError(f"scale must be one of {', '.join(f'{s:g}' for s in SCALES)}, got {scale!r}")
        if float(scale) != self._scale:
            self._scale = float(scale)
            self._paint_once_settled()
            self._apply_font()
        action = self.actions[f"scale {scale:g}"]
        if not action.isChecked():
            action.setChecked(True)
        self.scale_changed.emit(self._scale)

    def set_high_contrast(self, on: bool) -> None:
        self._contrast.set_on(on)
        if self.actions["contrast"].isChecked() != self.high_contrast():
            self.actions["contrast"].setChecked(self.high_contrast())

    def text_size_pt(self) -> float:
        """The window's text size now, in points."""
        return self._normal_pt * self._scale

    def scale_normal_text(self, factor: float) -> None:
        """Make the normal text size ``factor`` times larger (7 to 40 points); the scale stays."""
        self._normal_pt = max(7.0, min(40.0, self._normal_pt * factor))
        self._paint_once_settled()
        self._apply_font()

    def _paint_once_settled(self) -> None:
        """Paint the window once, two turns of the event loop from now, when the new text size has
        been laid out and the window has shared its room again (its refit, a turn later): laid out
        and painted in one turn, a new text size held the window 57-61 ms (``bench gui``).  While
        entering or leaving presentation mode, that is painted once at its end already."""
        if self._stages or not self.window.updatesEnabled():
            return
        self.window.setUpdatesEnabled(False)
        self._stages = [_layouts, self._paint_now]
        self._stage_timer.start()

    def _apply_font(self) -> None:
        # The application's font, not the window's: a widget made later (a table's new row, the
        # next exercise's answers) is born at this size; under the style sheets' propagation
        # (above) it would keep the application's size instead of inheriting the window's.  Only
        # the font: no widget is styled again, as a new style sheet would have each one be.
        QApplication.instance().setProperty(NORMAL_TEXT_PT, self._normal_pt)
        font = QFont(QApplication.font())
        font.setPointSizeF(self.text_size_pt())
        QApplication.setFont(font)
        # Every widget has it on return (Qt posts the change where no event loop runs yet).
        QApplication.sendPostedEvents(None, QEvent.Type.ApplicationFontChange)

    def set_presenting(self, on: bool) -> None:
        """Enter (full screen, ×1.5 text, high contrast, arrow keys step) or leave presentation mode.

        The text size changes at once; the colours and the window's size follow, each in a turn of
        the event loop of its own, so that none holds the window long (``settled`` says when all
        are done, and ``presenting_changed`` is sent then).  The window is painted once, in its
        final look: painted at each turn, each turn held it for a paint of everything (the longest
        stall of an enter or leave, median of 10, 56-61 ms against 36-37 at 1600 × 900), and the
        hall saw the big text in the small window on the way.
        """
        on = bool(on)
        if on == self._presenting:
            return
        self._presenting = on
        self.window.setUpdatesEnabled(False)
        if on:
            if not self.window.isFullScreen():  # not while still leaving
                self._was_maximized = self.window.isMaximized()
                self._normal_geometry = self.window.geometry()
            self.set_scale(max(self._scale, PRESENTING_SCALE))
        else:
            self.set_blanked(False)
            self.set_scale(1.0)
        if self.clicker is not None:
            self.clicker.arrows = on
            self.panel.set_compact(on)
        self.actions["blank"].setEnabled(on)
        self.actions["leave"].setEnabled(on)
        if self.actions["present"].isChecked() != on:
            self.actions["present"].setChecked(on)
        # Each stage's layouts are done in a turn of their own (the turn of a stage that does nothing):
        # done with the next stage, the font's layouts and the colours took one turn 44-68 ms long.
        self._stages = [_layouts, lambda: self.set_high_contrast(on), _layouts,
                        self._enter_screen if on else self._leave_screen,
                        self._paint_now, lambda: self.presenting_changed.emit(on)]
        self._stage_timer.start()

    def settled(self) -> bool:
        """Whether entering or leaving presentation mode is done (colours and window size too)."""
        return not self._stages

    def _next_stage(self) -> None:
        try:
            if self._stages:
                self._stages.pop(0)()
        finally:  # the stages after one that failed still run: the window is painted again
            if self._stages:
                self._stage_timer.start()

    def _paint_now(self) -> None:
        """Paint the window again, in this turn: its updates were held while it was laid out.

        Re-enabled, updates are asked for (Qt's ``update``), but where a request came while they were
        held, Qt kept the parts to paint marked and asked for no new one: nothing was painted until
        the window system sent an expose.  While the 3D pane made the window's panes windows of the
        window system of their own, their exposes came at once; without them, a new text size was
        not painted within 30 s in about half the runs of a test.  ``repaint`` paints those parts now.
        """
        self.window.setUpdatesEnabled(True)
        self.window.repaint()

    def _enter_screen(self) -> None:
        # The whole screen even where no window manager honours "full screen" (a bare X server).
        self.window.setGeometry(self.window.screen().geometry())
        self.window.showFullScreen()

    def _leave_screen(self) -> None:
        if self._was_maximized:
            self.window.showMaximized()
        else:
            self.window.showNormal()
            self.window.setGeometry(self._normal_geometry)

    def set_blanked(self, on: bool) -> None:
        """Black the window out (``on``) or bring it back."""
        if on == self.blanked():
            return
        if on:
            self._blank.setGeometry(self.window.rect())
            self._blank.raise_()
            self._blank.show()
        else:
            self._blank.hide()
        self.blanked_changed.emit(bool(on))

    def toggle_blank(self) -> None:
        self.set_blanked(not self.blanked())

    def eventFilter(self, watched, event) -> bool:
        if watched is self.window and event.type() == QEvent.Type.Resize and self.blanked():
            self._blank.setGeometry(self.window.rect())
        return False

    # --- the presenter's screen ---------------------------------------------

    def show_presenter(self) -> PresenterWindow:
        """Open the presenter window, on the second screen if there is one."""
        if self.presenter is None:
            self.presenter = PresenterWindow(self.panel)
        screens = QGuiApplication.screens()
        mine = self.window.screen()
        others = [s for s in screens if s is not mine]
        if others:
            self.presenter.setGeometry(others[0].availableGeometry())
        else:
            self._beside_the_window(mine.availableGeometry())
        self.presenter.set_one_screen(not others)
        self.presenter.show()
        return self.presenter

    def _beside_the_window(self, screen) -> None:
        """One screen: the presenter window takes a column at its right edge, and the main window
        (unless full screen or maximized) the rest, so that neither covers the other."""
        window = self.window
        frame, inner = window.frameGeometry(), window.geometry()  # the window manager's frame, as the
        left_edge, top_edge = inner.left() - frame.left(), inner.top() - frame.top()  # presenter gets it
        extra_width, extra_height = frame.width() - inner.width(), frame.height() - inner.height()
        column = round(screen.width() * PRESENTER_SHARE)
        right = screen.right() + 1 - column  # the column's left edge
        self.presenter.setGeometry(right + left_edge, screen.top() + top_edge, column - extra_width,
                                   screen.height() - extra_height)
        if not (window.isFullScreen() or window.isMaximized()) and frame.right() >= right:
            left = max(screen.left(), min(frame.left(), right - frame.width()))
            window.setGeometry(left + left_edge, inner.top(), min(inner.width(), right - left - extra_width),
                               inner.height())


def _layouts() -> None:
    """A stage of entering or leaving presentation mode that does nothing: its turn of the event loop
    lays out what the stage before changed."""


def _enlarged(label: QLabel, times: float, bold: bool = False) -> QLabel:
    """``label``, its text ``times`` the normal text size (bold if ``bold``): the lecturer's screen
    keeps its size while the hall's text is scaled."""
    font = QFont(label.font())
    font.setPointSizeF(normal_text_pt() * times)
    font.setBold(bold)
    label.setFont(font)
    return label


class PresenterWindow(QWidget):
    """The lecturer's view: this step's notes, the next step, and the time."""

    def __init__(self, panel: LessonPanel | None, parent: QWidget | None = None):
        super().__init__(parent, Qt.WindowType.Window)
        self.setWindowTitle("Render Explorer — presenter")
        self.panel = panel
        self.clock = _enlarged(QLabel(), 2.5, bold=True)
        self.current = _enlarged(QLabel(), 1.5, bold=True)
        self.current.setWordWrap(True)
        self.notes = _enlarged(QLabel(), 1.4)
        self.notes.setWordWrap(True)
        self.upcoming = _enlarged(QLabel(), 1.0)
        self.upcoming.setWordWrap(True)
        self.one_screen = QLabel(ONE_SCREEN)  # the notes may hold answers
        self.one_screen.setWordWrap(True)
        self.one_screen.hide()
        layout = QVBoxLayout(self)
        for w in (self.one_screen, self.clock, self.current, self.notes):
            layout.addWidget(w)
        layout.addStretch(1)
        layout.addWidget(_enlarged(QLabel("Next:"), 1.0))
        layout.addWidget(self.upcoming)
        self._timer = QTimer(self)
        self._timer.timeout.connect(self._tick)
        self._timer.start(1000)
        self._tick()
        if panel is not None:
            panel.step_selected.connect(lambda _step: self.refresh())
        self.refresh()

    def set_one_screen(self, one: bool) -> None:
        """Say (or not) that there is only one screen, which the room may see too."""
        self.one_screen.setVisible(one)

    def _tick(self) -> None:
        self.clock.setText(QTime.currentTime().toString("HH:mm:ss"))

    def refresh(self) -> None:
        """Show the panel's current step and the one after it."""
        if self.panel is None or self.panel.current_lesson() is None:
            self.current.setText("No lesson open")
            self.notes.clear()
            self.upcoming.clear()
            return
        lesson, step = self.panel.current_lesson(), self.panel.current_step()
        k = self.panel.step_index()[1]
        self.current.setText(f"{lesson.title} — step {k + 1} of {len(lesson.steps)}: {step.title}")
        self.notes.setText(step.notes or "(no notes for this step)")
        following = self.panel.next_step()
        if following is None:
            self.upcoming.setText("(the end of the last lesson)")
        else:
            nxt_lesson, nxt = following
            prefix = "" if nxt_lesson is lesson else f"{nxt_lesson.title}: "
            self.upcoming.setText(f"{prefix}{nxt.title}\n{nxt.text}")
