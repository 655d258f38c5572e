#!/usr/bin/env bash
# README command 2: set up everything the tests need, then run the whole suite under Xvfb.
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ensure_debian "${DEBIAN_GUI_PACKAGES[@]}" "${DEBIAN_TEST_PACKAGES[@]}"
ensure_venv "[test]"
export PATH="$VENV/bin:$PATH"
ruff check .
# The kernels compile here, once per machine and version of the code, on both cores: no test waits
# for a compile inside its own time limit.
python -m app compile
# Two worker processes, as many as this machine's cores; each starts an X server of its own
# (tests/qt_fixtures.py). An idle worker takes tests queued for the other (worksteal): one long test
# near the end does not leave a core idle.
exec xvfb-run -a -s "-screen 0 1920x1080x24" python -m pytest -n 2 --dist worksteal "$@"
