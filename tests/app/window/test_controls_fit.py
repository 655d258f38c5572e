"""The Controls dock's fields are seen whole presenting at x2 on a 1280 x 720 screen."""

from PySide6.QtWidgets import QAbstractSpinBox, QComboBox
from window_helpers import presenting_on_1280x720

from app.window.window_layout import in_front


def test_presenting_at_x2_on_1280x720_every_control_field_is_whole_in_the_dock(qtbot, monkeypatch):
    # The eye's three number boxes, each as wide as "-8888.88", widened the panel past the dock:
    # the Controls scrolled sideways and cut the third eye box, the angles and the distance.
    window = presenting_on_1280x720(qtbot, monkeypatch, 2.0)
    window.controls_dock.raise_()
    qtbot.waitUntil(lambda: in_front(window.controls_dock))
    scroll = window._controls
    viewport = scroll.viewport()
    panel = window.camera_panel
    fields = [f for kind in (QAbstractSpinBox, QComboBox) for f in panel.findChildren(kind) if f.isVisible()]
    assert len(fields) >= 9

    def whole() -> bool:
        assert not scroll.horizontalScrollBar().isVisible()
        for field in fields:
            left = field.mapTo(viewport, field.rect().topLeft()).x()
            assert left >= 0 and left + field.width() <= viewport.width(), field.toolTip()
            if isinstance(field, QAbstractSpinBox):  # its number inside its box
                assert field.fontMetrics().horizontalAdvance(field.text()) <= field.lineEdit().width()
        return True

    qtbot.waitUntil(whole, timeout=5000)
    window.presentation.set_presenting(False)
