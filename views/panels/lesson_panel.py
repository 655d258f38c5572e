"""The lesson panel: the lecture's lessons in order, the current step's text and formulas.

:class:`LessonPanel` lists the lessons (:func:`core.lessons.lesson_file.shipped_lessons`
plus any opened from a file), shows the current step's title, text and typeset
formulas, and moves through steps and lessons.  Whenever a step becomes
current it emits ``step_selected(LessonStep)``; applying the step (scene,
camera, panes, settings, highlight) is the window's job.

:class:`ClickerKeys` makes PageDown/PageUp (what presentation clickers send)
move through the steps from anywhere in the application, and nothing else.

Wiring it into a window::

    panel = LessonPanel()                      # loads the shipped lessons
    panel.step_selected.connect(window.apply_lesson_step)
    presentation = Presentation(window, panel) # views.presentation; installs ClickerKeys
    file_menu.addAction("Open lesson file…", panel.open_lesson_file)
    for action in presentation.actions.values(): view_menu.addAction(action)

where ``apply_lesson_step(step)`` loads ``step.scene``, shows ``step.panes``
(the first in front) and hides the others, applies ``step.image_order`` /
``step.object_order``, ``step.view``, ``step.overlays``, sets the scrubber to
``step.zbuffer_step`` and picks ``step.pixel`` when they are not None, and
marks ``step.highlight``; see :class:`core.lessons.lesson_file.LessonStep`.
"""

from __future__ import annotations

from pathlib import Path

