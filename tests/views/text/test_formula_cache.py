"""Typeset formulas kept on disk: a later process shows them without typesetting them again."""

import os
import subprocess
import sys

import numpy as np
import pytest
from checkout import ROOT, TYPESETTING

from views.text import formula_cache
from views.text.math_view import MathView, render_mathtext

FORMULA = r"$a t^2 + b t + c = 0$"
SHOW = TYPESETTING + f"""
import sys
from PySide6.QtWidgets import QApplication
app = QApplication(sys.argv[:1])
from views.text.math_view import MathView
view = MathView({FORMULA!r}, size_pt=12.0)
print(view.sizeHint().width(), view.sizeHint().height(), typesetting())
"""


@pytest.fixture
def cache_home(monkeypatch, tmp_path):
    from views.text import math_view

    math_view._typesetter().waitForDone()  # what earlier tests' views asked for is kept in their folder
    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    return tmp_path


def _show_in_new_process(cache_home):
    out = subprocess.run([sys.executable, "-c", SHOW], cwd=ROOT, capture_output=True, text=True, timeout=300,
                         env={**os.environ, "XDG_CACHE_HOME": str(cache_home)})
    assert out.returncode == 0, out.stderr
    width, height, loaded = out.stdout.split()
    return (int(width), int(height)), loaded == "True"


@pytest.mark.gui
def test_a_formula_typeset_once_is_shown_by_the_next_process_without_typesetting(tmp_path):
    # The processes' own cache folder: formulas this test process still typesets in the background
    # (for views of earlier tests) are kept where its own XDG_CACHE_HOME points, not here.
    home = tmp_path / "processes"
    first_size, first_loaded = _show_in_new_process(home)
    assert first_loaded  # nothing kept yet: typeset
    assert len(list((home / "render-explorer" / "formulas").glob("*.npy"))) == 1
    second_size, second_loaded = _show_in_new_process(home)
    assert not second_loaded
    assert second_size == first_size and first_size[0] > first_size[1] > 0


def test_a_damaged_kept_formula_is_typeset_again_and_replaced(qtbot, cache_home):
    args = (r"$\sqrt{b^2 - 4 a c}$", 13.0, "#112233", 96.0)
    reference = render_mathtext(*args).copy()  # typeset, not kept
    formula_cache.store(*args, np.zeros((2, 2, 4), np.uint8))
    (kept_path,) = formula_cache.folder().glob("*.npy")
    kept_path.write_bytes(b"not an array")
    assert formula_cache.load(*args) is None
    assert render_mathtext(*args, keep=True) == reference
    kept = formula_cache.load(*args)
    assert kept is not None and (kept.shape[1], kept.shape[0]) == (reference.width(), reference.height())


def test_a_cache_that_cannot_be_written_only_costs_the_typesetting(qtbot, monkeypatch, tmp_path):
    blocker = tmp_path / "a file, not a folder"
    blocker.write_text("")
    monkeypatch.setenv("XDG_CACHE_HOME", str(blocker))
    view = MathView(r"$x_{\mathrm{cache}} = 1$", size_pt=12.0)
    qtbot.addWidget(view)
    assert view.error is None and view.pixmap().width() > 0
    assert blocker.read_text() == ""


def test_the_folder_never_grows_past_its_limit_and_keeps_what_was_shown_last(cache_home):
    kib = np.zeros((16, 16, 4), np.uint8)  # 1 KiB of pixels, 1152 bytes as a file
    formulas = [(f"$x_{{{i}}}$", 12.0, "#000000", 72.0) for i in range(40)]
    for i, args in enumerate(formulas):
        formula_cache.store(*args, kib)
        os.utime(formula_cache._path(*args), ns=(i * 10**9, i * 10**9))  # stored one second apart
    assert formula_cache.load(*formulas[0]) is not None  # the oldest, shown again: used now
    folder = formula_cache.folder()
    size = (folder / next(os.scandir(folder)).name).stat().st_size
    formula_cache.trim(folder, most=20 * size)
    kept = {p.name for p in folder.glob("*.npy")}
    assert len(kept) == 15  # trimmed to three quarters of the limit
    assert formula_cache._path(*formulas[0]).name in kept  # shown last
    assert {formula_cache._path(*args).name for args in formulas[-14:]} <= kept  # the newest stores


def test_a_folder_under_its_limit_is_left_alone(cache_home):
    for i in range(5):
        formula_cache.store(f"$y_{i}$", 12.0, "#000000", 72.0, np.zeros((4, 4, 4), np.uint8))
    formula_cache.trim(formula_cache.folder())
    assert len(list(formula_cache.folder().glob("*.npy"))) == 5
