#!/usr/bin/env bash
# README command 1: set up what the app needs, then open it on the default lecture scene.
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
ensure_debian "${DEBIAN_GUI_PACKAGES[@]}"
ensure_venv ""
exec "$VENV/bin/python" -m app "$@"
