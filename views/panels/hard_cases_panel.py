"""The Hard cases panel: the textbook method beside the robust one, case by case.

A list of the lab's cases (:mod:`core.hard_cases`) on the left; on the right
the chosen case: its numbers as the textbook computes them, as the app's
robust method does and as exact arithmetic gives them (digits that differ
from the exact value in red), the error of each method against its
tolerance, pictures where the failure can be seen, and a few sentences on
why.  A slider sweeps the case's natural parameter (distance from the
origin, far/near ratio, angle) to show where the textbook method starts to
fail.

Cases are computed in a process of their own (:mod:`core.helper_process`), asked from a
:class:`~PySide6.QtCore.QThreadPool` thread (:class:`views.jobs.JobRun`): most of a case is
numbers worked out one by one in Python (exact rationals, one ray and triangle at a time), and on a
thread of the window's process it held Python's lock in turns with the window's thread, which
waited 110-280 ms at a time for it when a case was chosen.  One request at a time; a result that arrives
after a newer request was made is dropped, so the window never waits and
never shows a stale case.  When the panel is first shown every case is also
computed once at its defaults, at a lower priority, so the list can mark
which robust methods pass.
"""

from __future__ import annotations

import html
import inspect
import math

import numpy as np
from PySide6.QtCore import QEvent, QSize, Qt, QThreadPool, QTimer, Signal
from PySide6.QtGui import QFontMetrics
from PySide6.QtWidgets import (
    QComboBox,
    QGridLayout,
    QGroupBox,
    QHBoxLayout,
    QLabel,
    QListWidget,
    QScrollArea,
    QSlider,
    QSplitter,
    QVBoxLayout,
    QWidget,
)

from core import hard_cases, helper_process
from core.hard_cases.result import CaseResult, Parameter
from core.srgb import linear_to_srgb
from views.images.image_view import ImageView, zoom_together
from views.jobs import JobRun, JobSignals
from views.text.text_scale import scaled_style

#: Positions of the slider for a linear parameter, and per decade for a log one.
SLIDER_STEPS, STEPS_PER_DECADE = 120, 20
#: Wait this long after the slider stops before computing (milliseconds).
DEBOUNCE_MS = 120
WRONG, RIGHT, MUTED = "#ff5c5c", "#6fd08c", "#8a93a6"
#: What the user asked for runs before the start-up computation of the other cases.
REQUEST_PRIORITY, PREFETCH_PRIORITY = 1, 0
#: The table's three methods, in its columns' order.
METHODS = ("textbook", "robust", "reference")


def format_value(value) -> str:
    """A table cell's text: floats with 16 significant digits, ``—`` for nothing."""
    if value is None:
        return "—"
    if isinstance(value, str):
        return value
    if isinstance(value, (bool, np.bool_)):
        return str(bool(value))
    if isinstance(value, (int, np.integer)) or (isinstance(value, float) and value.is_integer()
                                                 and abs(value) < 1e15):
        return str(int(value))
    if math.isnan(value):
        return "NaN"
    return f"{value:.16g}"


def highlight_digits(value, exact) -> str:
    """Rich text of ``value`` with every character from the first that differs from ``exact`` in red.

    Strings (verdicts) are green when they equal the exact one and red otherwise.

    Examples
    --------
    >>> highlight_digits(2.9375, 3.0)
    '<span style="color:#ff5c5c">2.9375</span>'
    >>> highlight_digits(3.0000001, 3.0000002)
    '3.000000<span style="color:#ff5c5c">1</span>'
    """
    text, reference = format_value(value), format_value(exact)
    if value is None or exact is None:
        return html.escape(text)
    if isinstance(value, str) or isinstance(exact, str):
        color = RIGHT if text == reference else WRONG
        return f'<span style="color:{color}">{html.escape(text)}</span>'
    same = 0
    while same < min(len(text), len(reference)) and text[same] == reference[same]:
        same += 1
    if same == len(text) == len(reference):
        return html.escape(text)
    return html.escape(text[:same]) + f'<span style="color:{WRONG}">{html.escape(text[same:])}</span>'


def slider_steps(parameter: Parameter) -> int:
    """The slider's largest position: ``STEPS_PER_DECADE`` per decade, or ``SLIDER_STEPS``."""
    if parameter.log:
        decades = math.log10(parameter.maximum) - math.log10(parameter.minimum)
        return max(1, int(round(decades * STEPS_PER_DECADE)))
    return SLIDER_STEPS


