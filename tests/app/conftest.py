"""Fixtures of the window tests."""

import pytest
from qt_fixtures import application_font_restored, private_settings, require_display  # noqa: F401
from window_helpers import open_window


@pytest.fixture
def window(qtbot):
    return open_window(qtbot)
