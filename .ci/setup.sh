# Shared setup for the two README commands; sourced, not run.
# Creates .venv in the checkout and installs the project into it, but only
# when pyproject.toml or .ci/constraints.txt changed since the last install (a stamp records
# their hash).
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
VENV="$ROOT/.venv"
# The versions the suite last passed with: installed when they can be (see the file's header).
CONSTRAINTS="$ROOT/.ci/constraints.txt"
PY="${PYTHON:-python3}"

need_root() {
    if [ "$(id -u)" -eq 0 ]; then "$@"; else sudo "$@"; fi
}

ensure_python() {
    if ! command -v "$PY" >/dev/null || ! "$PY" -c 'import venv, ensurepip' 2>/dev/null; then
        echo "setup: installing python3 and python3-venv (Debian packages)"
        need_root apt-get update -qq
        need_root apt-get install -y -qq python3 python3-venv python3-pip
        PY=python3
    fi
}

# $1: pip extras spec, e.g. "" or "[test]"
ensure_venv() {
    local extras="$1"
    ensure_python
    [ -x "$VENV/bin/python" ] || "$PY" -m venv "$VENV"
    local stamp="$VENV/.installed$extras"
    local want
    want="$(cat pyproject.toml "$CONSTRAINTS" | sha256sum | cut -d' ' -f1)"
    # The test install is a superset of the app's: either stamp will do for the app.
    if [ -z "$extras" ] && [ "$(cat "$VENV/.installed[test]" 2>/dev/null)" = "$want" ]; then
        return
    fi
    if [ ! -f "$stamp" ] || [ "$(cat "$stamp")" != "$want" ]; then
        echo "setup: installing Python packages into .venv (once per change of pyproject.toml" \
             "or .ci/constraints.txt; about a minute, quietly)"
        # The package is installed editable, and setuptools then warns in a framed box that a
        # folder named like one of its packages would shadow it: a first-time user took the box
        # for a failure.  Python's UserWarnings of the install are not shown; errors still are.
        export PYTHONWARNINGS=ignore::UserWarning
        "$VENV/bin/python" -m pip install -q --upgrade pip
        if ! "$VENV/bin/python" -m pip install -q -c "$CONSTRAINTS" -e ".$extras"; then
            echo "setup: the tested versions in .ci/constraints.txt do not install with this Python" \
                 "($("$VENV/bin/python" --version 2>&1)); installing the newest versions that" \
                 "pyproject.toml allows instead" >&2
            "$VENV/bin/python" -m pip install -q -e ".$extras"
        fi
        unset PYTHONWARNINGS
        echo "$want" > "$stamp"
    fi
}

# Debian packages that Qt's xcb plugin and VTK's OpenGL need, and that a desktop install may
# lack (libxcb-cursor0 most often): both README commands install them.
DEBIAN_GUI_PACKAGES=(
    libgl1 libegl1 libglx-mesa0 libgl1-mesa-dri libdbus-1-3 libfontconfig1
    libxkbcommon0 libxkbcommon-x11-0 libxcb1 libxcb-cursor0 libxcb-icccm4 libxcb-image0
    libxcb-keysyms1 libxcb-randr0 libxcb-render-util0 libxcb-shape0 libxcb-xfixes0
    libxcb-xinerama0 libxcb-xkb1 libxrender1 libxext6 libxi6 fonts-dejavu-core
)
# The tests' X server, besides.
DEBIAN_TEST_PACKAGES=(xvfb xauth)

# $@: Debian package names; installs those not installed yet.
ensure_debian() {
    local missing=()
    for p in "$@"; do
        dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "ok installed" || missing+=("$p")
    done
    if [ ${#missing[@]} -gt 0 ]; then
        echo "setup: installing Debian packages: ${missing[*]}"
        need_root apt-get update -qq
        DEBIAN_FRONTEND=noninteractive need_root apt-get install -y -qq --no-install-recommends "${missing[@]}"
    fi
}