def slider_value(parameter: Parameter, position: int) -> float:
    """The parameter value at slider ``position`` (0 .. :func:`slider_steps`), log or linear."""
    f = position / slider_steps(parameter)
    if parameter.log:
        lo, hi = math.log10(parameter.minimum), math.log10(parameter.maximum)
        return float(10.0 ** round(lo + f * (hi - lo), 3))
    return float(round(parameter.minimum + f * (parameter.maximum - parameter.minimum), 6))


def slider_position(parameter: Parameter) -> int:
    """The slider position nearest to ``parameter.value``."""
    if parameter.log:
        lo, hi = math.log10(parameter.minimum), math.log10(parameter.maximum)
        f = (math.log10(max(parameter.value, parameter.minimum)) - lo) / (hi - lo)
    else:
        f = (parameter.value - parameter.minimum) / (parameter.maximum - parameter.minimum)
    return int(round(min(max(f, 0.0), 1.0) * slider_steps(parameter)))


def _case_run(request_id: int, name: str, value, options: dict, signals: JobSignals) -> JobRun:
    """Case ``name`` at parameter ``value`` (``None``: its default) with ``options``, computed off the
    GUI thread and reported to ``signals`` as request ``request_id``."""
    def run(_cancelled, _progress) -> CaseResult:
        return helper_process.call(hard_cases.__name__, "run_case", name, value, **options)

    return JobRun(request_id, run, signals)


def _named(name: str, text: str) -> str:
    """Rich ``text`` after its method's muted ``name``, for the table's values one under another."""
    return f'<span style="color:{MUTED}">{name}:</span> {text}'


class _HorizontalScrollArea(QScrollArea):
    """Scrolls its widget sideways only, as tall as the widget: a table wider than the pane even with its
    values stacked (a very narrow pane) scrolls by itself, and the words above and below it keep the
    pane's width."""

    def __init__(self, widget: QWidget):
        super().__init__()
        self.setWidget(widget)
        self.setWidgetResizable(True)
        self.setFrameShape(QScrollArea.Shape.NoFrame)
        self.setVerticalScrollBarPolicy(Qt.ScrollBarPolicy.ScrollBarAlwaysOff)
        widget.installEventFilter(self)

    def eventFilter(self, watched, event) -> bool:
        if event.type() == QEvent.Type.LayoutRequest:  # new rows, or larger text: a new height
            self.updateGeometry()
        return False

    def resizeEvent(self, event) -> None:
        super().resizeEvent(event)
        self.updateGeometry()  # wrapped words take another height at another width

    def sizeHint(self) -> QSize:
        widget, bar = self.widget(), self.horizontalScrollBar().sizeHint().height()
        width = max(self.viewport().width(), widget.minimumSizeHint().width())
        tall = widget.heightForWidth(width) if widget.hasHeightForWidth() else widget.sizeHint().height()
        return QSize(widget.sizeHint().width(), max(tall, widget.minimumSizeHint().height()) + bar)

    def minimumSizeHint(self) -> QSize:
        return QSize(0, self.sizeHint().height())