from PySide6.QtCore import QEvent, QObject, Qt, Signal
from PySide6.QtGui import QFont
from PySide6.QtWidgets import (
    QFrame,
    QHBoxLayout,
    QLabel,
    QListWidget,
    QListWidgetItem,
    QMessageBox,
    QPushButton,
    QScrollArea,
    QSizePolicy,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from core.lessons.lesson_file import Lesson, LessonFileError, LessonStep, load_lesson, shipped_lessons
from views.file_dialogs import ask_open
from views.images.image_view import ARROWS, ImageView
from views.keyboard_focus import follow_focus
from views.text.math_view import MathView

#: Keys that go forward and back.  PageDown/PageUp act everywhere (ClickerKeys);
#: the arrows act when the panel has the focus, or everywhere while presenting.
NEXT_KEYS = (Qt.Key.Key_PageDown, Qt.Key.Key_Right, Qt.Key.Key_Down)
PREVIOUS_KEYS = (Qt.Key.Key_PageUp, Qt.Key.Key_Left, Qt.Key.Key_Up)


def lesson_label(lesson: Lesson) -> str:
    """The lesson's line in the list: title and the lecture figures and questions it shows."""
    refs = [f"Fig. {f}" for f in lesson.figures] + [f"Q{q}" for q in lesson.questions]
    return lesson.title + (f"  ({', '.join(refs)})" if refs else "")


class _LessonList(QListWidget):
    """The list of lessons, the open one kept in view when the list is resized (the left column's
    share changes with each step's words)."""

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        if self.currentItem() is not None:
            self.scrollToItem(self.currentItem())


class LessonPanel(QWidget):
    """Lesson list, the current step (title, text, formulas) and step controls.

    Signals
    -------
    step_selected(LessonStep) : a step became current; the window applies it.
    lesson_opened(Lesson) : a lesson file was loaded (the window checks its facts).
    """

    step_selected = Signal(object)
    lesson_opened = Signal(object)

    def __init__(self, lessons: list[Lesson] | None = None, parent: QWidget | None = None):
        super().__init__(parent)
        self._lessons: list[Lesson] = []
        self._lesson = -1
        self._step = 0
        self._pending = False  # the current step is not what the window shows (see leave_step)
        self.setFocusPolicy(Qt.FocusPolicy.StrongFocus)

        self.list = _LessonList()
        self.list.setWordWrap(True)
        self.list.setToolTip("The lecture's lessons in order; click one to start it")
        self.list.currentRowChanged.connect(self._on_row)
        self.list.itemClicked.connect(self._on_click)

        self.lesson_title = QLabel()
        self.lesson_title.setWordWrap(True)
        bold = QFont()  # only the weight: the size follows the window (presentation scale)
        bold.setBold(True)
        self.lesson_title.setFont(bold)
        self.step_title = QLabel()
        self.step_title.setWordWrap(True)
        self.step_title.setFont(bold)
        self.text = QLabel()
        self.text.setWordWrap(True)
        self.text.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
        self.text.setSizePolicy(QSizePolicy.Policy.Preferred, QSizePolicy.Policy.MinimumExpanding)
        self.text.setAlignment(Qt.AlignmentFlag.AlignTop | Qt.AlignmentFlag.AlignLeft)
        self.formulas = QVBoxLayout()
        self.formulas.setSpacing(2)

        self.previous_button = QPushButton("◀ Previous")
        self.previous_button.setToolTip("Previous step (PageUp)")
        self.previous_button.clicked.connect(self.previous)
        self.next_button = QPushButton("Next ▶")
        self.next_button.setToolTip("Next step (PageDown)")
        self.next_button.clicked.connect(self.next)
        self.position = QLabel()
        self.position.setAlignment(Qt.AlignmentFlag.AlignCenter)
        self.open_button = QPushButton("Open lesson file…")
        self.open_button.clicked.connect(lambda: self.open_lesson_file())
        for b in (self.previous_button, self.next_button, self.open_button):
            b.setFocusPolicy(Qt.FocusPolicy.NoFocus)  # arrows and PageUp/Down stay with the panel

        controls = QHBoxLayout()
        controls.addWidget(self.previous_button)
        controls.addWidget(self.position, 1)
        controls.addWidget(self.next_button)

        words = QWidget()
        words_layout = QVBoxLayout(words)
        words_layout.setContentsMargins(0, 0, 0, 0)
        words_layout.addWidget(self.lesson_title)
        words_layout.addWidget(self.step_title)
        words_layout.addWidget(self.text)
        words_layout.addLayout(self.formulas)
        words_layout.addStretch(1)
        self.scroll = QScrollArea()  # long text at a large scale scrolls; the controls stay in view
        self.scroll.setWidgetResizable(True)
        self.scroll.setFrameShape(QFrame.Shape.NoFrame)
        # A formula too long for the panel breaks into lines; one line still too long scrolls sideways.
        self.scroll.setHorizontalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAsNeeded)
        self.scroll.setWidget(words)
        step = QWidget()
        step_layout = QVBoxLayout(step)
        step_layout.setContentsMargins(0, 0, 0, 0)
        step_layout.addWidget(self.scroll, 1)
        step_layout.addLayout(controls)

        self.list_area = top = QWidget()
        top_layout = QVBoxLayout(top)
        top_layout.setContentsMargins(0, 0, 0, 0)
        top_layout.addWidget(self.list, 1)
        top_layout.addWidget(self.open_button)

        self.splitter = QSplitter(Qt.Orientation.Vertical)
        self.splitter.addWidget(top)
        self.splitter.addWidget(step)
        self.splitter.setStretchFactor(0, 1)
        self.splitter.setStretchFactor(1, 3)
        self.splitter.setSizes([200, 600])  # the step's words get more room than the list
        self.splitter.setChildrenCollapsible(False)
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 4, 4, 4)
        layout.addWidget(self.splitter)

        self.set_lessons(shipped_lessons() if lessons is None else lessons)
        # Opened before anyone listens: the window does not show this step yet, so the first
        # Next shows it rather than skipping it.
        self._pending = True

    def set_compact(self, compact: bool) -> None:
        """Hide the lesson list (presentation mode: the room sees only the lesson)."""
        self.list_area.setVisible(not compact)

    # --- the lessons --------------------------------------------------------

    def lessons(self) -> list[Lesson]:
        return list(self._lessons)

    def set_lessons(self, lessons: list[Lesson]) -> None:
        """Replace the list and open the first lesson's first step (if any)."""
        self._lessons = list(lessons)
        self.list.blockSignals(True)
        self.list.clear()
        for lesson in self._lessons:
            item = QListWidgetItem(lesson_label(lesson))
            item.setToolTip(lesson.summary)
            self.list.addItem(item)
        self.list.blockSignals(False)
        self._lesson = -1
        if self._lessons:
            self.select(0, 0)
        else:
            self._show()

    def set_note(self, lesson: int, note: str) -> None:
        """Show ``note`` (e.g. exercise progress) under lesson ``lesson``'s line in the list."""
        item = self.list.item(lesson)
        label = lesson_label(self._lessons[lesson])
        item.setText(f"{label}\n    {note}" if note else label)

    def current_lesson(self) -> Lesson | None:
        return self._lessons[self._lesson] if 0 <= self._lesson < len(self._lessons) else None

    def current_step(self) -> LessonStep | None:
        lesson = self.current_lesson()
        return lesson.steps[self._step] if lesson is not None else None

    def step_index(self) -> tuple[int, int]:
        """``(lesson, step)``, both 0-based; ``(-1, 0)`` with no lesson."""
        return self._lesson, self._step

    def next_step(self) -> tuple[Lesson, LessonStep] | None:
        """The step :meth:`next` would go to (for the presenter window), or None at the very end."""
        target = self._moved(+1)
        if target is None:
            return None
        lesson = self._lessons[target[0]]
        return lesson, lesson.steps[target[1]]

    def select(self, lesson: int, step: int = 0) -> None:
        """Make step ``step`` of lesson ``lesson`` current and emit ``step_selected``."""
        if not 0 <= lesson < len(self._lessons):
            raise IndexError(f"no lesson {lesson}: there are {len(self._lessons)}")
        steps = self._lessons[lesson].steps
        if not 0 <= step < len(steps):
            raise IndexError(f"no step {step}: lesson {self._lessons[lesson].id!r} has {len(steps)}")
        self._lesson, self._step = lesson, step
        self._pending = False
        self.list.blockSignals(True)
        self.list.setCurrentRow(lesson)
        self.list.blockSignals(False)
        self._show()
        self.step_selected.emit(steps[step])

    def _on_row(self, row: int) -> None:
        if 0 <= row < len(self._lessons) and row != self._lesson:
            self.select(row, 0)

    def _on_click(self, item: QListWidgetItem) -> None:
        """A click on the lesson already open shows its step again (the first click after start)."""
        if self.list.row(item) == self._lesson:
            self.select(self._lesson, self._step)

    def _moved(self, delta: int) -> tuple[int, int] | None:
        if self.current_lesson() is None:
            return None
        lesson, step = self._lesson, self._step + delta
        if step >= len(self._lessons[lesson].steps):
            lesson, step = lesson + 1, 0
        elif step < 0:
            lesson -= 1
            step = len(self._lessons[lesson].steps) - 1 if lesson >= 0 else 0
        return (lesson, step) if 0 <= lesson < len(self._lessons) else None

    def leave_step(self, why: str) -> None:
        """The window no longer shows the current step (``why``: what it shows instead).

        The step's text gives way to ``why``, so no sentence describes a picture that is gone;
        the next Next (PageDown) shows the step again instead of skipping it.
        """
        if self.current_step() is None:
            return
        self._pending = True
        self._show()
        self.text.setText(f"{why} Press Next (PageDown) to show this step again.")
        self._clear_formulas()

    def next(self) -> bool:
        """Go to the next step, or the next lesson's first step; False at the very end.

        When the window does not show the current step (just opened, or :meth:`leave_step`), show
        that step instead.
        """
        if self._pending and self.current_step() is not None:
            self.select(*self.step_index())
            return True
        target = self._moved(+1)
        if target is not None:
            self.select(*target)
        return target is not None

    def previous(self) -> bool:
        """Go to the previous step, or the previous lesson's last step; False at the very start."""
        target = self._moved(-1)
        if target is not None:
            self.select(*target)
        return target is not None

    def open_lesson_file(self, path=None) -> Lesson | None:
        """Load a lesson file (asking for one when ``path`` is None), add it to the list and start it.

        A file that does not load is reported in a dialog listing every
        problem, and nothing else changes.
        """
        if path is None:
            path = ask_open(self, "Open lesson file", "Lesson files (*.json);;All files (*)")
            if not path:
                return None
        try:
            lesson = load_lesson(path)
        except LessonFileError as exc:
            box = QMessageBox(QMessageBox.Icon.Warning, "Cannot open lesson file",
                              f"{Path(path).name} cannot be used as a lesson:", QMessageBox.StandardButton.Ok,
                              self)
            box.setInformativeText("\n".join(exc.problems[:12]) + (
                f"\n... and {len(exc.problems) - 12} more" if len(exc.problems) > 12 else ""))
            box.setDetailedText(str(exc))
            box.setObjectName("lesson_error")
            box.open()
            return None
        self._lessons.append(lesson)
        item = QListWidgetItem(lesson_label(lesson))
        item.setToolTip(f"{lesson.summary}\n{path}")
        self.list.addItem(item)
        self.select(len(self._lessons) - 1, 0)
        self.lesson_opened.emit(lesson)
        return lesson

    # --- showing the step ---------------------------------------------------

    def formula_views(self) -> list[MathView]:
        """The typeset formulas of the current step, top to bottom."""
        return [self.formulas.itemAt(i).widget() for i in range(self.formulas.count())]

    def typesetting(self) -> bool:
        """Whether a formula of the current step is still being typeset (off the GUI thread: it shows
        once typeset, and meanwhile no formula of another step shows)."""
        return any(view.pending for view in self.formula_views())

    def _clear_formulas(self) -> None:
        while self.formulas.count():
            widget = self.formulas.takeAt(0).widget()
            widget.hide()
            widget.deleteLater()

    def _show(self) -> None:
        self._clear_formulas()
        lesson, step = self.current_lesson(), self.current_step()
        if lesson is None:
            for label in (self.lesson_title, self.step_title, self.text, self.position):
                label.clear()
            self.previous_button.setEnabled(False)
            self.next_button.setEnabled(False)
            return
        self.lesson_title.setText(lesson.title)
        self.step_title.setText(step.title)
        self.text.setText(step.text)
        for formula in step.formulas:
            self.formulas.addWidget(MathView(formula, self.formulas.parentWidget(), later=True))
        self.position.setText(f"step {self._step + 1} of {len(lesson.steps)}")
        self.previous_button.setEnabled(self._moved(-1) is not None)
        self.next_button.setEnabled(self._pending or self._moved(+1) is not None)

    def keyPressEvent(self, event) -> None:
        if event.key() in NEXT_KEYS:
            self.next()
        elif event.key() in PREVIOUS_KEYS:
            self.previous()
        else:
            super().keyPressEvent(event)


