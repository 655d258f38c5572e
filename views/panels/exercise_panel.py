"""The exercise panel: a lesson's exercises asked one by one, answered, and judged at once.

The student predicts, then checks: :class:`ExercisePanel` shows the question
and an answer widget for its kind (choices, a number, a pixel, a list to put in
order), or pictures to pick from, and judges the answer with :func:`core.lessons.exercises.judge`, which
asks the pipelines.  Feedback comes at once: right or wrong and one sentence
why; a wrong answer is told what is wrong with it, never the answer, and gets a second try;
Enter checks; "Show me" asks the window to show the step (and the pixel the question names, or
for a pixel exercise a right pixel); "Reveal" gives the answer (for a pixel exercise it picks a right
pixel too).  Until it is answered right or revealed, an exercise is
:attr:`ExercisePanel.waiting_for` its answer, and the window withholds the readouts that would give
it away (:mod:`app.lessons.withheld_answers`) and says when it shows another scene than the one
asked about (:mod:`app.lessons.asked_scene`).

While presenting, :meth:`ExercisePanel.set_room` puts the question to the room:
large, with the answers hidden until Space (or "Show answers") reveals them.

:class:`ExerciseProgress` keeps, per lesson, which exercises were answered and
which right at the first try, in ``QSettings`` (so across restarts), and can
forget them, and the student's seed, which draws their variant of each exercise.
"""

from __future__ import annotations

import random

from PySide6.QtCore import QCoreApplication, QEvent, QRect, QSettings, QSize, Qt, QTimer, Signal
from PySide6.QtGui import QFont, QFontMetrics
from PySide6.QtWidgets import (
    QApplication,
    QButtonGroup,
    QFrame,
    QGridLayout,
    QHBoxLayout,
    QLabel,
    QLineEdit,
    QListWidget,
    QPushButton,
    QRadioButton,
    QScrollArea,
    QVBoxLayout,
    QWidget,
)

from core.lessons.exercises import (
    Exercise,
    a_right_pixel,
    choice_label,
    judge,
    named_pixel,
    number,
    pictures,
    right_choices,
    right_order,
    variant,
)
from core.lessons.facts import StepPipelines
from views.images.image_view import ImageView, zoom_together

FIRST_TRY, LATER, REVEALED = "first try", "later", "revealed"
RIGHT_COLOR, WRONG_COLOR = "#1b8a3a", "#c62828"
ROOM_SCALE = 1.8
"""The question's size, put to the room, relative to the panel's font."""
ROOM_LEAST = 0.8
"""The least size of a long question put to the room, relative to the panel's font (presenting at x2,
1.6 times the normal text)."""
PICTURE_LEAST = 108
"""The height a long question put to the room leaves each picture to pick (as its width allows)."""


OPEN_A_LESSON = ("Pick a step in the Lessons tab (or press PageDown): the exercises of its lesson "
                 "are asked here, on the lesson's scene.")

class Missing(str):
    """What an answer lacks, in a sentence (an answer may itself be a string: a view's name)."""


class ExerciseProgress:
    """Which exercises of each lesson were answered, and how, kept in ``settings``.

    Keys are ``exercises/<lesson id>/<index>``, values :data:`FIRST_TRY`,
    :data:`LATER` or :data:`REVEALED`.
    """

    def __init__(self, settings: QSettings):
        self.settings = settings

    def record(self, lesson_id: str, index: int, outcome: str) -> None:
        """Note an exercise's outcome (the first one stays: a later answer does not undo it)."""
        key = f"exercises/{lesson_id}/{index}"
        if self.settings.value(key) is None:
            self.settings.setValue(key, outcome)
            self.settings.sync()

    def outcome(self, lesson_id: str, index: int) -> str | None:
        return self.settings.value(f"exercises/{lesson_id}/{index}")

    def summary(self, lesson) -> str:
        """``"2/3 done, 1 right at first try"``, or "" before any answer."""
        outcomes = [self.outcome(lesson.id, k) for k in range(len(lesson.exercises))]
        done = sum(o is not None for o in outcomes)
        if not done:
            return ""
        return f"{done}/{len(outcomes)} done, {outcomes.count(FIRST_TRY)} right at first try"

    def seed(self) -> int:
        """This student's seed for exercise variants, drawn once and kept."""
        value = self.settings.value("exercise_seed")
        if value is None:
            value = random.randrange(1 << 30)
            self.settings.setValue("exercise_seed", value)
            self.settings.sync()
        return int(value)

    def reset(self, lesson_id: str | None = None) -> None:
        """Forget one lesson's progress, or every lesson's."""
        self.settings.remove(f"exercises/{lesson_id}" if lesson_id else "exercises")
        self.settings.sync()


