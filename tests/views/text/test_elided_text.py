"""Status text kept to one line: shortened with "…" to fit, the whole text still there to read."""

from views.text.elided_label import ElidedLabel, ElidedProgressBar

LONG = "Cost: choose a knob and press Run; the sweep shows its progress in the panel"


def test_a_progress_bar_shortens_its_text_to_its_width_and_keeps_the_whole_format(qtbot):
    bar = ElidedProgressBar()
    qtbot.addWidget(bar)
    bar.setRange(0, 100)
    bar.setValue(40)
    bar.setFormat(LONG + " %p%")
    bar.resize(260, bar.sizeHint().height())
    bar.show()
    qtbot.waitExposed(bar)
    drawn = bar.shown_text()
    assert drawn.endswith("…") and drawn[:-1] in LONG
    assert bar.fontMetrics().horizontalAdvance(drawn) <= bar.width()
    assert bar.format() == LONG + " %p%" and bar.text() == LONG + " 40%"
    assert bar.toolTip() == LONG
    bar.resize(2000, bar.height())  # room enough: the whole text
    assert bar.shown_text() == LONG + " 40%"


def test_a_label_given_more_lines_breaks_between_words_and_ends_in_an_ellipsis_only_without_room(qtbot):
    label = ElidedLabel(LONG)
    qtbot.addWidget(label)
    metrics = label.fontMetrics()
    label.resize(metrics.horizontalAdvance(LONG) // 2 + metrics.horizontalAdvance("choose"), 40)
    label.show()
    qtbot.waitExposed(label)
    assert label.shown_lines()[-1].endswith("…")  # one line, as by default
    label.set_max_lines(3)  # the whole text needs two lines at this width: it reads whole
    lines = label.shown_lines()
    assert len(lines) == 2 and " ".join(lines) == LONG
    assert all(metrics.horizontalAdvance(line) <= label.width() for line in lines)
    assert label.height() >= 2 * metrics.height()  # as tall as its lines
    label.resize(metrics.horizontalAdvance(LONG) // 3, label.height())  # more than 3 lines: the 3rd ends in …
    lines = label.shown_lines()
    assert len(lines) == 3 and lines[-1].endswith("…") and LONG.startswith(" ".join(lines)[:-1])
    assert label.text() == LONG and label.toolTip() == LONG
