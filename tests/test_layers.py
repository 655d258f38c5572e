"""Dependencies point one way: app -> views -> core, and core never loads Qt or VTK."""

import pkgutil
import shutil
import subprocess
import sys
from pathlib import Path

import core

ROOT = Path(__file__).resolve().parents[1]
GUI_PACKAGES = ("PySide6", "pyvista", "pyvistaqt", "vtk", "vtkmodules")


def test_importing_every_core_module_loads_no_qt_or_vtk():
    modules = [m.name for m in pkgutil.walk_packages(core.__path__, "core.")]
    assert "core.camera" in modules and "core.image_order.kernels.render" in modules
    code = (
        "import importlib, sys\n"
        f"for name in {modules!r}: importlib.import_module(name)\n"
        f"print(sorted(m for m in sys.modules if m.split('.')[0] in {GUI_PACKAGES!r}))\n"
    )
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True,
                         check=True)
    assert out.stdout.strip() == "[]"


def test_import_linter_contracts_hold():
    lint = shutil.which("lint-imports", path=str(Path(sys.executable).parent))
    assert lint, "import-linter is a test dependency: install with pip install -e .[test]"
    out = subprocess.run([lint], cwd=ROOT, capture_output=True, text=True)
    assert out.returncode == 0, out.stdout + out.stderr
    assert "3 kept, 0 broken" in out.stdout
