"""Dependencies point one way: app -> views -> core, with no circles; core never loads Qt or VTK,
and its tests need neither Qt nor pyvista."""

import ast
import os
import pkgutil
import shutil
import subprocess
import sys
from pathlib import Path

from checkout import ROOT

import core

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


def _circles(edges: dict[str, set[str]]) -> list[list[str]]:
    """The strongly connected components of more than one module (Tarjan's algorithm, iterative)."""
    index: dict[str, int] = {}
    low: dict[str, int] = {}
    stack: list[str] = []
    on_stack: set[str] = set()
    circles = []
    for root in sorted(edges):
        if root in index:
            continue
        work = [(root, iter(sorted(edges[root])))]
        index[root] = low[root] = len(index)
        stack.append(root)
        on_stack.add(root)
        while work:
            node, targets = work[-1]
            for target in targets:
                if target not in index:
                    index[target] = low[target] = len(index)
                    stack.append(target)
                    on_stack.add(target)
                    work.append((target, iter(sorted(edges[target]))))
                    break
                if target in on_stack:
                    low[node] = min(low[node], index[target])
            else:
                work.pop()
                if work:
                    low[work[-1][0]] = min(low[work[-1][0]], low[node])
                if low[node] == index[node]:
                    component = []
                    while True:
                        member = stack.pop()
                        on_stack.discard(member)
                        component.append(member)
                        if member == node:
                            break
                    if len(component) > 1:
                        circles.append(sorted(component))
    return circles


def test_the_circle_finder_finds_a_circle():
    assert _circles({"a": {"b"}, "b": {"c"}, "c": {"a"}, "d": {"a"}}) == [["a", "b", "c"]]
    assert _circles({"a": {"b"}, "b": set()}) == []


def test_no_module_imports_itself_through_others():
    """Dependencies run one way, from the array drivers to the kernels to the formulas: no module
    reaches itself through the modules it imports (a package's ``__init__`` counts as a module)."""
    import grimp

    graph = grimp.build_graph("app", "core", "views", cache_dir=None)
    edges = {m: set(graph.find_modules_directly_imported_by(m)) & graph.modules for m in graph.modules}
    assert len(edges) > 200 and "core.object_order.clipping" in edges["core.object_order.pipeline"]
    assert _circles(edges) == []


#: Refuses the GUI packages as if they were not installed.
_WITHOUT_GUI = f"""
import importlib.abc, sys
class _NotInstalled(importlib.abc.MetaPathFinder):
    def find_spec(self, name, path=None, target=None):
        if name.split(".")[0] in {GUI_PACKAGES!r}:
            raise ModuleNotFoundError(f"No module named {{name!r}}", name=name)
        return None
sys.meta_path.insert(0, _NotInstalled())
"""

TESTS = ROOT / "tests"


def _imported(path: Path) -> set[str]:
    """The top-level names a file imports anywhere in it, inside functions too (absolute imports)."""
    tree = ast.parse(path.read_text(encoding="utf-8"), str(path))
    names = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            names |= {alias.name.split(".")[0] for alias in node.names}
        elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
            names.add(node.module.split(".")[0])
    return names


def _gui_imports_of_core_tests() -> dict[str, set[str]]:
    """Each file the core tests run (their modules, conftests, and the helper modules of tests/ they
    import, followed through) that imports a GUI package, with those packages."""
    files = sorted((TESTS / "core").rglob("*.py"))
    seen, found = set(files), {}
    while files:
        path = files.pop()
        names = _imported(path)
        if names & set(GUI_PACKAGES):
            found[str(path.relative_to(ROOT))] = names & set(GUI_PACKAGES)
        helpers = {TESTS / f"{name}.py" for name in names} - seen
        helpers = {h for h in helpers if h.is_file()}
        seen |= helpers
        files += sorted(helpers)
    return found


def test_the_import_scan_sees_an_import_inside_a_function(tmp_path):
    source = tmp_path / "example.py"
    source.write_text("import numpy\ndef f():\n    from PySide6.QtCore import Qt\n    import vtk.util\n")
    assert _imported(source) == {"numpy", "PySide6", "vtk"}


def test_the_core_tests_run_where_qt_and_pyvista_are_not_installed(tmp_path):
    """``pytest tests/core`` needs neither Qt nor pyvista nor VTK: no file it runs imports them, even
    inside a function (core itself is held to that by the import contract above), and collecting it
    with those packages refused at import (a ``sitecustomize`` that raises ``ModuleNotFoundError`` for
    them, as where they are not installed) imports every test module and conftest without an error."""
    assert _gui_imports_of_core_tests() == {}
    (tmp_path / "sitecustomize.py").write_text(_WITHOUT_GUI)
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(tmp_path), str(ROOT)])}
    check = subprocess.run([sys.executable, "-c", "import PySide6"], env=env, capture_output=True,
                           text=True)
    assert "No module named 'PySide6'" in check.stderr
    command = [sys.executable, "-m", "pytest", "-q", "--collect-only", "-p", "no:pytest-qt",
               "-p", "no:cacheprovider", "-p", "no:xdist", "tests/core"]
    ran = subprocess.run(command, cwd=ROOT, env=env, capture_output=True, text=True, timeout=600)
    assert ran.returncode == 0, ran.stdout[-3000:] + ran.stderr[-3000:]
    summary = ran.stdout.strip().splitlines()[-1]
    assert int(summary.split(" tests collected")[0].split()[-1]) > 1000 and "error" not in summary
