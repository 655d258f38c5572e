"""Fixtures of the window tests."""

import pytest
from window_helpers import open_window


@pytest.fixture
def window(qtbot):
    return open_window(qtbot)