class _Picture(ImageView):
    """A picture to pick: as tall as its width gives it (4:3), so that the dock's width, widened where
    the pane the exercise covers leaves room, makes it larger (at a fixed 120 pixels high it showed
    88 x 66 at text x2 on 1280 x 720)."""

    LEAST = 72
    """The least height of a picture to pick."""

    def __init__(self):
        super().__init__()
        self.setMinimumSize(96, self.LEAST)
        policy = self.sizePolicy()
        policy.setHeightForWidth(True)
        self.setSizePolicy(policy)
        self.tallest = 10_000  # the panel's room for a picture: two rows in view with the rest
        self.zoom_with_ctrl()  # the plain wheel scrolls the panel

    def hasHeightForWidth(self) -> bool:  # noqa: N802 (Qt's name)
        return True

    def heightForWidth(self, width: int) -> int:  # noqa: N802
        return max(self.LEAST, min(width * 3 // 4, self.tallest))

    def sizeHint(self) -> QSize:  # noqa: N802
        return QSize(160, 120)


class ExercisePanel(QWidget):
    """The current lesson's exercises, one at a time.

    Signals
    -------
    show_me(int step, object pixel) : show the lesson step (0-based) the exercise is about and,
        when not None, pick the pixel ``(x, y)``.
    progressed(str lesson_id) : an exercise of that lesson was answered or revealed.
    waiting(object exercise) : the exercise asked now waits for its answer; None once it is answered
        right or revealed (or when nothing is asked).  See :attr:`waiting_for`.
    answers_hidden(bool) : the answers were hidden (put to the room) or shown: the panel needs another
        height.
    """

    show_me = Signal(int, object)
    progressed = Signal(str)
    waiting = Signal(object)
    answers_hidden = Signal(bool)

    def __init__(self, progress: ExerciseProgress, run=None, parent: QWidget | None = None):
        """``run(work, done)`` runs ``work()`` (which asks the pipelines: up to a second on a large
        scene) and calls ``done(result)`` on the GUI thread; by default at once, on this thread."""
        super().__init__(parent)
        self.progress = progress
        self._run = run or (lambda work, done: done(work()))
        self.lesson = None
        self.index = 0
        self.tries = 0
        self.helped = False
        self.room = False
        self.waiting_for: Exercise | None = None  # the exercise asked and not yet answered right or revealed
        self._pipelines: dict[int, StepPipelines] = {}
        # The question is sized once a turn, whatever asked (a resize, a new text size, the answers
        # shown): entering presentation mode asked ten times, each laying out the window's layouts.
        self._sizing = QTimer(self, singleShot=True, interval=0, timeout=self._size_question)

        self.position = QLabel()
        self.question = QLabel()
        self.question.setWordWrap(True)
        self.elsewhere = QLabel()  # the window shows another scene than the one asked about
        self.elsewhere.setWordWrap(True)
        self.elsewhere.hide()
        self.answer_area = QWidget()
        self.answer_layout = QVBoxLayout(self.answer_area)
        self.answer_layout.setContentsMargins(0, 0, 0, 0)
        self.choices = QButtonGroup(self)
        self.number_edit = QLineEdit(self.answer_area)
        self.number_edit.setPlaceholderText("a number; Enter checks it")
        self.pixel_edit = QLineEdit(self.answer_area)
        self.pixel_edit.setPlaceholderText("x, y — or click the pixel in the image")
        self.order_list = QListWidget(self.answer_area)
        self.order_list.setDragDropMode(QListWidget.DragDropMode.InternalMove)
        self.order_list.setToolTip("Drag the items into order, or move the selected one with Alt+Up and "
                                   "Alt+Down")
        self.order_list.installEventFilter(self)
        self.picture_grid = QWidget(self.answer_area)  # pick_picture: each picture, its radio button
        self.picture_layout = QGridLayout(self.picture_grid)
        self.picture_views: list[ImageView] = []
        self.picture_keys: list[str] = []
        self.feedback = QLabel()
        self.feedback.setWordWrap(True)
        self.check_button = QPushButton("Check")
        self.check_button.clicked.connect(self.check)
        self.show_button = QPushButton("Show me")
        self.show_button.clicked.connect(self._show_me)
        self.reveal_button = QPushButton("Reveal")
        self.reveal_button.clicked.connect(self.reveal)
        self.room_button = QPushButton("Show answers (Space)")
        self.room_button.clicked.connect(lambda: self.set_answers_hidden(False))
        self.previous_button = QPushButton("◀")
        self.previous_button.clicked.connect(lambda: self.go(self.index - 1))
        self.next_button = QPushButton("▶")
        self.next_button.clicked.connect(lambda: self.go(self.index + 1))
        self.reset_button = QPushButton("Reset progress")
        self.reset_button.clicked.connect(self._reset)

        top = QHBoxLayout()
        top.addWidget(self.previous_button)
        top.addWidget(self.position, 1)
        top.addWidget(self.next_button)
        buttons = QHBoxLayout()
        for b in (self.check_button, self.show_button, self.reveal_button):
            buttons.addWidget(b)
        # The question and its answers scroll (at a large text scale, or four pictures in a short
        # dock: the panel never makes the window taller); Check and the verdict stay in view below.
        content = QWidget()
        layout = QVBoxLayout(content)
        layout.addLayout(top)
        layout.addWidget(self.question)
        layout.addWidget(self.elsewhere)
        layout.addWidget(self.answer_area)
        layout.addWidget(self.room_button)
        layout.addStretch(1)
        layout.addWidget(self.reset_button)
        scroll = self.scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setFrameShape(QFrame.Shape.NoFrame)
        scroll.setWidget(content)
        # The words under it (the verdict) take its room without resizing the panel: refit then too.
        scroll.viewport().installEventFilter(self)
        outer = QVBoxLayout(self)
        outer.setContentsMargins(0, 0, 0, 0)
        outer.addWidget(scroll, 1)
        below = QVBoxLayout()
        below.setContentsMargins(layout.contentsMargins().left(), 0, layout.contentsMargins().right(), 0)
        below.addLayout(buttons)
        below.addWidget(self.feedback)
        outer.addLayout(below)
        self.set_lesson(None)

    # --- which exercise -----------------------------------------------------

    def set_lesson(self, lesson) -> None:
        """Ask ``lesson``'s exercises from the first (None: nothing to ask)."""
        if lesson is self.lesson and lesson is not None:
            return
        self.lesson, self._pipelines = lesson, {}
        self.go(0)

    def exercise(self) -> Exercise | None:
        """The exercise shown: this student's variant of it (:func:`core.lessons.exercises.variant`)."""
        if self.lesson is None or not self.lesson.exercises:
            return None
        return variant(self.lesson.exercises[self.index], self.progress.seed(), self.index)

    def go(self, index: int) -> None:
        """Show exercise ``index`` (clamped) with a fresh answer."""
        count = len(self.lesson.exercises) if self.lesson is not None else 0
        self.index = max(0, min(index, count - 1)) if count else 0
        self.tries = 0
        self.helped = False  # Show me gave a right pixel: a right answer is not one at the first try
        self.feedback.clear()
        self._fill()
        self._wait_for(self.exercise())

    def _wait_for(self, ex: Exercise | None) -> None:
        self.waiting_for = ex
        self.waiting.emit(ex)

    def set_elsewhere(self, why: str) -> None:
        """Say, in italics under the question, that the window shows another scene than the one the
        exercise asks about (``why``; "" when it shows that one)."""
        self.elsewhere.setText(f"<i>{why}</i>" if why else "")
        self.elsewhere.setVisible(bool(why))

    def _fill(self) -> None:
        ex = self.exercise()
        for w in (self.number_edit, self.pixel_edit, self.order_list, self.picture_grid):
            # Out of the layout but kept in the panel, hidden explicitly: taken out with setParent(None)
            # in the turn it went in, the show Qt queued then made it a window of its own.
            self.answer_layout.removeWidget(w)
            w.hide()
        while self.picture_layout.count():
            widget = self.picture_layout.takeAt(0).widget()
            widget.hide()  # gone at once, not when the event loop comes round to deleting it
            widget.deleteLater()
        self.picture_views, self.picture_keys = [], []
        for button in self.choices.buttons():
            self.choices.removeButton(button)
            button.hide()
            button.deleteLater()
        for b in (self.check_button, self.show_button, self.reveal_button, self.previous_button,
                  self.next_button):
            b.setEnabled(ex is not None)
        if ex is None:
            self.position.setText("No exercises in this lesson" if self.lesson else "No lesson open")
            self.question.setText("" if self.lesson else OPEN_A_LESSON)
            self.room_button.hide()  # no answers to show
            return
        n = len(self.lesson.exercises)
        done = self.progress.outcome(self.lesson.id, self.index)
        self.position.setText(f"Exercise {self.index + 1} of {n}" + (f" ({done})" if done else ""))
        self.previous_button.setEnabled(self.index > 0)
        self.next_button.setEnabled(self.index < n - 1)
        self.question.setText(ex.question)
        self._size_question()
        if ex.kind == "choose_one":
            for i, choice in enumerate(ex.args["choices"]):
                button = QRadioButton(choice_label(choice))
                self.choices.addButton(button, i)
                self.answer_layout.addWidget(button)
        elif ex.kind == "number":
            self.number_edit.clear()
            self._answer_with(self.number_edit)
        elif ex.kind == "click_pixel":
            self.pixel_edit.clear()
            self._answer_with(self.pixel_edit)
        elif ex.kind == "pick_picture":
            self._answer_with(self.picture_grid)
            p = self._p(ex)
            self._run(lambda: pictures(ex, p), lambda drawn: self._show_pictures(ex, drawn))
        else:
            self._set_order(list(ex.args["items"]))
            self._answer_with(self.order_list)
        self.set_answers_hidden(self.room)

    def _answer_with(self, field: QWidget) -> None:
        """Put ``field`` under the question, shown (the fields are hidden explicitly between questions)."""
        self.answer_layout.addWidget(field)
        field.show()

    def _set_order(self, items: list[str]) -> None:
        """The items to put in order, the list as tall as they are (no scrolling, no empty rows)."""
        self.order_list.clear()
        self.order_list.addItems(items)
        self.order_list.setCurrentRow(0)
        self._fit_order()

    def _fit_order(self) -> None:
        """The order list as tall as its rows at the text size now."""
        rows = sum(self.order_list.sizeHintForRow(i) for i in range(self.order_list.count()))
        self.order_list.setFixedHeight(rows + 2 * self.order_list.frameWidth() + 4)

    def move_item(self, step: int) -> None:
        """Move the order list's selected item ``step`` places down (negative: up)."""
        row = self.order_list.currentRow()
        to = row + step
        if row >= 0 and 0 <= to < self.order_list.count():
            self.order_list.insertItem(to, self.order_list.takeItem(row))
            self.order_list.setCurrentRow(to)

    def eventFilter(self, watched, event) -> bool:
        if watched is self.order_list and event.type() == QEvent.Type.KeyPress \
                and event.modifiers() & Qt.KeyboardModifier.AltModifier \
                and event.key() in (Qt.Key.Key_Up, Qt.Key.Key_Down):
            self.move_item(-1 if event.key() == Qt.Key.Key_Up else 1)
            return True
        if watched is self.order_list and event.type() == QEvent.Type.FontChange:
            QTimer.singleShot(0, self, self._fit_order)  # a new text size: rows of another height
        if watched is not self.order_list and watched is self.scroll.viewport() \
                and event.type() == QEvent.Type.Resize:
            self._sizing.start()
        return super().eventFilter(watched, event)

    def _show_pictures(self, ex: Exercise, drawn: dict) -> None:
        """The pictures in this student's order (their seed shuffles them), each with a button."""
        if ex is not self.exercise():
            return
        keys = list(drawn)
        random.Random(self.progress.seed() + self.index).shuffle(keys)
        for i, key in enumerate(keys):
            view = _Picture()
            view.set_image(drawn[key])
            button = QRadioButton(f"picture {i + 1}")
            view.pixel_clicked.connect(lambda _x, _y, b=button: b.setChecked(True))
            self.choices.addButton(button, i)
            self.picture_layout.addWidget(view, 2 * (i // 2), i % 2)
            self.picture_layout.addWidget(button, 2 * (i // 2) + 1, i % 2)
            self.picture_views.append(view)
        zoom_together(self.picture_views)
        self.picture_keys = keys
        self._sizing.start()  # and the pictures' room

    def _p(self, ex: Exercise) -> StepPipelines:
        if ex.step not in self._pipelines:
            self._pipelines[ex.step] = StepPipelines(self.lesson.steps[ex.step])
        return self._pipelines[ex.step]

    # --- answering ----------------------------------------------------------

    def given(self):
        """The answer as entered, in the form :func:`core.lessons.exercises.judge` takes, or a
        :class:`Missing` sentence saying what is lacking."""
        ex = self.exercise()
        if ex.kind == "choose_one":
            i = self.choices.checkedId()
            return i if i >= 0 else Missing("Choose one of the answers first.")
        if ex.kind == "pick_picture":
            i = self.choices.checkedId()
            return self.picture_keys[i] if i >= 0 else Missing("Pick one of the pictures first.")
        if ex.kind == "number":
            try:
                return float(self.number_edit.text().replace(",", "."))
            except ValueError:
                return Missing("Type a number: digits, a point before decimals, a minus sign if below zero.")
        if ex.kind == "click_pixel":
            parts = self.pixel_edit.text().replace("(", "").replace(")", "").split(",")
            try:
                x, y = (int(v) for v in parts)
            except ValueError:
                return Missing("Click a pixel in the image, or type its column and row: x, y.")
            cam = self.lesson.steps[ex.step].scene.camera
            if not (0 <= x < cam.width and 0 <= y < cam.height):
                return Missing(f"Pixel ({x}, {y}) is outside the {cam.width} x {cam.height} image.")
            return x, y
        return [self.order_list.item(i).text() for i in range(self.order_list.count())]

    def click(self, x: int, y: int) -> None:
        """A pixel clicked in the image answers a pixel exercise."""
        ex = self.exercise()
        if ex is not None and ex.kind == "click_pixel":
            self.pixel_edit.setText(f"{x}, {y}")
            self.check()

    def check(self) -> None:
        """Judge the answer: right or wrong and why; a wrong first answer may be tried again."""
        ex = self.exercise()
        given = self.given()
        if isinstance(given, Missing):
            self._say(given, None)
            return
        p = self._p(ex)
        self.check_button.setEnabled(False)
        self._run(lambda: judge(ex, p, given), lambda verdict: self._judged(ex, verdict))

    def _judged(self, ex: Exercise, verdict) -> None:
        self.check_button.setEnabled(True)
        if ex is not self.exercise():
            return  # the student moved on meanwhile
        self.tries += 1
        if verdict.right:
            self._record(FIRST_TRY if self.tries == 1 and not self.helped else LATER)
            self._say(verdict.sentence, True)
            self._wait_for(None)
        elif self.tries == 1:
            self._say(f"{verdict.sentence} Try once more.", False)
        else:
            self._say(f"{verdict.sentence} Press Reveal for the answer.", False)

    def reveal(self) -> None:
        """Give the answer the pipelines compute."""
        ex = self.exercise()
        p = self._p(ex)
        work = {"choose_one": lambda: right_choices(ex, p), "number": lambda: number(ex, p),
                "click_pixel": lambda: a_right_pixel(ex, p), "order": lambda: right_order(ex, p),
                "pick_picture": lambda: ex.args["view"]}[ex.kind]
        self._run(work, lambda answer: self._revealed(ex, answer))

    def _revealed(self, ex: Exercise, computed) -> None:
        if ex is not self.exercise():
            return
        if ex.kind == "choose_one":
            right = computed
            self.choices.button(right[0]).setChecked(True)
            answer = choice_label(ex.args["choices"][right[0]])
        elif ex.kind == "number":
            answer = f"{computed:.6g}"
            self.number_edit.setText(answer)
        elif ex.kind == "pick_picture":
            if computed in self.picture_keys:
                k = self.picture_keys.index(computed)
                self.choices.button(k).setChecked(True)
                answer = f"picture {k + 1}"
            else:
                answer = f"the {computed} view"
        elif ex.kind == "click_pixel":
            answer = f"pixel {computed}, for example"
            self.pixel_edit.setText(f"{computed[0]}, {computed[1]}")
        else:
            order = computed
            self._set_order(order)
            answer = " → ".join(order)
        self._record(REVEALED)
        self._say(f"The answer: {answer}. {ex.why}".strip(), True)
        self.set_answers_hidden(False)
        self._wait_for(None)
        if ex.kind == "click_pixel":  # the pixel named is also picked, where the student looks for it
            self.show_me.emit(ex.step, computed)

    def _show_me(self) -> None:
        ex = self.exercise()
        if ex.kind != "click_pixel":  # the pixel the question names, if it names one
            self.show_me.emit(ex.step, named_pixel(ex))
            return
        p = self._p(ex)
        self.helped = True  # the pixel shown is a right one
        self._run(lambda: a_right_pixel(ex, p), lambda pixel: self._shown(ex, pixel))

    def _shown(self, ex: Exercise, pixel) -> None:
        if ex is self.exercise():  # not if the student went on to another exercise or lesson meanwhile
            self.show_me.emit(ex.step, pixel)

    def _record(self, outcome: str) -> None:
        self.progress.record(self.lesson.id, self.index, outcome)
        self.progressed.emit(self.lesson.id)

    def _reset(self) -> None:
        if self.lesson is not None:
            self.progress.reset(self.lesson.id)
            self.progressed.emit(self.lesson.id)
            self.go(self.index)

    def _say(self, text: str, right: bool | None) -> None:
        color = {True: RIGHT_COLOR, False: WRONG_COLOR, None: ""}[right]
        self.feedback.setStyleSheet(f"color: {color};" if color else "")
        self.feedback.setText(text)

    # --- put to the room ----------------------------------------------------

    def set_room(self, room: bool) -> None:
        """Put the question to the room: large, with its answers hidden until Space shows them."""
        self.room = room
        self._size_question()
        self.set_answers_hidden(room)

    def _size_question(self) -> None:
        """Put to the room, the question is :data:`ROOM_SCALE` times the panel's text, or as much of
        that as leaves the rest of the panel (Show answers, Reset progress, pictures to pick at
        :data:`PICTURE_LEAST` high) in view at the question's width (a long question at x2 in the
        dock of a 1280 x 720 screen ran below the fold, Show answers with it); never smaller than
        :data:`ROOM_LEAST` of the panel's text.  The pictures then take the room left
        (:meth:`_fit_pictures`).

        Both sizes are reckoned from the room the rest takes, the question and the pictures left
        out: reckoned each from the other's last size, they settled at sizes that hung on the order
        in which resizes came (pictures 87 to 135 high on one screen)."""
        style = ""
        if self.room:
            base = QApplication.font().pointSizeF()  # the text size now (presentation's scale)
            scale, width = ROOM_SCALE, self.question.width()
            view = self.scroll.viewport()
            first = self._fitted_picture()
            pictures = 0 if first is None else 2 * min(PICTURE_LEAST, first.width() * 3 // 4)
            room = view.height() - self._rest_height() - pictures
            least = ROOM_LEAST if self.room_button.isVisible() else 1.0  # alone, or over its answers
            while scale > least and min(width, view.height()) > 0 and self._question_height(base * scale,
                                                                                       width) > room:
                scale = round(scale - 0.1, 1)
            style = f"font-size: {base * scale:.1f}pt; font-weight: bold;"
        if style != self.question.styleSheet():
            # A style sheet, not setFont: the window's style sheet would override a font set in code.
            self.question.setStyleSheet(style)
            self.question.ensurePolished()
        self._fit_pictures()

    def _fitted_picture(self):
        """The first picture to pick, when the pictures are in the panel and fitted to its room."""
        return self.picture_views[0] if self.picture_views and self.answer_area.isVisible() else None

    def _rest_height(self) -> int:
        """The height the panel's content takes at the scroll area's width, but for the question and
        the pictures' two rows: measured with the pictures at their least height, which their width
        does not change (the layout's own widths for them are not yet theirs when they come)."""
        first = self._fitted_picture()
        if first is not None:
            self._set_tallest(_Picture.LEAST)
        # The layouts inside keep their last sizes until told: tell them now.
        QCoreApplication.sendPostedEvents(None, QEvent.Type.LayoutRequest)
        layout = self.scroll.widget().layout()
        total = layout.totalHeightForWidth(self.scroll.viewport().width())
        rows = 0 if first is None else 2 * _Picture.LEAST
        return total - self.question.heightForWidth(self.question.width()) - rows

    def _set_tallest(self, tallest: int) -> None:
        for picture in self.picture_views:
            picture.tallest = tallest
            picture.updateGeometry()

    def _fit_pictures(self) -> None:
        """Pictures to pick as large as their width makes them, or as the panel's height leaves for
        their two rows beside the rest of it, so that all four are in view."""
        if self._fitted_picture() is None:
            return
        rest = self._rest_height()
        room = self.scroll.viewport().height() - rest - self.question.heightForWidth(self.question.width())
        self._set_tallest(max(_Picture.LEAST, room // 2))

    def _question_height(self, points: float, width: int) -> int:
        font = QFont(self.question.font())
        font.setPointSizeF(points)
        font.setBold(True)
        lines = QFontMetrics(font).boundingRect(QRect(0, 0, width, 100_000), Qt.TextFlag.TextWordWrap,
                                                self.question.text())
        return lines.height()

    def resizeEvent(self, event) -> None:  # noqa: N802 (Qt's name)
        super().resizeEvent(event)
        self._sizing.start()  # once the question has its new width

    def changeEvent(self, event) -> None:  # noqa: N802
        super().changeEvent(event)
        if event.type() == QEvent.Type.FontChange:  # another text scale: another size for the room
            self._sizing.start()

    def set_answers_hidden(self, hidden: bool) -> None:
        self.answer_area.setVisible(not hidden)
        self.room_button.setVisible(hidden and self.lesson is not None and bool(self.lesson.exercises))
        self._sizing.start()  # the question leaves the answers their room
        self.answers_hidden.emit(hidden)

    def keyPressEvent(self, event) -> None:
        if event.key() == Qt.Key.Key_Space and not self.answer_area.isVisible():
            self.set_answers_hidden(False)
        elif event.key() in (Qt.Key.Key_Return, Qt.Key.Key_Enter) and self.check_button.isEnabled() \
                and self.answer_area.isVisible():
            self.check()  # Enter checks the answer: typed in a field (which passes the key on), or chosen
        else:
            super().keyPressEvent(event)
