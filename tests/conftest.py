"""Shared test set-up: GUI tests need a real X server, and say so instead of skipping."""

import atexit
import os
import shutil
import tempfile

import pytest
import pyvista as pv

pv.OFF_SCREEN = True
# The window keeps its last scene in the user's settings (QSettings); the tests, and the
# windows they start in subprocesses, keep theirs in a folder of their own.
os.environ["XDG_CONFIG_HOME"] = tempfile.mkdtemp(prefix="render-explorer-test-config-")
atexit.register(shutil.rmtree, os.environ["XDG_CONFIG_HOME"], ignore_errors=True)


def pytest_configure(config):
    config.addinivalue_line("markers", "gui: needs an X server (Qt xcb plugin, OpenGL for VTK)")


@pytest.fixture(autouse=True)
def _require_display(request):
    needs_gui = "qtbot" in request.fixturenames or request.node.get_closest_marker("gui")
    if needs_gui and not os.environ.get("DISPLAY"):
        pytest.fail(
            "This GUI test needs an X server (VTK gets no OpenGL context offscreen). "
            "Run the suite with `bash .ci/test.sh`, which starts Xvfb, "
            "or wrap pytest in `xvfb-run -a`."
        )
