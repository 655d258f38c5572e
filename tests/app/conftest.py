"""Fixtures of the window tests."""

import pytest
from qt_fixtures import (  # noqa: F401
    application_font_restored,
    closed_widgets_deleted,
    private_settings,
    require_display,
)
from window_helpers import open_window


@pytest.fixture
def window(qtbot):
    return open_window(qtbot)