class ClickerKeys(QObject):
    """A key filter for the whole application: PageDown/PageUp step through ``panel``'s lessons.

    Installed on whichever widget has the keyboard focus (:mod:`views.keyboard_focus`),
    it takes these two keys before that widget or any shortcut sees them, so they
    mean "next" and "previous" everywhere and nothing else.  With ``arrows`` on
    (presentation mode) the arrow keys do the same, except in a focused picture that
    picks pixels, which keeps them to move its picked pixel (Tab or a click gave it the focus).
    """

    def __init__(self, panel: LessonPanel, parent: QObject | None = None):
        super().__init__(parent or panel)
        self.panel = panel
        self.arrows = False
        self._focus = None

    def install(self) -> None:
        if self._focus is None:
            self._focus = follow_focus(self)

    def remove(self) -> None:
        if self._focus is not None:
            self._focus.stop()
            self._focus = None

    def _keys(self):
        if self.arrows:
            return NEXT_KEYS, PREVIOUS_KEYS
        return (Qt.Key.Key_PageDown,), (Qt.Key.Key_PageUp,)

    def eventFilter(self, watched, event) -> bool:
        if event.type() not in (QEvent.Type.KeyPress, QEvent.Type.ShortcutOverride):
            return False
        forward, back = self._keys()
        key = event.key()
        if key not in forward and key not in back:
            return False
        if key in ARROWS and isinstance(watched, ImageView) and watched.pickable:
            return False
        if event.type() == QEvent.Type.ShortcutOverride:
            event.accept()  # no shortcut may take the key: it arrives as a key press, here
        elif key in forward:
            self.panel.next()
        else:
            self.panel.previous()
        return True
