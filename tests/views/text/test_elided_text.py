"""Status text kept to one line: shortened with "…" to fit, the whole text still there to read."""

from views.text.elided_label import ElidedProgressBar

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