class HardCasesPanel(QWidget):
    """The hard-case lab as a standalone widget.

    Signals
    -------
    result_shown(str name) : a case's result is on screen (after every recomputation too).
    """

    result_shown = Signal(str)

    def __init__(self, parent: QWidget | None = None, pool: QThreadPool | None = None):
        super().__init__(parent)
        self._pool = pool or QThreadPool(self)
        if pool is None:
            self._pool.setMaxThreadCount(1)
        self._signals = JobSignals(self)
        self._signals.finished.connect(self._on_finished)
        self._signals.failed.connect(self._on_failed)
        self._request = 0
        self._results: dict[str, CaseResult] = {}
        self._parameter: Parameter | None = None
        self.result: CaseResult | None = None

        self.cases = QListWidget()
        for i, name in enumerate(hard_cases.CASES, start=1):
            self.cases.addItem(f"{i}. {name.replace('_', ' ')} …")
        self.cases.setMinimumWidth(220)
        self.cases.setWordWrap(True)
        self.cases.currentRowChanged.connect(self._on_case_chosen)

        self.title = QLabel()
        scaled_style(self.title, "font-weight: bold;", 15)
        self.title.setWordWrap(True)
        self.status = QLabel()
        self.status.setStyleSheet(f"color: {MUTED};")
        self.verdict = QLabel()
        self.verdict.setWordWrap(True)
        self.verdict.setTextFormat(Qt.TextFormat.RichText)

        self.slider = QSlider(Qt.Orientation.Horizontal)
        self.slider_label = QLabel()
        self.slider_label.setWordWrap(True)  # on a line of its own: the slider keeps its room at large text
        self.slider_value = QLabel()
        self.slider_value.setMinimumWidth(90)
        self.option_label = QLabel("fixed ε")
        self.option = QComboBox()
        self._debounce = QTimer(self, singleShot=True, interval=DEBOUNCE_MS)
        self._debounce.timeout.connect(self._compute_current)
        self.slider.valueChanged.connect(self._on_slider)
        self.option.currentIndexChanged.connect(lambda _: self._changed())
        sweep = QHBoxLayout()
        sweep.addWidget(self.slider, 1)
        sweep.addWidget(self.slider_value)
        sweep.addWidget(self.option_label)
        sweep.addWidget(self.option)

        self.table = QGridLayout()
        self.table.setHorizontalSpacing(18)
        self.table_caption = QLabel("Textbook, robust and exact (digits that differ from exact in red)")
        self.table_caption.setWordWrap(True)  # a box's own title would not wrap, and hold the pane wide
        table_box = QGroupBox()
        table_box.setLayout(self.table)
        self.table_headers: list[QLabel] = []
        self.table_cells: list[list[QLabel]] = []
        self._values: list[list[tuple[str, str]]] = []  # each row's three values, as rich and plain text
        self._methods: tuple[str, str, str] = ("", "", "")  # the methods' descriptions, in METHODS' order
        self._arrangement: tuple | None = None  # (stacked, text size) the table was laid out for

        self.naive_image = ImageView(placeholder="", pickable=False)  # only looked at: no pixel readout
        self.robust_image = ImageView(placeholder="", pickable=False)
        zoom_together([self.naive_image, self.robust_image])
        for view in (self.naive_image, self.robust_image):
            view.zoom_with_ctrl()  # the plain wheel scrolls the case's details
        self.naive_image.setAccessibleName("Picture of the textbook method")  # also its File → Export entry
        self.robust_image.setAccessibleName("Picture of the robust method")
        self.naive_caption, self.robust_caption = QLabel(), QLabel()
        images = QGridLayout()
        images.addWidget(self.naive_caption, 0, 0)
        images.addWidget(self.robust_caption, 0, 1)
        images.addWidget(self.naive_image, 1, 0)
        images.addWidget(self.robust_image, 1, 1)
        images.setRowStretch(1, 1)
        self.image_box = QGroupBox()
        self.image_box.setLayout(images)
        self.image_box.setMinimumHeight(220)

        self.explanation = QLabel()
        self.explanation.setWordWrap(True)
        scaled_style(self.explanation, "", 11)
        self.reference = QLabel()
        self.reference.setWordWrap(True)
        self.reference.setStyleSheet(f"color: {MUTED};")

        detail = QWidget()
        column = QVBoxLayout(detail)
        column.addWidget(self.title)
        column.addWidget(self.slider_label)
        column.addLayout(sweep)
        column.addWidget(self.verdict)
        column.addWidget(self.table_caption)
        self._table_area = _HorizontalScrollArea(table_box)
        self._table_area.installEventFilter(self)
        table_box.installEventFilter(self)
        column.addWidget(self._table_area)
        column.addWidget(self.image_box, 1)
        column.addWidget(self.explanation)
        column.addWidget(self.reference)
        column.addWidget(self.status)
        column.addStretch(0)
        scroll = QScrollArea()
        scroll.setWidgetResizable(True)
        scroll.setWidget(detail)

        splitter = QSplitter()
        splitter.addWidget(self.cases)
        splitter.addWidget(scroll)
        splitter.setStretchFactor(1, 1)
        splitter.setSizes([260, 1000])
        layout = QVBoxLayout(self)
        layout.setContentsMargins(4, 4, 4, 4)
        layout.addWidget(splitter)
        self._prefetched = False
        self.cases.setCurrentRow(0)

    def eventFilter(self, watched, event) -> bool:
        # A new width, or new text sizes (the box asks for a new layout): side by side, or stacked?
        if event.type() in (QEvent.Type.Resize, QEvent.Type.LayoutRequest):
            self._arrange_table()
        return False

    def showEvent(self, event):
        super().showEvent(event)
        if not self._prefetched:
            self._prefetched = True
            for i, name in enumerate(hard_cases.CASES):
                self._pool.start(_case_run(-1 - i, name, None, {}, self._signals), PREFETCH_PRIORITY)

    # -- requests ---------------------------------------------------------------------------

    @property
    def case_name(self) -> str:
        return list(hard_cases.CASES)[max(self.cases.currentRow(), 0)]

    def select(self, name: str) -> None:
        """Show case ``name`` (computed off the GUI thread if not yet known)."""
        self.cases.setCurrentRow(list(hard_cases.CASES).index(name))

    def _on_case_chosen(self, row: int) -> None:
        if row < 0:
            return
        name = self.case_name
        case = hard_cases.CASES[name]
        self.option.blockSignals(True)
        self.option.clear()
        for option, values in case.options.items():
            for v in values:
                self.option.addItem(f"{v:g}", (option, v))
            default = inspect.signature(case.run).parameters[option].default
            self.option.setCurrentIndex(list(values).index(default))
        self.option.blockSignals(False)
        self.option.setVisible(bool(case.options))
        self.option_label.setVisible(bool(case.options))
        if name in self._results:
            self._show(self._results[name])
        else:
            self._parameter = None
            if self._prefetched:  # before the first show, the prefetch there brings it
                self._submit(name, None)

    def _on_slider(self, position: int) -> None:
        if self._parameter is None:
            return
        self.slider_value.setText(f"{slider_value(self._parameter, position):g}")
        self._changed()

    def _changed(self) -> None:
        """The user moved the slider or picked an option: compute anew once they pause.  What is
        computing now is for the old setting and is not shown: its result arriving in the pause moved
        the slider back under the user's hand."""
        self._request += 1
        self._debounce.start()

    def _compute_current(self) -> None:
        value = slider_value(self._parameter, self.slider.value()) if self._parameter is not None else None
        self._submit(self.case_name, value)

    def _submit(self, name: str, value) -> None:
        self._request += 1
        options = dict([self.option.currentData()]) if self.option.isVisible() and self.option.count() else {}
        self.status.setText("computing…")
        self._pool.start(_case_run(self._request, name, value, options, self._signals), REQUEST_PRIORITY)

    def _on_finished(self, request_id: int, result: CaseResult) -> None:
        if request_id < 0:  # the first computation of every case, at its defaults
            mark = "✓" if result.passed else "✗"
            self.cases.item(-1 - request_id).setText(f"{mark} {result.title}")
            self._results.setdefault(result.name, result)
            if result.name == self.case_name and self.result is None:
                self._show(result)
            return
        if request_id != self._request:
            return  # a newer request is on its way
        self._results[result.name] = result
        self._show(result)

    def _on_failed(self, request_id: int, message: str) -> None:
        if request_id == self._request:
            self.status.setText(f"could not compute this case: {message}")

    def shutdown(self) -> None:
        """Drop queued computations and wait for a running one to end."""
        self._request += 1
        self._pool.clear()
        self._pool.waitForDone()

    def closeEvent(self, event):
        self.shutdown()
        super().closeEvent(event)

    # -- showing ----------------------------------------------------------------------------

    def _show(self, r: CaseResult) -> None:
        self.result = r
        self.status.setText("")
        self.title.setText(r.title)
        self._parameter = r.parameter
        has_parameter = r.parameter is not None
        for w in (self.slider, self.slider_label, self.slider_value):
            w.setVisible(has_parameter)
        if has_parameter:
            self.slider.blockSignals(True)
            self.slider.setRange(0, slider_steps(r.parameter))
            self.slider.setValue(slider_position(r.parameter))
            self.slider.blockSignals(False)
            self.slider_label.setText(r.parameter.label)
            self.slider_value.setText(f"{r.parameter.value:g}")
        ok = f'<b style="color:{RIGHT}">passes</b>' if r.passed else f'<b style="color:{WRONG}">FAILS</b>'
        naive_ok = "passes" if r.naive_passed else "fails"
        self.verdict.setText(
            f"Error ({html.escape(r.error_unit)}): textbook <b>{format_value(r.naive_error)}</b> "
            f"({naive_ok}), robust <b>{format_value(r.robust_error)}</b>; "
            f"tolerance {r.tolerance:.3g}: the robust method {ok}.")
        self._fill_table(r)
        self.image_box.setVisible(bool(r.images))
        if r.images:
            image = r.images[0]
            self.image_box.setTitle(image.caption)
            self.naive_image.set_image(linear_to_srgb(image.naive))
            self.robust_image.set_image(linear_to_srgb(image.robust))
            self.naive_caption.setText(f"textbook: {r.naive_method}")
            self.robust_caption.setText(f"robust: {r.robust_method}")
        self.explanation.setText(r.explanation)
        self.reference.setText(f"Reference: {r.reference_method}. Tolerance: {r.tolerance_reason}.")
        self.result_shown.emit(r.name)

    def _fill_table(self, r: CaseResult) -> None:
        while self.table.count():
            item = self.table.takeAt(0)
            widget = item.widget()
            if widget is not None:
                widget.setParent(None)  # off screen now, not at the next event loop pass
                widget.deleteLater()
        self._methods = (r.naive_method, r.robust_method, r.reference_method)
        self.table_headers = [QLabel() for _ in range(1 + len(METHODS))]
        for label in self.table_headers:
            label.setWordWrap(True)
        self.table_cells, self._values = [], []
        for row in r.rows:
            exact = row.exact if row.compare else None
            values = [(highlight_digits(row.naive, exact), format_value(row.naive)),
                      (highlight_digits(row.robust, exact), format_value(row.robust)),
                      (html.escape(format_value(row.exact)), format_value(row.exact))]
            cells = [QLabel(), *(QLabel() for _ in values)]
            for cell in cells:
                cell.setTextFormat(Qt.TextFormat.RichText)
                cell.setTextInteractionFlags(Qt.TextInteractionFlag.TextSelectableByMouse)
            cells[0].setWordWrap(True)
            self.table_cells.append(cells)
            self._values.append(values)
        self._arrangement = None
        self._arrange_table()

    def _side_by_side_width(self) -> int:
        """The narrowest the table can be with the three methods side by side: each value on one line,
        the row names and (bold) headers wrapped at their longest word, with the box's margins and the
        spacing between columns. Measured from the texts, so the same in either arrangement."""
        plain = self.fontMetrics()
        bold_font = self.font()
        bold_font.setBold(True)
        bold = QFontMetrics(bold_font)
        words = [word for row in self.result.rows for word in row.label.split()]
        widths = [max(plain.horizontalAdvance(word) for word in words)]
        for col, (name, method) in enumerate(zip(METHODS, self._methods, strict=True), start=1):
            header = [bold.horizontalAdvance(word) for word in f"{name}: {method}".split()]
            values = [plain.horizontalAdvance(values[col - 1][1]) for values in self._values]
            widths.append(max(*header, *values))
        box, grid = self.table.parentWidget().contentsMargins(), self.table.contentsMargins()
        margins = box.left() + box.right() + grid.left() + grid.right()
        return sum(widths) + self.table.horizontalSpacing() * (len(widths) - 1) + margins

    def _arrange_table(self) -> None:
        """The three methods side by side where their values fit the pane's width, else each row's
        values one under another, named: large text then reads whole without scrolling sideways."""
        if not self.table_cells:
            return
        stacked = self._side_by_side_width() > self._table_area.viewport().width()
        arrangement = (stacked, self.font().pointSizeF())  # the indent under a row follows the text size
        if arrangement == self._arrangement:
            return
        self._arrangement = arrangement
        while self.table.count():
            self.table.takeAt(0)  # the same labels, placed again below
        for col in range(self.table.columnCount()):
            self.table.setColumnStretch(col, 0)
        self.table_headers[0].setVisible(not stacked)
        for header, name, method in zip(self.table_headers[1:], METHODS, self._methods, strict=True):
            header.setText(_named(name, html.escape(method)) if stacked else
                           f"<b>{html.escape(f'{name}: {method}')}</b>")
        indent = self.fontMetrics().horizontalAdvance("MM") if stacked else -1  # values under their row
        for cells, values, row in zip(self.table_cells, self._values, self.result.rows, strict=True):
            cells[0].setText(f"<b>{html.escape(row.label)}</b>" if stacked else html.escape(row.label))
            for name, cell, (text, _) in zip(METHODS, cells[1:], values, strict=True):
                cell.setText(_named(name, text) if stacked else text)
                cell.setWordWrap(stacked)  # a value too long for the line goes under its method's name
                cell.setIndent(indent)
        if stacked:
            for row, header in enumerate(self.table_headers[1:]):
                self.table.addWidget(header, row, 0)
            row = len(METHODS)
            for cells in self.table_cells:
                for cell in cells:
                    self.table.addWidget(cell, row, 0)
                    row += 1
            return
        for col, header in enumerate(self.table_headers):
            self.table.addWidget(header, 0, col)
        for row, cells in enumerate(self.table_cells, start=1):
            for col, cell in enumerate(cells):
                self.table.addWidget(cell, row, col)
        self.table.setColumnStretch(0, 2)
        for col in (1, 2, 3):
            self.table.setColumnStretch(col, 3)
